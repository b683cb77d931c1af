/// pcl_sparse_decode: reads a .psm model file and resamples it into a point cloud with normals and
/// curvature (docs/METHOD.md step 12); optionally reconstructs the input vertices of a mesh.
///
///   pcl_sparse_decode MODEL.psm OUT.{pcd,ply} [-n N | -density D] [-seed S] [-threads T]
///                     [-recon MESH RECON.{ply,obj,off,stl}] [-stream auto|on|off] [-block N] [--json] [-q]

#include "tool_resampling.h"
#include "tool_support.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const tools::ToolDescription kTool = {
    "pcl_sparse_decode", "MODEL.psm OUT.{pcd,ply} [options]",
    {
      {"MODEL.psm", "a model file written by pcl_sparse_encode -o"},
      {"OUT", "the resampled cloud: x y z, normal, curvature (.pcd or .ply)"},
      {"-n N", "exactly N points (default: the model's number of input vertices)"},
      {"-density D", "D points per unit area instead of -n"},
      {"-seed S", "seed of the sampling (default 42)"},
      {"-threads T", "OpenMP threads (default: all; the output does not depend on it)"},
      {"-recon MESH RECON", "reconstruct MESH's vertices from the model (needs a model written with"},
      {"", "--store-vertices) and write MESH with them to RECON"},
      {"-stream M", "auto (default) or on: write the cloud block by block as it is made, memory set"},
      {"", "by -block, not N; off: make the whole cloud first (the same bytes either way)"},
      {"-block N", "streamed: N points per block (default 2097152; memory about 200 x N bytes)"},
      {"--json", "print one JSON object on stdout"},
      {"-q", "quiet"},
    },
    2, {"-n", "-density", "-seed", "-threads", {"-recon", 2}, "-stream", "-block"}, {"--json", "-q"}};
} // namespace

int
main (int argc, char** argv)
{
  return tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    const bool json = args.has ("--json");
    const bool quiet = args.has ("-q");
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
    std::size_t n = 0;
    double density = 0.0;
    const bool has_n = args.integer ("-n", n, tools::Range::closed (1, SparseSurfaceResampling<pcl::PointNormal>::max_points));
    const bool has_density = args.number ("-density", density, tools::Range::above (0.0));
    if (has_n && has_density)
      throw Error ("options -n and -density exclude each other");
    std::uint64_t seed = 42;
    args.integer ("-seed", seed, tools::Range::atLeast (0));
    int threads = 0;
    args.integer ("-threads", threads, tools::Range::atLeast (0));
    const bool stream = tools::chooseStreaming (args, out_path, true, false);

    pcl::console::TicToc timer;
    timer.tic ();
    const auto model = std::make_shared<const SparseSurfaceModel> (loadModel (model_path));
    const double load_seconds = timer.toc () / 1000.0;

    // Check -recon before writing anything, so that a bad request leaves no output behind.
    TriangleMesh recon;
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
    }

    timer.tic ();
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    SparseSurfaceResamplingOptions options;
    options.seed = seed;
    resampling.setOptions (options);
    if (has_density)
      resampling.setDensity (density);
    else
      resampling.setPointCount (has_n ? n : std::max<std::size_t> (model->num_input_vertices, 1));
    resampling.setNumberOfThreads (threads);
    resampling.setProgressCallback (makeConsoleProgress (quiet || json));
    tools::setStreamBlock (args, resampling);
    std::size_t points = 0;
    double resample_seconds = 0.0, write_seconds = 0.0;
    if (stream)
    {
      const tools::StreamedCloud streamed = tools::streamResampledCloud (resampling, model, out_path, true);
      points = streamed.points;
      resample_seconds = streamed.resample_seconds;
      write_seconds = streamed.save_seconds;
    }
    else
    {
      const tools::LocalCloud local = tools::resampleInLocalFrame (resampling, model);
      points = local.cloud.size ();
      resample_seconds = timer.toc () / 1000.0;
      timer.tic ();
      tools::saveLocalCloud (out_path, local, true);
      write_seconds = timer.toc () / 1000.0;
    }

    timer.tic ();
    if (!recon_mesh.empty ())
    {
      const std::vector<Eigen::Vector3d> vertices = model->reconstructVertices (recon.vertices.size ());
      for (std::size_t v = 0; v < vertices.size (); ++v)
        if (vertices[v].allFinite ())
          recon.vertices[v] = vertices[v];
      saveTriangleMesh (recon_out, recon);
    }
    write_seconds += timer.toc () / 1000.0;

    if (json)
      tools::JsonObject ()
        .add ("model", model_path)
        .add ("patches", model->numPatches ())
        .add ("nnz", model->numNonZeros ())
        .add ("points", points)
        .add ("streamed", stream)
        .add ("area", resampling.getEstimatedArea ())
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
  });
}
