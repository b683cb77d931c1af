/// bench_patches: time of the patch partition (docs/METHOD.md steps 4-6) on real meshes, with the Harris 3D
/// candidate order computed beforehand (its time is reported apart), as a markdown table row per mesh.
///
///   bench_patches MESH... [-rho R] [-repeat N] [-authors] [-header 0]
///
/// -authors: the authors' code's choices (cone 72 degrees, no pairwise cone, no coverage pass, no face completion, every
/// patch kept).
/// Columns: vertices, Harris seconds, partition seconds (best of N, wall clock and process CPU time: on
/// a machine shared with other jobs the CPU time is the meaningful one), microseconds per vertex, patches M,
/// seeds grown by the sampling loop, coverage-pass patches, patch size median, mean patches per vertex.

#include "bench_main.h"

#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>

#include <pcl/console/parse.h>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  double
  now ()
  {
    return std::chrono::duration<double> (std::chrono::steady_clock::now ().time_since_epoch ()).count ();
  }
} // namespace

static int
run (int argc, char** argv)
{
  PatchOptions options;
  int repeat = 3;
  pcl::console::parse_argument (argc, argv, "-rho", options.rho);
  pcl::console::parse_argument (argc, argv, "-repeat", repeat);
  int header = 1;
  pcl::console::parse_argument (argc, argv, "-header", header);
  const bool authors = pcl::console::find_switch (argc, argv, "-authors");
  if (authors)
    options = authorsCodePatchOptions (options);
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-rho" || arg == "-repeat" || arg == "-header")
      ++i;
    else if (arg != "-authors")
      files.push_back (arg);
  }
  if (header)
  {
    std::printf ("| mesh | variant | rho | vertices | Harris s | partition s | partition CPU s | CPU us / vertex | M | uncovered | seeds grown | coverage patches | size median | patches / vertex |\n");
    std::printf ("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  for (const std::string& path : files)
  {
    auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
    double t0 = now ();
    const MeshTopology topology = buildMeshTopology (*mesh);
    std::vector<double> responses;
    std::vector<int> keypoints;
    computeUnitScaleHarris3D (*mesh, topology, 0, responses, keypoints);  // the sampling's default order
    const double harris_seconds = now () - t0;

    FeatureAwarePatchSampling<pcl::PointXYZ> sampling;
    sampling.setInputMesh (mesh);
    sampling.setOptions (options);
    sampling.setResponses (responses);
    sampling.setKeypoints (keypoints);
    std::vector<Patch> patches;
    double best = 1e300, best_cpu = 1e300;
    for (int r = 0; r < std::max (1, repeat); ++r)
    {
      t0 = now ();
      const std::clock_t c0 = std::clock ();
      sampling.compute (patches);
      best = std::min (best, now () - t0);
      best_cpu = std::min (best_cpu, static_cast<double> (std::clock () - c0) / CLOCKS_PER_SEC);
    }
    std::vector<std::size_t> sizes;
    std::size_t memberships = 0;
    for (const Patch& p : patches)
    {
      sizes.push_back (p.size ());
      memberships += p.size ();
    }
    std::sort (sizes.begin (), sizes.end ());
    const std::string name = path.substr (path.find_last_of ('/') + 1);
    std::vector<std::uint8_t> in_patch (mesh->vertices.size (), 0);
    for (const Patch& p : patches)
      for (int v : p.vertices)
        in_patch[v] = 1;
    const std::size_t uncovered = std::count (in_patch.begin (), in_patch.end (), 0);
    std::printf ("| %s | %s | %g | %zu | %.3f | %.3f | %.3f | %.2f | %zu | %zu | %zu | %zu | %zu | %.2f |\n", name.c_str (),
                 authors ? "authors" : "ours", options.rho, mesh->vertices.size (), harris_seconds, best, best_cpu,
                 1e6 * best_cpu / mesh->vertices.size (), patches.size (), uncovered,
                 sampling.getNumGrownSeeds (), sampling.getNumCoveragePatches (),
                 sizes.empty () ? 0 : sizes[sizes.size () / 2],
                 static_cast<double> (memberships) / std::max<std::size_t> (1, mesh->vertices.size ()));
    std::fflush (stdout);
  }
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
