/// pcl_sparse_decode: reads a .psm model file and resamples it into a point cloud with normals and
/// curvature (docs/METHOD.md step 12); optionally reconstructs the input vertices of a mesh.
///
///   pcl_sparse_decode MODEL.psm OUT.{pcd,ply} [-n N | -density D] [-box XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX]
///                     [-seed S] [-max-slope DEG] [-clearance C] [-threads T] [-recon MESH RECON.{ply,obj,off,stl}]
///                     [-stream auto|on|off] [-block N] [--json] [-q]
///
/// -box decodes a region: of a tiled model (pcl_sparse_encode -tiles) only the tiles whose patches reach
/// into the box are read, and the points are exactly those the whole model gives inside the box.
/// Under `mpirun -n K` a tiled model at a -density is decoded tile by tile over the K processes (each reads
/// its tiles and the neighbours reaching them, keeps its own patches' points, rank 0 writes them in tile
/// order): the same file as without mpirun. Otherwise rank 0 decodes alone.

#include "tool_processes.h"
#include "tool_resampling.h"
#include "tool_support.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/common/upper_median.h>
#include <pcl_sparse/format/attribute_sections.h>
#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// -recon takes the faces of \a mesh and the model's positions of its vertices: a mesh with the same vertex
  /// count but not the one encoded (another mesh, or its vertices in another order) gave a tangle without a
  /// word. The model puts the encoded mesh's vertices within its coding error of where they were (about
  /// 1e-4 of the diagonal; quantised files 1e-3), so half of them more than 5 % of the diagonal away is
  /// another mesh.
  void
  checkReconstructionMesh (const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& reconstructed, double diagonal,
                           const std::string& path)
  {
    std::vector<double> distances;
    distances.reserve (reconstructed.size ());
    for (std::size_t v = 0; v < reconstructed.size (); ++v)
      if (reconstructed[v].allFinite ())
        distances.push_back ((reconstructed[v] - mesh.vertices[v]).norm ());
    if (distances.empty () || !(diagonal > 0.0))
      return;
    const double median = upperMedian (distances);
    if (!(median <= 0.05 * diagonal))
      throw Error (tools::format ("option -recon: '%s' is not the mesh the model was encoded from: half its vertices lie "
                                  "%.3g %% of the diagonal or more from where the model puts them (the model's own error "
                                  "is about 0.01 %%); the same vertex count, but another mesh or another vertex order",
                                  path.c_str (), 100.0 * median / diagonal));
  }

  const tools::ToolDescription kTool = {
    "pcl_sparse_decode", "MODEL.psm OUT.{pcd,ply} [options]",
    {
      {"MODEL.psm", "a model file written by pcl_sparse_encode -o"},
      {"OUT", "the resampled cloud: x y z, normal, curvature (.pcd or .ply), and rgb where the model"},
      {"", "codes colour (intensity where it codes intensity)"},
      {"-n N", "exactly N points (default: the model's number of input vertices)"},
      {"-density D", "D points per unit area instead of -n"},
      {"-box X0,Y0,Z0,X1,Y1,Z1", "only the points inside this box (needs -density); of a tiled model only the"},
      {"", "tiles reaching into it are read"},
      {"-seed S", "seed of the sampling (default 42)"},
      tools::maxSlopeHelpLine (),
      tools::clearanceHelpLine (),
      {"-threads T", "OpenMP threads (default: all; the output does not depend on it)"},
      {"-recon MESH RECON", "reconstruct MESH's vertices from the model (needs a model written with"},
      {"", "--store-vertices) and write MESH with them to RECON"},
      {"-stream M", "auto (default) or on: write the cloud block by block as it is made, memory set"},
      {"", "by -block, not N; off: make the whole cloud first (the same bytes either way); a"},
      {"", "-box region is written whole"},
      {"-block N", "streamed: N points per block, 4096 to 67108864 (default 2097152; memory about 200 x N bytes)"},
      tools::noAttributesHelpLine (),
      {"--json", "print one JSON object on stdout"},
      {"-q", "quiet"},
    },
    2, {"-n", "-density", "-seed", "-max-slope", "-clearance", "-threads", "-box", {"-recon", 2}, "-stream", "-block"},
    {"--json", "-q", "-no-attributes"}};

  /// The points of a tiled model at a density, decoded over the processes of \a group: each rank takes a
  /// run of tiles (about the same number of patches each), reads them and every tile whose patches reach into them (ownership
  /// at their borders), resamples with the whole model's patch numbers and keeps its own tiles' points;
  /// rank 0 concatenates them in tile order, which is the order of the full decode, and gets them in
  /// \a local (the other ranks get nothing). Returns the bytes this rank read.
  template <typename PointT>
  std::uint64_t
  decodeAcross (const tools::ProcessGroup& group, const TiledModelIndex& index, const std::string& path,
                SparseSurfaceResampling<PointT>& resampling, tools::LocalCloud<PointT>& local, std::size_t& patches)
  {
    // Contiguous runs of tiles of about equal patch counts, so a rank's neighbours are few.
    std::vector<std::size_t> mine;
    const double share = static_cast<double> (index.total_patches) / group.size ();
    for (std::size_t i = 0; i < index.entries.size (); ++i)
    {
      const double middle = index.entries[i].first_patch + 0.5 * index.entries[i].num_patches;
      // A file of tiles without patches (version 2 allows them) has share 0: all to rank 0, not NaN to int.
      const int rank = share > 0.0 ? std::min (static_cast<int> (middle / share), group.size () - 1) : 0;
      if (rank == group.rank ())
        mine.push_back (i);
    }
    std::vector<Eigen::AlignedBox3d> boxes;
    for (std::size_t i : mine)
      boxes.push_back (index.entries[i].reach);
    std::uint64_t bytes_read = 0;
    std::vector<std::uint8_t> message;
    const Eigen::Vector3d far = index.grid.origin + index.grid.edge * index.grid.counts.cast<double> ();
    const Eigen::Vector3d origin = localFrameOrigin ({index.grid.origin, far});
    if (!mine.empty ())
    {
      TiledModel tiled = loadTiledModelRegions (path, boxes, &bytes_read);
      const std::vector<std::size_t> numbers = tiled.patchNumbers ();
      resampling.setPatchNumbers (numbers);
      const tools::LocalCloud<PointT> part =
        tools::resampleInLocalFrame (resampling, std::make_shared<const SparseSurfaceModel> (std::move (tiled.model)), origin);
      const std::vector<int>& from = resampling.getPointPatches ();
      // Points come in patch order: each own tile's points are one run. Message: per tile, its entry, count, points.
      std::size_t p = 0;
      for (std::size_t i : mine)
      {
        const TileIndexEntry& e = index.entries[i];
        while (p < from.size () && numbers[from[p]] < e.first_patch)
          ++p;
        const std::size_t first = p;
        while (p < from.size () && numbers[from[p]] < e.first_patch + e.num_patches)
          ++p;
        const std::uint64_t header[2] = {i, p - first};
        const auto* h = reinterpret_cast<const std::uint8_t*> (header);
        message.insert (message.end (), h, h + sizeof header);
        const auto* points = reinterpret_cast<const std::uint8_t*> (part.cloud.points.data () + first);
        message.insert (message.end (), points, points + (p - first) * sizeof (PointT));
      }
    }
    const std::vector<std::vector<std::uint8_t>> all = group.gather (message);
    if (group.rank () != 0)
      return bytes_read;
    std::vector<std::pair<const std::uint8_t*, std::uint64_t>> runs (index.entries.size (), {nullptr, 0});
    std::size_t total = 0;
    for (const std::vector<std::uint8_t>& m : all)
      for (std::size_t at = 0; at + 16 <= m.size ();)
      {
        std::uint64_t header[2];
        std::memcpy (header, m.data () + at, sizeof header);
        at += sizeof header;
        runs.at (header[0]) = {m.data () + at, header[1]};
        at += header[1] * sizeof (PointT);
        total += header[1];
      }
    local.origin = origin;
    local.cloud.resize (total);
    std::size_t at = 0;
    for (const auto& run : runs)
      if (run.second > 0)
      {
        std::memcpy (static_cast<void*> (local.cloud.points.data () + at), run.first, run.second * sizeof (PointT));
        at += run.second;
      }
    patches = index.total_patches;
    return bytes_read;
  }

  /// What the command line asks of the resampling and the output.
  struct DecodeRequest
  {
    SparseSurfaceResamplingOptions options;
    bool has_density = false, has_n = false;
    double density = 0.0;
    std::size_t n = 0;
    int threads = 0;
    bool quiet = false;   ///< no progress
    bool stream = true;   ///< tools::chooseStreaming
    bool has_box = false;
    Eigen::AlignedBox3d box;
    std::string path;     ///< the output cloud
  };

  /// What decodeAndWrite did.
  struct Decoded
  {
    std::size_t points = 0;
    double resample_seconds = 0.0, write_seconds = 0.0, area = 0.0;
    bool streamed = false;
    std::string attributes;  ///< "none", "rgb" or "intensity": the field written after x y z
  };

  /// The attribute channels of a tiled model, from its index (version 3 files share them; none for version 2).
  std::vector<AttributeChannelInfo>
  tiledChannels (const TiledModelIndex& index)
  {
    if (index.shared.channels.empty ())
      return {};
    ByteReader channels (index.shared.channels.data (), index.shared.channels.size (), "section ACHN");
    return decodeAttributeChannels (channels, (index.shared.flags & 1) != 0);
  }

  /// Decodes a tiled model over the processes of \a group into PointT (decodeAcross) and writes the cloud
  /// on rank 0. Returns the tool's exit code.
  template <typename PointT>
  int
  decodeAcrossAndWrite (const tools::ProcessGroup& group, const TiledModelIndex& index, const std::string& model_path,
                        const std::string& out_path, const DecodeRequest& request, bool json, bool quiet)
  {
    pcl::console::TicToc timer;
    timer.tic ();
    SparseSurfaceResampling<PointT> resampling;
    resampling.setOptions (request.options);
    resampling.setDensity (request.density);
    resampling.setNumberOfThreads (request.threads);
    tools::LocalCloud<PointT> local;
    std::size_t patches = 0;
    std::uint64_t bytes_read = 0;
    try
    {
      bytes_read = decodeAcross (group, index, model_path, resampling, local, patches);
    }
    catch (const Error& e)
    {
      // The library's advice, to resample in blocks, is for one process: the ranks' clouds are gathered whole.
      throw Error (std::string (e.what ()) + " (under mpirun every rank holds its clouds whole: run one process to stream)");
    }
    if (group.rank () != 0)
      return 0;
    const double resample_seconds = timer.toc () / 1000.0;
    timer.tic ();
    tools::saveLocalCloud (out_path, local, true);
    const double write_seconds = timer.toc () / 1000.0;
    if (json)
      tools::JsonObject ()
        .add ("model", model_path)
        .add ("patches", patches)
        .add ("points", local.cloud.size ())
        .add ("tiled", true)
        .add ("ranks", group.size ())
        .add ("attributes", tools::extraFieldName (cloudExtraFieldOf<PointT> ()))
        .add ("bytes_read_rank0", bytes_read)
        .add ("seconds", tools::JsonObject ().addSeconds ("resample", resample_seconds).addSeconds ("write", write_seconds))
        .print ();
    else if (!quiet)
      std::printf ("%zu patches -> %zu points over %d processes; seconds: resample %.3f, write %.3f\n", patches,
                   local.cloud.size (), group.size (), resample_seconds, write_seconds);
    return 0;
  }

  /// Resamples \a model into PointT as \a request asks and writes the cloud, streamed or whole (only the
  /// points inside -box); \a origin: the local frame of a tiled model (else the model's own).
  template <typename PointT>
  Decoded
  decodeAndWrite (const tools::CommandLine& args, const DecodeRequest& request, const SparseSurfaceModel::ConstPtr& model,
                  const std::vector<std::size_t>& patch_numbers, const Eigen::Vector3d* origin)
  {
    pcl::console::TicToc timer;
    timer.tic ();
    SparseSurfaceResampling<PointT> resampling;
    resampling.setOptions (request.options);
    if (request.has_density)
      resampling.setDensity (request.density);
    else
      resampling.setPointCount (request.has_n ? request.n : std::max<std::size_t> (model->num_input_vertices, 1));
    resampling.setNumberOfThreads (request.threads);
    resampling.setProgressCallback (makeConsoleProgress (request.quiet));
    resampling.setPatchNumbers (patch_numbers);
    tools::setStreamBlock (args, resampling);
    Decoded decoded;
    decoded.attributes = tools::extraFieldName (cloudExtraFieldOf<PointT> ());
    decoded.streamed = request.stream && !request.has_box && !model->patches.empty ();
    if (decoded.streamed)
    {
      const tools::StreamedCloud result = tools::streamResampledCloud (resampling, model, request.path, true, origin);
      decoded.points = result.points;
      decoded.resample_seconds = result.resample_seconds;
      decoded.write_seconds = result.save_seconds;
    }
    else
    {
      tools::LocalCloud<PointT> local;
      if (!model->patches.empty () || !request.has_box)
        local = origin ? tools::resampleInLocalFrame (resampling, model, *origin) : tools::resampleInLocalFrame (resampling, model);
      if (request.has_box)
      {
        // Exactly the points inside the box (closed), as the whole model places them.
        std::size_t kept = 0;
        for (const PointT& p : local.cloud)
          if (request.box.contains (local.origin + p.getVector3fMap ().template cast<double> ()))
            local.cloud[kept++] = p;
        local.cloud.resize (kept);
        if (kept == 0)  // an empty cloud is the right answer, but a box off the model by mistake said nothing
          tools::printNote (tools::format ("%s: no point of the model lies in the box of -box (the cloud written is empty)",
                                           request.path.c_str ()));
      }
      decoded.points = local.cloud.size ();
      decoded.resample_seconds = timer.toc () / 1000.0;
      timer.tic ();
      tools::saveLocalCloud (request.path, local, true);
      decoded.write_seconds = timer.toc () / 1000.0;
    }
    decoded.area = resampling.getEstimatedArea ();
    return decoded;
  }

  /// Option -box: six numbers, min corner then max corner.
  Eigen::AlignedBox3d
  parseBox (const tools::CommandLine& args)
  {
    const std::string expected = "XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (six finite numbers, min <= max)";
    std::vector<double> v;
    args.numbers ("-box", 6, expected, v);
    if (v[0] > v[3] || v[1] > v[4] || v[2] > v[5])
      throw Error ("option -box: expected " + expected + ", got '" + args.value ("-box") + "'");
    return Eigen::AlignedBox3d (Eigen::Vector3d (v[0], v[1], v[2]), Eigen::Vector3d (v[3], v[4], v[5]));
  }
} // namespace

int
main (int argc, char** argv)
{
  const tools::ProcessGroup group (argc, argv);
  return group.finish (tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    const bool json = args.has ("--json");
    const bool quiet = args.has ("-q");
    if (quiet || json)
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);  // notes off, as in the other tools
    args.expectPositional (2, "MODEL.psm and OUT.{pcd,ply}");
    const std::string& model_path = args.positional ()[0];
    const std::string& out_path = args.positional ()[1];
    const std::vector<std::string> recon_args = args.values ("-recon");
    const std::string recon_mesh = recon_args.empty () ? std::string () : recon_args[0];
    const std::string recon_out = recon_args.empty () ? std::string () : recon_args[1];
    if (!tools::hasExtension (out_path, ".pcd") && !tools::hasExtension (out_path, ".ply"))
      throw Error ("output '" + out_path + "' must end in .pcd or .ply");
    if (!recon_out.empty () && !isMeshFileExtension (recon_out))
      throw Error ("option -recon: '" + recon_out + "' has no mesh extension (.obj .off .ply .stl)");
    tools::checkOutputPaths ({model_path, recon_mesh}, {out_path, recon_out});
    std::size_t n = 0;
    double density = 0.0;
    const bool has_n = args.integer ("-n", n, tools::Range::closed (1, SparseSurfaceResampling<pcl::PointNormal>::max_points));
    const bool has_density = args.number ("-density", density, tools::Range::above (0.0));
    if (has_n && has_density)
      throw Error ("options -n and -density exclude each other");
    SparseSurfaceResamplingOptions resampling_options;
    args.integer ("-seed", resampling_options.seed, tools::Range::atLeast (0));
    tools::readOwnershipOptions (args, resampling_options);
    int threads = 0;
    args.integer ("-threads", threads, tools::Range::closed (0, 1024));
    const bool stream = tools::chooseStreaming (args, out_path, true, false);

    const bool has_box = args.has ("-box");
    const Eigen::AlignedBox3d box = has_box ? parseBox (args) : Eigen::AlignedBox3d ();
    if (has_box && !has_density)
      throw Error ("option -box needs -density D (points per unit area: -n counts the whole model's points)");
    if (has_box && args.value ("-stream") == "on")  // it quietly did not stream
      throw Error ("option -stream on: -box keeps the points inside the box, written whole (use -stream auto)");
    if (has_box && args.has ("-block"))
      throw Error ("option -block sets the blocks of a streamed cloud; -box keeps the points inside the box, written whole");
    if (has_box && !recon_mesh.empty ())
      throw Error ("options -box and -recon exclude each other");

    const bool attributes = !args.has ("-no-attributes");
    DecodeRequest request;
    request.options = resampling_options;
    request.has_density = has_density;
    request.density = density;
    request.has_n = has_n;
    request.n = n;
    request.threads = threads;
    request.quiet = quiet || json;
    request.stream = stream;
    request.has_box = has_box;
    request.box = box;
    request.path = out_path;

    const bool is_tiled = isTiledModelFile (model_path);
    const bool across = group.size () > 1 && is_tiled && has_density && !has_box && recon_mesh.empty ();
    if (group.size () > 1 && !across && group.rank () != 0)
      return 0;  // rank 0 decodes alone
    if (across)
    {
      // The ranks' clouds are gathered whole on rank 0: neither option would do anything.
      if (args.value ("-stream") == "on" || args.has ("-block"))
        throw Error (std::string ("option ") + (args.has ("-block") ? "-block" : "-stream on") +
                     ": under mpirun the tiles' clouds are gathered whole on rank 0 (run one process to stream)");
      // The fields from the index, which every rank reads, so that all gather the same point type.
      const TiledModelIndex index = readTiledModelIndex (model_path);
      return tools::withPointTypeOf (tools::resampledExtraField (tiledChannels (index), attributes), [&] (auto* type) {
        using PointT = std::remove_pointer_t<decltype (type)>;
        return decodeAcrossAndWrite<PointT> (group, index, model_path, out_path, request, json, quiet);
      });
    }

    pcl::console::TicToc timer;
    timer.tic ();
    // A tiled model: the tiles reaching into the box (or all), their patch numbers and the grid's frame,
    // so a region resamples exactly as the whole model does there.
    std::uint64_t bytes_read = 0;
    std::vector<std::size_t> patch_numbers;
    Eigen::Vector3d frame_origin = Eigen::Vector3d::Zero ();
    SparseSurfaceModel::ConstPtr model;
    if (is_tiled)
    {
      const Eigen::Vector3d inf = Eigen::Vector3d::Constant (std::numeric_limits<double>::infinity ());
      TiledModel tiled = loadTiledModelRegion (model_path, has_box ? box : Eigen::AlignedBox3d (-inf, inf), &bytes_read);
      patch_numbers = tiled.patchNumbers ();
      const Eigen::Vector3d far = tiled.grid.origin + tiled.grid.edge * tiled.grid.counts.cast<double> ();
      frame_origin = localFrameOrigin ({tiled.grid.origin, far});
      model = std::make_shared<const SparseSurfaceModel> (std::move (tiled.model));
    }
    else
    {
      model = std::make_shared<const SparseSurfaceModel> (loadModel (model_path));
      bytes_read = static_cast<std::uint64_t> (inspectModelFile (model_path).file_bytes);
    }
    const double load_seconds = timer.toc () / 1000.0;

    // Check -recon before writing anything, so that a bad request leaves no output behind.
    TriangleMesh recon;
    std::vector<Eigen::Vector3d> reconstructed;
    if (!recon_mesh.empty ())
    {
      recon = loadTriangleMesh (recon_mesh);
      if (recon.vertices.size () != model->num_input_vertices)
        throw Error ("option -recon: '" + recon_mesh + "' has " + std::to_string (recon.vertices.size ()) +
                     " vertices, the model was encoded from " + std::to_string (model->num_input_vertices));
      bool any = false;
      for (const PatchCode& patch : model->patches)
        any = any || !patch.vertices.empty ();
      if (!any && !model->patches.empty ())
        throw Error ("option -recon: '" + model_path + "' stores no patch vertices (encode with --store-vertices)");
      reconstructed = model->reconstructVertices (recon.vertices.size ());
      checkReconstructionMesh (recon, reconstructed, model->bbox_diagonal, recon_mesh);
    }

    const Decoded decoded =
      tools::withPointTypeOf (tools::resampledExtraField (model->attribute_channels, attributes), [&] (auto* type) {
        return decodeAndWrite<std::remove_pointer_t<decltype (type)>> (args, request, model, patch_numbers,
                                                                      is_tiled ? &frame_origin : nullptr);
      });
    const std::size_t points = decoded.points;
    const double resample_seconds = decoded.resample_seconds;
    double write_seconds = decoded.write_seconds;
    timer.tic ();
    if (!recon_mesh.empty ())
    {
      for (std::size_t v = 0; v < reconstructed.size (); ++v)
        if (reconstructed[v].allFinite ())
          recon.vertices[v] = reconstructed[v];
      saveTriangleMesh (recon_out, recon);
      tools::removeIfRunFails (recon_out);
    }
    write_seconds += timer.toc () / 1000.0;

    if (json)
      tools::JsonObject ()
        .add ("model", model_path)
        .add ("patches", model->numPatches ())
        .add ("nnz", model->numNonZeros ())
        .add ("points", points)
        .add ("streamed", decoded.streamed)
        .add ("attributes", decoded.attributes)
        .add ("area", decoded.area)
        .add ("tiled", is_tiled)
        .add ("bytes_read", bytes_read)
        .add ("seconds", tools::JsonObject ()
                           .addSeconds ("load", load_seconds)
                           .addSeconds ("resample", resample_seconds)
                           .addSeconds ("write", write_seconds))
        .print ();
    else if (!quiet)
      std::printf ("%zu patches, %zu atoms -> %zu points; seconds: load %.3f, resample %.3f, write %.3f\n",
                   model->numPatches (), model->numNonZeros (), points, load_seconds, resample_seconds,
                   write_seconds);
    return 0;
  }));
}
