/// Thread-count independence, byte for byte: the encoder's model (as .psm bytes) and the resampled cloud
/// are identical with 1 and 2 threads, set through the stages (setNumberOfThreads), through
/// omp_set_num_threads, and for the tools through OMP_NUM_THREADS (output files compared byte by byte).

#include "robustness_cases.h"
#include "shared_data.h"

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using namespace pcl_sparse;

namespace
{
  /// A mesh with features, curvature, a boundary and flat parts (ties in the Harris order).
  TriangleMesh
  testMesh ()
  {
    TriangleMesh mesh = makeCube (12, 1.0);
    appendMesh (mesh, makeHeightFieldGrid (40, 40, 1.0, 1.0, [] (double x, double y) {
                  return 2.0 + 0.2 * std::sin (4.0 * x) * std::cos (3.0 * y);
                }));
    appendMesh (mesh, makeTorus (48, 16, 1.0, 0.3));
    return mesh;
  }

  /// threads > 0: through the stages; threads < 0: omp_set_num_threads (-threads) and the stages' default.
  std::vector<std::uint8_t>
  encodeBytes (const TriangleMesh::ConstPtr& mesh, int threads, SparseSurfaceModel* model_out = nullptr)
  {
    const int saved = omp_get_max_threads ();
    if (threads < 0)
      omp_set_num_threads (-threads);
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (mesh);
    encoder.setNumberOfThreads (threads > 0 ? threads : 0);
    SparseSurfaceModel model;
    encoder.compute (model);
    omp_set_num_threads (saved);
    if (model_out)
      *model_out = model;
    return encodeModel (model);
  }

  std::vector<std::uint8_t>
  resampleBytes (const SparseSurfaceModel& model, int threads)
  {
    const int saved = omp_get_max_threads ();
    if (threads < 0)
      omp_set_num_threads (-threads);
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (std::make_shared<const SparseSurfaceModel> (model));
    resampling.setPointCount (20000);
    resampling.setNumberOfThreads (threads > 0 ? threads : 0);
    SparseSurfaceResampling<pcl::PointNormal>::PointCloud cloud;
    resampling.compute (cloud);
    omp_set_num_threads (saved);
    std::vector<std::uint8_t> bytes (cloud.size () * sizeof (pcl::PointNormal));
    if (!cloud.empty ())
      std::memcpy (bytes.data (), cloud.points.data (), bytes.size ());
    return bytes;
  }

  void
  expectThreadIndependent (const TriangleMesh& input)
  {
    const TriangleMesh::ConstPtr mesh = std::make_shared<const TriangleMesh> (input);
    SparseSurfaceModel model;
    const std::vector<std::uint8_t> one = encodeBytes (mesh, 1, &model);
    ASSERT_GT (model.patches.size (), 10u);
    EXPECT_TRUE (one == encodeBytes (mesh, 2)) << "model differs: setNumberOfThreads 1 vs 2";
    EXPECT_TRUE (one == encodeBytes (mesh, -1)) << "model differs: omp_set_num_threads (1)";
    EXPECT_TRUE (one == encodeBytes (mesh, -2)) << "model differs: omp_set_num_threads (2)";

    const std::vector<std::uint8_t> cloud = resampleBytes (model, 1);
    ASSERT_EQ (cloud.size (), 20000 * sizeof (pcl::PointNormal));
    EXPECT_TRUE (cloud == resampleBytes (model, 2)) << "cloud differs: setNumberOfThreads 1 vs 2";
    EXPECT_TRUE (cloud == resampleBytes (model, -1)) << "cloud differs: omp_set_num_threads (1)";
    EXPECT_TRUE (cloud == resampleBytes (model, -2)) << "cloud differs: omp_set_num_threads (2)";
  }

  std::string
  fileBytes (const fs::path& path)
  {
    std::ifstream in (path, std::ios::binary);
    return std::string (std::istreambuf_iterator<char> (in), std::istreambuf_iterator<char> ());
  }

  std::string
  app (const std::string& name)
  {
    return std::string (PCL_SPARSE_BINARY_DIR) + "/apps/pcl_sparse_" + name;
  }

  /// Runs \a command with OMP_NUM_THREADS = \a threads; true when it exits with 0.
  bool
  runWithThreads (int threads, const std::string& command)
  {
    const std::string full = "OMP_NUM_THREADS=" + std::to_string (threads) + " timeout 120 " + command + " -q";
    return std::system (full.c_str ()) == 0;
  }
} // namespace

TEST (Determinism, EncoderAndResamplingGeneratedMesh)
{
  expectThreadIndependent (testMesh ());
}

TEST (Determinism, EncoderAndResamplingFandisk)
{
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/fandisk.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  expectThreadIndependent (loadTriangleMesh (path));
}

TEST (Determinism, LosslessFileResamplesLikeTheModelInMemory)
{
  const TriangleMesh::ConstPtr mesh = std::make_shared<const TriangleMesh> (testMesh ());
  SparseSurfaceModel model;
  const std::vector<std::uint8_t> bytes = encodeBytes (mesh, 0, &model);
  const SparseSurfaceModel loaded = decodeModel (bytes.data (), bytes.size ());
  const std::vector<std::uint8_t> cloud = resampleBytes (model, 0);
  ASSERT_EQ (cloud.size (), 20000 * sizeof (pcl::PointNormal));
  EXPECT_TRUE (cloud == resampleBytes (loaded, 0));
}

TEST (Determinism, ToolsUnderOmpNumThreads)
{
  for (const char* name : {"encode", "resample", "decode"})
    if (!fs::exists (app (name)))
      GTEST_SKIP () << app (name) << " is not built";
  const fs::path dir = fs::path (PCL_SPARSE_BINARY_DIR) / "determinism_tools";
  fs::remove_all (dir);
  fs::create_directories (dir);
  std::string mesh = std::string (PCL_SPARSE_SHARED_MESHES) + "/fandisk.off";
  if (!fs::exists (mesh))
  {
    mesh = (dir / "mesh.obj").string ();
    std::ofstream (mesh) << robustness::objText (testMesh ());
  }
  for (const int threads : {1, 2})
  {
    const std::string t = std::to_string (threads);
    const std::string psm = (dir / ("m" + t + ".psm")).string ();
    ASSERT_TRUE (runWithThreads (threads, app ("encode") + " " + mesh + " -o " + psm));
    ASSERT_TRUE (runWithThreads (threads, app ("encode") + " " + mesh + " -o " + (dir / ("q" + t + ".psm")).string () +
                                            " -tolerance 1e-5"));
    ASSERT_TRUE (runWithThreads (threads, app ("resample") + " " + mesh + " " + (dir / ("r" + t + ".pcd")).string () +
                                            " -n 30000"));
    ASSERT_TRUE (runWithThreads (threads, app ("resample") + " " + mesh + " " + (dir / ("r" + t + ".ply")).string () +
                                            " -n 30000"));
    ASSERT_TRUE (runWithThreads (threads, app ("decode") + " " + psm + " " + (dir / ("d" + t + ".pcd")).string () +
                                            " -n 30000"));
  }
  for (const std::string& name : {"m?.psm", "q?.psm", "r?.pcd", "r?.ply", "d?.pcd"})
  {
    const std::size_t at = name.find ('?');
    const fs::path one = dir / (name.substr (0, at) + "1" + name.substr (at + 1)),
                   two = dir / (name.substr (0, at) + "2" + name.substr (at + 1));
    SCOPED_TRACE (one.string ());
    const std::string a = fileBytes (one), b = fileBytes (two);  // a file not written reads empty
    EXPECT_GT (a.size (), 1000u);
    EXPECT_TRUE (a == b) << one << " and " << two << " differ";
  }
  fs::remove_all (dir);
}

namespace
{
  /// Threads of this process (entries of /proc/self/task); 0 where there is no /proc.
  std::size_t
  processThreadCount ()
  {
    std::error_code error;
    fs::directory_iterator it ("/proc/self/task", error), end;
    return error ? 0 : static_cast<std::size_t> (std::distance (it, end));
  }
} // namespace

// setNumberOfThreads (1) runs on this thread only. Eigen's matrix products parallelise with OpenMP themselves
// when no team of more than one thread is running, so from inside a one-thread loop each colour Gram product
// (CosineGram) started a team of all the cores; under load they spun waiting for each other (a 640x480 RGB-D
// frame's coding 0.7 -> 5.2 s with one core busy). The library is built with EIGEN_DONT_PARALLELIZE. Those
// teams live only as long as their product, so a watcher thread polls the process's thread count meanwhile.
TEST (Determinism, OneThreadStartsNoOtherThread)
{
  if (omp_get_max_threads () < 2)
    GTEST_SKIP () << "one core: OpenMP would start no other thread anyway";
  if (processThreadCount () != 1)
    GTEST_SKIP () << "the process already runs " << processThreadCount ()
                  << " threads (run this test on its own, as ctest does)";
  // A 320 x 240 organized RGB-D frame of a wavy wall with a textured colour, as a sensor gives it.
  const int width = 320, height = 240;
  const double f = 250.0;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZRGB>> (width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
    {
      pcl::PointXYZRGB& p = cloud->at (x, y);
      const double z = 2.0 + 0.1 * std::sin (0.05 * x) * std::cos (0.04 * y);
      p.x = static_cast<float> ((x - 0.5 * width) / f * z);
      p.y = static_cast<float> ((y - 0.5 * height) / f * z);
      p.z = static_cast<float> (z);
      p.r = static_cast<std::uint8_t> (std::lround (128.0 + 100.0 * std::sin (0.3 * x)));
      p.g = static_cast<std::uint8_t> (std::lround (128.0 + 100.0 * std::cos (0.2 * y + 0.1 * x)));
      p.b = 50;
    }
  std::atomic<bool> done (false);
  std::atomic<std::size_t> most (0);
  std::thread watcher ([&] {
    while (!done)
    {
      most = std::max<std::size_t> (most, processThreadCount ());
      std::this_thread::sleep_for (std::chrono::microseconds (200));
    }
  });
  SparseSurfaceEncoder<pcl::PointXYZRGB> encoder;
  encoder.setInputCloud (cloud);
  encoder.setNumberOfThreads (1);
  SparseSurfaceModel model;
  encoder.compute (model);
  done = true;
  watcher.join ();
  ASSERT_GE (model.patches.size (), 10u);
  ASSERT_EQ (model.attribute_channels.size (), 3u);  // coded colour: the Gram products ran
  EXPECT_EQ (most, 2u) << "this thread and the watcher; more: the encoder started threads of its own";
}
