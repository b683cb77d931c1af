/// pcl_sparse_patches: partitions a mesh into the paper's overlapping height-field patches (docs/METHOD.md
/// steps 3-6) and writes the mesh coloured by patch, seeds marked, so the partition can be inspected.
///
///   pcl_sparse_patches MESH OUT.ply [-rho R] [-delta D] [-cone C] [-eta E] [-sigma S] [-min-size N]
///                      [--authors] [--json] [-q]

#include "tool_input.h"
#include "tool_render.h"
#include "tool_support.h"

#include <pcl_sparse/common/color_map.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/patches/patch_checks.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const PatchOptions kDefaults;

  const tools::ToolDescription kTool = {
    "pcl_sparse_patches", "IN OUT.ply [options]",
    {
      {"IN", "a triangle mesh (.obj .off .ply .stl) or a scan (.pcd .xyz, .ply of points)"},
      {"OUT.ply", "the mesh (a scan's neighbourhood surface), each vertex coloured by one of its patches,"},
      {"", "seeds black"},
      {"-viewpoint X,Y,Z", "scans: the sensor position the normals face (points exactly there dropped)"},
      {"-rho R", tools::format ("size bound A_p / A (default %g)", kDefaults.rho)},
      {"-delta D", tools::format ("smooth variation angle in degrees (default %g; %g on a lidar frame's rings)",
                                  kDefaults.delta * 180.0 / M_PI, kDefaults.lidar_delta * 180.0 / M_PI)},
      {"-cone C",
       tools::format ("normal cone angle in degrees (default %g, the authors' code's; paper 90)", kDefaults.cone_angle * 180.0 / M_PI)},
      {"-eta E", tools::format ("flatness bound A_p / A_p^proj (default %g)", kDefaults.eta)},
      {"-sigma S", tools::format ("seed overlap control (default %g)", kDefaults.sigma)},
      {"-min-size N", tools::format ("smallest patch the sampling keeps (default %d)", kDefaults.min_patch_size)},
      {"--authors", "the authors' code: cone 72 degrees, no pairwise cone, no coverage pass, no face completion,"},
      {"", "every patch kept"},
      {"-preset P", "default or paper (the paper's cone of 90 degrees, no pairwise cone, no face completion,"},
      {"", "every patch kept);"},
      {"", "the other options override it"},
      tools::pngHelpLine (),
      {"--keep-redundant-patches", "keep the patches whose every vertex and triangle others also hold (the paper's"},
      {"", "patches; default: dropped, PatchOptions::drop_redundant_patches)"},
      {"-merge-patches K", tools::format ("merge each patch with at most K vertices and triangles of its own into its"
                                          " neighbours (default %d; 0: none)", kDefaults.merge_own_elements)},
      {"-point-patches S", tools::format ("scans: a point in no triangle gets a patch of its own only farther than S"
                                          " mean edge lengths from the triangles (default %g; 0: every such point)",
                                          kDefaults.unreferenced_patch_spacings)},
      {"--json", "print one JSON object on stdout"},
      {"-q", "quiet (no progress, no messages besides the report and errors)"},
    },
    1, {"-rho", "-delta", "-cone", "-eta", "-sigma", "-min-size", "-viewpoint", "-preset", "-png", "-size", "-view",
        "-merge-patches", "-point-patches"},
    {"--json", "-q", "--authors", "--keep-redundant-patches"}};
} // namespace

int
main (int argc, char** argv)
{
  return tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    const bool json = args.has ("--json");
    const bool quiet = args.has ("-q");
    if (quiet || json)  // as the other tools: --json's stdout is one object, and notes stay off stderr
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
    args.expectPositional (2, "IN and OUT.ply");
    tools::checkPngOptions (args);
    const std::string& input = args.positional ()[0];
    const std::string& output = args.positional ()[1];
    if (!tools::hasExtension (output, ".ply"))
      throw Error (output + ": the output must be a .ply file");
    tools::checkOutputPaths ({input}, {output, args.value ("-png")});

    PatchOptions options = encoderPresetOptions (encoderPresetFromName (args.value ("-preset", "default"))).patches;
    if (args.has ("--authors"))
      options = authorsCodePatchOptions (options);
    args.number ("-rho", options.rho, tools::Range::aboveUpTo (0.0, 1.0));
    args.angle ("-delta", options.delta);
    if (args.has ("-delta"))  // everywhere, lidar rings too
      options.lidar_delta = 0.0;
    args.angle ("-cone", options.cone_angle);
    args.number ("-eta", options.eta);
    args.number ("-sigma", options.sigma);
    args.integer ("-min-size", options.min_patch_size);
    if (args.has ("--keep-redundant-patches"))
      options.drop_redundant_patches = false;
    args.integer ("-merge-patches", options.merge_own_elements, tools::Range::atLeast (0));
    args.number ("-point-patches", options.unreferenced_patch_spacings, tools::Range::atLeast (0.0));
    Eigen::Vector3d viewpoint;
    const bool has_viewpoint = tools::parseViewpoint (args, viewpoint);
    try
    {
      options.validate ();
    }
    catch (const Error& e)
    {
      // The stage names its field; the user gave an option ("-min-size 0" said "(angles are given in degrees)";
      // -delta and -cone are checked in degrees as they are read).
      const std::string what = e.what ();
      const std::pair<const char*, const char*> options_of_fields[] = {
        {"eta =", "-eta"}, {"sigma =", "-sigma"}, {"min_patch_size =", "-min-size"}, {"rho =", "-rho"}};
      for (const auto& [field, option] : options_of_fields)
        if (what.find (field) != std::string::npos)
          throw Error (what + " (option " + option + ")");
      throw;
    }

    const tools::SurfaceInput surface_input = tools::loadSurfaceInput (input, has_viewpoint ? &viewpoint : nullptr);
    tools::refuseViewpointOnMesh (has_viewpoint, surface_input.mesh != nullptr, input);
    pcl::console::TicToc timer;
    timer.tic ();
    FeatureAwarePatchSampling<pcl::PointXYZ> sampling;
    tools::setSurfaceInput (sampling, surface_input);
    if (has_viewpoint)
      sampling.setViewPoint (viewpoint.x (), viewpoint.y (), viewpoint.z ());
    sampling.setOptions (options);
    sampling.setProgressCallback (makeConsoleProgress (quiet || json));
    std::vector<Patch> patches;
    sampling.compute (patches);
    const double seconds = timer.toc () / 1000.0;
    // The surface the patches grew on: the mesh, or a scan's neighbourhood surface (moved to the file's frame).
    const TriangleMesh::ConstPtr mesh = tools::surfaceInInputFrame (sampling);

    // Statistics.
    std::vector<std::size_t> sizes;
    std::vector<int> count (mesh->vertices.size (), 0);
    for (const Patch& p : patches)
    {
      sizes.push_back (p.size ());
      for (int v : p.vertices)
        ++count[v];
    }
    std::sort (sizes.begin (), sizes.end ());
    std::size_t covered = 0, memberships = 0;
    for (int c : count)
      if (c > 0)
      {
        ++covered;
        memberships += static_cast<std::size_t> (c);
      }
    std::size_t kinds[3] = {0, 0, 0};
    for (PatchFrameKind k : sampling.getFrameKinds ())
      ++kinds[static_cast<int> (k)];
    const double per_vertex = covered > 0 ? static_cast<double> (memberships) / covered : 0.0;
    const std::size_t smin = sizes.empty () ? 0 : sizes.front (), smax = sizes.empty () ? 0 : sizes.back ();
    const std::size_t smed = sizes.empty () ? 0 : sizes[sizes.size () / 2];
    const std::shared_ptr<const CloudSurface>& scan_surface = sampling.getCloudSurface ();
    PatchInvariantChecker checker (*mesh, options, scan_surface ? scan_surface->normals : std::vector<Eigen::Vector3d> ());
    std::size_t invalid = 0;
    for (const Patch& p : patches)
      if (!checker.check (p).empty ())
        ++invalid;
    const std::size_t uncovered = mesh->vertices.size () - covered;

    std::vector<RgbColor> colors = tools::centralPatchColors (patches, mesh->vertices.size ());
    for (const Patch& p : patches)
      colors[p.seed] = {0, 0, 0};
    saveColoredMesh (output, *mesh, colors);
    tools::removeIfRunFails (output);
    tools::writeMeshPng (args, *mesh, colors, true);

    if (json)
      tools::JsonObject ()
        .add ("file", input)
        .add ("vertices", mesh->vertices.size ())
        .add ("patches", patches.size ())
        .add ("uncovered", uncovered)
        .add ("unreferenced", sampling.getUnreferencedVertices ().size ())
        .add ("coverage_patches", sampling.getNumCoveragePatches ())
        .add ("redundant_patches", sampling.getNumRedundantPatches ())
        .add ("merged_patches", sampling.getNumMergedPatches ())
        .add ("keypoints", sampling.getKeypoints ().size ())
        .add ("size_min", smin)
        .add ("size_median", smed)
        .add ("size_max", smax)
        .add ("patches_per_vertex", per_vertex)
        .add ("invalid_patches", invalid)
        .add ("frames_jet", kinds[0])
        .add ("frames_seed_normal", kinds[1])
        .add ("frames_normal_only", kinds[2])
        .addSeconds ("seconds", seconds)
        .print ();
    else
    {
      std::printf ("file: %s\n", input.c_str ());
      std::printf ("vertices: %zu\n", mesh->vertices.size ());
      std::printf ("patches (M): %zu\n", patches.size ());
      std::printf ("uncovered vertices: %zu\n", uncovered);
      std::printf ("unreferenced vertices: %zu\n", sampling.getUnreferencedVertices ().size ());
      std::printf ("coverage-pass patches: %zu\n", sampling.getNumCoveragePatches ());
      std::printf ("redundant patches dropped: %zu\n", sampling.getNumRedundantPatches ());
      std::printf ("patches merged into neighbours: %zu\n", sampling.getNumMergedPatches ());
      std::printf ("patch size min/median/max: %zu / %zu / %zu\n", smin, smed, smax);
      std::printf ("mean patches per vertex: %.3f\n", per_vertex);
      std::printf ("patches violating an invariant: %zu\n", invalid);
      std::printf ("frames jet / seed normal / normal only: %zu / %zu / %zu\n", kinds[0], kinds[1], kinds[2]);
      std::printf ("seconds: %.3f\n", seconds);
    }
    return 0;
  });
}
