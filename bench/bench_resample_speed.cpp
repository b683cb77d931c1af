// Resampling throughput from an encoded model (issue 14): points per second, and per core, at 1 and 2
// threads. Each mesh is encoded once (the paper's atoms unless -basis names another, 64 footprint angles,
// 1 thread, not timed), then a fresh stage resamples N PointNormal points (so the model's overlap tables are included) several times;
// the best run counts, since the machine is shared and slower runs measure the other jobs. Seconds are the
// wall clock and the process's CPU seconds; per core = points / CPU seconds (at 1 thread the two agree
// unless other jobs took the core; at 2 threads it shows what the second core added).
// Uses only the public API, so bench/resample_speed.sh builds the same file against an older library to
// compare in the same run. Prints one markdown row per (mesh, threads) and a checksum of the cloud, so
// the 1- and 2-thread clouds of a build can be seen to agree.
//
//   bench_resample_speed [-n N] [-repeat R] [-threads T1,T2,..] [-label NAME] [-basis paper|dct|quadric] MESH...
#include "bench_main.h"

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/common/time.h>

#include <ctime>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  SparseSurfaceModel::Ptr
  encodeMesh (const std::shared_ptr<TriangleMesh>& mesh, CosineBasisKind basis)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (mesh);
    encoder.setNumberOfThreads (1);
    SparseSurfaceEncoderOptions options;
    options.coding.footprint_angles = 64;
    options.basis = basis;
    options.coding.max_atoms = 12;
    encoder.setOptions (options);
    auto model = std::make_shared<SparseSurfaceModel> ();
    encoder.compute (*model);
    return model;
  }

  double
  processSeconds ()
  {
    timespec t;
    clock_gettime (CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  }

  /// FNV-1a over the cloud's bytes: equal clouds, equal sums.
  std::uint64_t
  checksum (const pcl::PointCloud<pcl::PointNormal>& cloud)
  {
    std::uint64_t h = 1469598103934665603ULL;
    for (const pcl::PointNormal& p : cloud)
    {
      const float v[7] = {p.x, p.y, p.z, p.normal_x, p.normal_y, p.normal_z, p.curvature};
      unsigned char bytes[sizeof (v)];
      std::memcpy (bytes, v, sizeof (v));
      for (unsigned char b : bytes)
        h = (h ^ b) * 1099511628211ULL;
    }
    return h;
  }
} // namespace

static int
run (int argc, char** argv)
{
  std::size_t n = 4000000;
  int repeat = 3;
  std::vector<int> threads = {1, 2};
  std::string label = "this build";
  CosineBasisKind basis = CosineBasisKind::Paper;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "-n" && i + 1 < argc)
      n = std::stoul (argv[++i]);
    else if (a == "-repeat" && i + 1 < argc)
      repeat = std::max (1, std::stoi (argv[++i]));
    else if (a == "-label" && i + 1 < argc)
      label = argv[++i];
    else if (a == "-basis" && i + 1 < argc)
      basis = cosineBasisKindFromName (argv[++i]);
    else if (a == "-threads" && i + 1 < argc)
    {
      threads.clear ();
      std::stringstream list (argv[++i]);
      for (std::string t; std::getline (list, t, ',');)
        threads.push_back (std::stoi (t));
    }
    else
      meshes.push_back (a);
  }
  for (const std::string& path : meshes)
  {
    auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
    const SparseSurfaceModel::Ptr model = encodeMesh (mesh, basis);
    const std::string name = path.substr (path.find_last_of ('/') + 1);
    for (int t : threads)
    {
      double best = std::numeric_limits<double>::infinity (), best_cpu = best;
      std::uint64_t sum = 0;
      std::size_t points = 0;
      for (int r = 0; r < repeat; ++r)
      {
        SparseSurfaceResampling<pcl::PointNormal> resampling;
        resampling.setInputModel (model);
        resampling.setPointCount (n);
        resampling.setNumberOfThreads (t);
        pcl::PointCloud<pcl::PointNormal> cloud;
        pcl::StopWatch watch;
        const double cpu = processSeconds ();
        resampling.compute (cloud);
        best = std::min (best, watch.getTimeSeconds ());
        best_cpu = std::min (best_cpu, processSeconds () - cpu);
        sum = checksum (cloud);
        points = cloud.size ();
      }
      const double rate = static_cast<double> (points) / best;
      std::printf ("| %s | %s | %zu | %d | %.3f | %.3f | %.2f | %.2f | %.2f | %016llx |\n", name.c_str (), label.c_str (),
                   model->numPatches (), t, best, best_cpu, 1e-6 * rate, 1e-6 * rate / t, 1e-6 * points / best_cpu,
                   static_cast<unsigned long long> (sum));
      std::fflush (stdout);
    }
  }
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
