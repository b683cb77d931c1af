/// pcl_sparse_resample: a mesh (encoded first) or a saved model (.psm) to a point cloud with analytic
/// normals and curvature, at any density (docs/METHOD.md step 12).
///
///   pcl_sparse_resample IN OUT [-n N | -density D | -spacing S] [-rho R] [-f F] [-angles K] [-preset default|paper]
///                       [-basis quadric|dct|paper] [-seed S] [-max-slope DEG] [-clearance C]
///                       [-threads T] [-ascii] [-stream auto|on|off] [-block N] [-q] [--json]

#include "tool_input.h"
#include "tool_render.h"
#include "tool_resampling.h"
#include "tool_support.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/model/vertex_attributes.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/common/io.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const tools::ToolDescription kTool = {
    "pcl_sparse_resample", "IN OUT [options]",
    {
      {"IN", "a triangle mesh (.obj .off .ply .stl) or a scan (.pcd .xyz, .ply of points), encoded first,"},
      {"", "or a saved model (.psm)"},
      {"OUT", "the cloud: .pcd (binary unless -ascii) or .ply; fields x y z, the normal (normal_x normal_y"},
      {"", "normal_z in .pcd, nx ny nz in .ply), curvature"},
      {"", "(curvature = signed mean curvature, 1/length, positive where convex), and rgb where"},
      {"", "the input has colour (intensity where it has intensity)"},
      {"-n N", "exactly N points (default: 4 x the mesh's vertices, 1 x the scan's kept points, 4 x a model's"},
      {"", "input vertices: a .psm does not say whether it came from a scan)"},
      {"-density D", "D points per unit of surface area instead"},
      {"-spacing S", "mean spacing S between neighbouring points instead (density 1 / S^2)"},
      {"-rho R", "encoder: patch area bound rho (default: 0.001, paper)"},
      {"-f F", "encoder: Nyquist factor f in [0, 1] (default: 0.5, paper)"},
      {"-angles K", "encoder: footprint angles (default: 64)"},
      {"-preset P", "encoder: default (measured best) or paper (the paper's configuration)"},
      {"-basis B", "encoder: atoms, quadric (default: half-period cosines and the quadric's monomials,"},
      {"", "the least distance and normal error; see README), dct (the cosines alone) or paper"},
      {"-viewpoint X,Y,Z", "scans: the sensor position the normals face (default: the file's VIEWPOINT"},
      {"", "when plausible, else consistently oriented, outward on closed surfaces);"},
      {"", "points exactly there are dropped as no-returns (not those at the file's origin)"},
      {"-seed S", "seed of the sampling (default: 42)"},
      tools::maxSlopeHelpLine (),
      tools::clearanceHelpLine (),
      {"-threads T", "threads (default: all; the cloud does not depend on it)"},
      {"-ascii", "write ascii instead of binary"},
      {"-stream M", "auto (default): write the cloud block by block as it is made, memory set by"},
      {"", "-block, not N, for binary .pcd and any .ply without -png; on: so, or fail; off: whole"},
      {"", "(the same bytes either way)"},
      {"-block N", "streamed: N points per block, 4096 to 67108864 (default 2097152; memory about 200 x N bytes)"},
      tools::noAttributesHelpLine (),
      tools::pngHelpLine (),
      {"-q", "quiet: no progress or messages"},
      {"--json", "print one JSON object with counts and timings on stdout"},
    },
    1, {"-n", "-density", "-spacing", "-rho", "-f", "-seed", "-max-slope", "-clearance", "-threads", "-angles", "-basis",
     "-viewpoint", "-preset", "-png", "-size", "-view", "-stream", "-block"},
    {"-ascii", "-q", "--json", "-no-attributes"}};

  struct Settings
  {
    std::string input, output;
    int mode = 0;  ///< 0 default count, 1 count, 2 density, 3 spacing
    std::size_t count = 0;
    double density = 0.0, spacing = 0.0;
    SparseSurfaceEncoderOptions encoder;
    SparseSurfaceResamplingOptions resampling;
    int threads = 0;
    bool binary = true, quiet = false, json = false;
    bool attributes = true;  ///< colour or intensity coded and written where the input has them
    bool stream = true;  ///< write block by block (tools::streamResampledCloud)
    bool has_viewpoint = false;
    Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero ();
  };

  Settings
  parseSettings (const tools::CommandLine& args)
  {
    using tools::Range;
    Settings s;
    args.expectPositional (2, "IN and OUT");
    tools::checkPngOptions (args);
    s.input = args.positional ()[0];
    s.output = args.positional ()[1];
    if (!tools::hasExtension (s.output, ".pcd") && !tools::hasExtension (s.output, ".ply"))
      throw Error (s.output + ": the output must be .pcd or .ply");
    tools::checkOutputPaths ({s.input}, {s.output, args.value ("-png")});
    if (!tools::hasExtension (s.input, ".psm") && !tools::isSurfaceInputExtension (s.input))
      throw Error (s.input + ": unknown input extension (a mesh .obj .off .ply .stl, a cloud .pcd .xyz .ply or a model .psm)");

    int given = 0;
    if (args.integer ("-n", s.count, Range::closed (1, SparseSurfaceResampling<pcl::PointNormal>::max_points)))
    {
      ++given;
      s.mode = 1;
    }
    if (args.number ("-density", s.density, Range::above (0.0)))
    {
      ++given;
      s.mode = 2;
    }
    if (args.number ("-spacing", s.spacing, Range::above (0.0)))
    {
      ++given;
      s.mode = 3;
    }
    if (given > 1)
      throw Error ("options -n, -density and -spacing exclude each other");
    if (s.mode == 3)  // refused now by the stage's own setter (1e-200 overflows 1/spacing^2), not after encoding
      SparseSurfaceResampling<pcl::PointNormal> ().setSpacing (s.spacing);
    s.encoder = encoderPresetOptions (encoderPresetFromName (args.value ("-preset", "default")));
    args.number ("-rho", s.encoder.patches.rho, Range::aboveUpTo (0.0, 1.0));
    args.number ("-f", s.encoder.coding.nyquist_factor, Range::closed (0.0, 1.0));
    args.integer ("-angles", s.encoder.coding.footprint_angles, Range::closed (3, 4096));
    if (args.has ("-basis"))
      s.encoder.basis = cosineBasisKindFromName (args.value ("-basis"));
    args.integer ("-seed", s.resampling.seed, Range::atLeast (0));
    tools::readOwnershipOptions (args, s.resampling);
    args.integer ("-threads", s.threads, Range::closed (0, 1024));  // 0 = OpenMP's default, as the other tools
    s.has_viewpoint = tools::parseViewpoint (args, s.viewpoint);
    s.binary = !args.has ("-ascii");
    s.attributes = !args.has ("-no-attributes");
    s.quiet = args.has ("-q");
    s.json = args.has ("--json");
    s.stream = tools::chooseStreaming (args, s.output, s.binary, args.has ("-png"));
    return s;
  }

  /// What resampleAndWrite did.
  struct Resampled
  {
    std::size_t points = 0;
    double resample_seconds = 0.0, save_seconds = 0.0, area = 0.0, density = 0.0;
    std::string attributes;  ///< "none", "rgb" or "intensity": the field written after x y z
  };

  /// Resamples \a model into PointT (the fields written) and writes the cloud, whole or streamed;
  /// \a default_count: the point count when no -n, -density or -spacing is given.
  template <typename PointT>
  Resampled
  resampleAndWrite (const tools::CommandLine& args, const Settings& s, const SparseSurfaceModel::ConstPtr& model,
                    std::size_t default_count, const ProgressCallback& progress)
  {
    SparseSurfaceResampling<PointT> resampling;
    resampling.setOptions (s.resampling);
    resampling.setNumberOfThreads (s.threads);
    resampling.setProgressCallback (progress);
    tools::setStreamBlock (args, resampling);
    if (s.mode == 0)
    {
      if (default_count == 0)
        throw Error (s.input + ": the model does not record its vertex count; give -n, -density or -spacing");
      resampling.setPointCount (std::min<std::size_t> (default_count, SparseSurfaceResampling<PointT>::max_points));
    }
    else if (s.mode == 1)
      resampling.setPointCount (s.count);
    else if (s.mode == 2)
      resampling.setDensity (s.density);
    else
      resampling.setSpacing (s.spacing);
    Resampled out;
    out.attributes = tools::extraFieldName (cloudExtraFieldOf<PointT> ());
    if (s.stream)
    {
      const tools::StreamedCloud streamed = tools::streamResampledCloud (resampling, model, s.output, s.binary);
      out.points = streamed.points;
      out.resample_seconds = streamed.resample_seconds;
      out.save_seconds = streamed.save_seconds;
      pcl::console::print_info ("Resampled and wrote %zu points block by block (area %.6g, density %.6g%s) in %.3f s\n",
                                out.points, resampling.getEstimatedArea (), resampling.getDensityUsed (),
                                streamed.bounds_pass ? "; map coordinates: a first pass for the bounds" : "",
                                out.resample_seconds);
    }
    else
    {
      pcl::console::TicToc timer;
      timer.tic ();
      const tools::LocalCloud<PointT> local = tools::resampleInLocalFrame (resampling, model);
      out.points = local.cloud.size ();
      out.resample_seconds = timer.toc () / 1000.0;
      pcl::console::print_info ("Resampled %zu points (area %.6g, density %.6g) in %.3f s\n", out.points,
                                resampling.getEstimatedArea (), resampling.getDensityUsed (), out.resample_seconds);
      timer.tic ();
      tools::saveLocalCloud (s.output, local, s.binary);
      if constexpr (std::is_same_v<PointT, pcl::PointNormal>)
        tools::writeCloudPng (args, local.cloud, local.origin);
      else
      {
        pcl::PointCloud<pcl::PointNormal> shape;  // the picture shades the surface; its colour is not drawn
        pcl::copyPointCloud (local.cloud, shape);
        tools::writeCloudPng (args, shape, local.origin);
      }
      out.save_seconds = timer.toc () / 1000.0;
    }
    out.area = resampling.getEstimatedArea ();
    out.density = resampling.getDensityUsed ();
    return out;
  }
} // namespace

int
main (int argc, char** argv)
{
  return tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    const Settings s = parseSettings (args);
    if (s.quiet || s.json)
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
    const ProgressCallback progress = makeConsoleProgress (s.quiet || s.json);  // as encode, decode and patches
    pcl::console::TicToc total;
    total.tic ();

    // Input: a saved model, or a mesh encoded here.
    auto model = std::make_shared<SparseSurfaceModel> ();
    std::size_t input_vertices = 0, default_factor = 4;
    tools::SurfaceInput input;
    std::shared_ptr<const CloudSurface> surface;
    double load_seconds = 0.0, encode_seconds = 0.0;
    pcl::console::TicToc timer;
    timer.tic ();
    if (tools::hasExtension (s.input, ".psm"))
    {
      // A model is resampled as it was encoded: encoder options would be ignored without a word.
      for (const char* option : {"-rho", "-f", "-angles", "-basis", "-preset", "-viewpoint"})
        if (args.has (option))
          throw Error (std::string ("option ") + option + " encodes a mesh or cloud; " + s.input + " is already a model");
      *model = loadModel (s.input);
      load_seconds = timer.toc () / 1000.0;
      input_vertices = model->num_input_vertices;
    }
    else
    {
      input = tools::loadSurfaceInput (s.input, s.has_viewpoint ? &s.viewpoint : nullptr);
      load_seconds = timer.toc () / 1000.0;
      tools::refuseViewpointOnMesh (s.has_viewpoint, input.mesh != nullptr, s.input);
      // A scan's default count is its kept points (a clean cloud of the same size); a mesh's 4 x its vertices.
      input_vertices = input.points ();
      default_factor = input.mesh ? 4 : 1;
      pcl::console::print_info ("Loaded %s: %zu %s in %.3f s\n", s.input.c_str (), input.points (),
                                input.mesh ? "vertices" : "points", load_seconds);
      s.encoder.validate ();
      SparseSurfaceEncoder<pcl::PointXYZ> encoder;
      tools::setSurfaceInput (encoder, input);
      if (s.has_viewpoint)
        encoder.setViewPoint (s.viewpoint.x (), s.viewpoint.y (), s.viewpoint.z ());
      encoder.setOptions (s.encoder);
      encoder.setNumberOfThreads (s.threads);
      encoder.setProgressCallback (progress);
      // -no-attributes: a scan's colour is not coded (on the 640x480 stereo frame that is a tenth of the
      // run). The geometry does not depend on it.
      if (!s.attributes)
        encoder.setVertexAttributes (std::make_shared<VertexAttributes> ());
      timer.tic ();
      encoder.compute (*model);
      encode_seconds = timer.toc () / 1000.0;
      surface = encoder.getCloudSurface ();
      tools::printAttributeGaps (s.input, encoder.getAttributeGaps ());
      tools::printScanSummary (tools::cleaningReportOf (input, nullptr), surface.get ());
      pcl::console::print_info ("Encoded into %zu patches, %zu coefficients in %.3f s\n", model->numPatches (),
                                model->numNonZeros (), encode_seconds);
    }

    const Resampled out = tools::withPointTypeOf (tools::resampledExtraField (model->attribute_channels, s.attributes), [&] (auto* type) {
      return resampleAndWrite<std::remove_pointer_t<decltype (type)>> (args, s, model, input_vertices * default_factor,
                                                                      progress);
    });
    const std::size_t points = out.points;
    const double resample_seconds = out.resample_seconds, save_seconds = out.save_seconds;
    const double seconds = total.toc () / 1000.0;
    if (!s.quiet && !s.json)
    {
      pcl::console::print_highlight ("Wrote %s: ", s.output.c_str ());
      pcl::console::print_value ("%zu", points);
      pcl::console::print_info (" points in %.3f s (save %.3f s)\n", seconds, save_seconds);
    }
    if (s.json)
    {
      tools::JsonObject json;
      json.add ("input", s.input)
        .add ("output", s.output)
        .add ("points", points)
        .add ("streamed", s.stream)
        .add ("patches", model->numPatches ())
        .add ("input_vertices", input_vertices)
        .add ("area", out.area)
        .add ("density", out.density)
        .add ("attributes", out.attributes)
        .addSeconds ("load_seconds", load_seconds)
        .addSeconds ("encode_seconds", encode_seconds)
        .addSeconds ("resample_seconds", resample_seconds)
        .addSeconds ("save_seconds", save_seconds)
        .addSeconds ("seconds", seconds);
      if (input.mesh || input.scan)
        tools::addInputJson (json, tools::cleaningReportOf (input, nullptr), surface.get ());
      json.print ();
    }
    return 0;
  });
}
