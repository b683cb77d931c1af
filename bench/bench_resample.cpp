// Resampling benchmark: our model -> cloud resampling against pcl::MovingLeastSquares upsampling of the
// mesh vertices (RANDOM_UNIFORM_DENSITY and SAMPLE_LOCAL_PLANE, search radius 3 x the median edge length,
// polynomial order 2), at the same output count (about 4 x the vertex count), single-threaded.
// Runs are timed in CPU seconds of the calling thread (the machine is shared: wall clock would count other
// jobs). Multithreaded output is identical (tested), and is not timed here for the same reason.
// Prints a markdown table (bench/resample.sh writes it to bench/results/resample.md).
//
//   bench_resample [-throughput N] MESH...
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/common/time.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  double
  threadSeconds ()
  {
    timespec t;
    clock_gettime (CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  }

  double
  medianEdgeLength (const TriangleMesh& mesh)
  {
    std::vector<double> lengths;
    for (const Eigen::Vector3i& t : mesh.triangles)
      for (int k = 0; k < 3; ++k)
        lengths.push_back ((mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm ());
    std::nth_element (lengths.begin (), lengths.begin () + lengths.size () / 2, lengths.end ());
    return lengths[lengths.size () / 2];
  }

  struct Row
  {
    std::string method;
    std::size_t points = 0;
    double seconds = 0.0;
    CloudQuality quality;
  };

  /// MLS upsampling of the vertices; \a target points wanted in total.
  Row
  runMls (const TriangleMesh& mesh, bool random_density, double edge, std::size_t target)
  {
    pcl::PointCloud<pcl::PointXYZ>::Ptr vertices (new pcl::PointCloud<pcl::PointXYZ>);
    for (const Eigen::Vector3d& v : mesh.vertices)
      vertices->push_back (pcl::PointXYZ (static_cast<float> (v.x ()), static_cast<float> (v.y ()), static_cast<float> (v.z ())));
    const double radius = 3.0 * edge;
    pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
    mls.setInputCloud (vertices);
    mls.setSearchMethod (pcl::search::KdTree<pcl::PointXYZ>::Ptr (new pcl::search::KdTree<pcl::PointXYZ>));
    mls.setSearchRadius (radius);
    mls.setPolynomialOrder (2);
    mls.setComputeNormals (true);
    mls.setNumberOfThreads (1);
    if (random_density)
    {
      // Each vertex adds floor(D / 2 / #neighbours) points: choose D for the target total.
      pcl::KdTreeFLANN<pcl::PointXYZ> tree;
      tree.setInputCloud (vertices);
      std::vector<int> neighbours;
      std::vector<float> distances;
      std::vector<int> counts;
      for (const auto& p : *vertices)
        counts.push_back (std::max (1, tree.radiusSearch (p, radius, neighbours, distances)));
      double low = 1.0, high = 1e6;
      for (int iteration = 0; iteration < 60; ++iteration)
      {
        const double d = 0.5 * (low + high);
        std::size_t total = 0;
        for (int c : counts)
          total += std::max (1, static_cast<int> (std::floor (d / 2.0 / c)));
        (total < target ? low : high) = d;
      }
      mls.setUpsamplingMethod (pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal>::RANDOM_UNIFORM_DENSITY);
      mls.setPointDensity (static_cast<int> (std::ceil (high)));
    }
    else
    {
      // A grid of step s clipped to a disk of radius 1.2 s (PCL starts the grid at -radius) holds 4 points.
      mls.setUpsamplingMethod (pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal>::SAMPLE_LOCAL_PLANE);
      mls.setUpsamplingRadius (0.6 * edge);
      mls.setUpsamplingStepSize (0.5 * edge);
    }
    Row row;
    row.method = random_density ? "MLS RANDOM_UNIFORM_DENSITY" : "MLS SAMPLE_LOCAL_PLANE";
    pcl::PointCloud<pcl::PointNormal> cloud;
    const double start = threadSeconds ();
    mls.process (cloud);
    row.seconds = threadSeconds () - start;
    row.points = cloud.size ();
    row.quality = evaluateCloudQuality (mesh, cloud);
    return row;
  }

  Row
  runOurs (const TriangleMesh& mesh, const SparseSurfaceModel::ConstPtr& model, std::size_t count, int threads,
           pcl::PointCloud<pcl::PointNormal>* keep = nullptr)
  {
    SparseSurfaceResampling resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (count);
    resampling.setNumberOfThreads (threads);
    pcl::PointCloud<pcl::PointNormal> cloud;
    pcl::StopWatch watch;
    const double start = threadSeconds ();
    resampling.compute (cloud);
    Row row;
    row.seconds = threads == 1 ? threadSeconds () - start : watch.getTimeSeconds ();
    row.method = "ours (" + std::to_string (threads) + " thread" + (threads > 1 ? "s" : "") + ")";
    row.points = cloud.size ();
    if (!keep)
      row.quality = evaluateCloudQuality (mesh, cloud);
    else
      *keep = cloud;
    return row;
  }

  void
  printRow (const std::string& name, const Row& row, double reference_seconds)
  {
    const CloudQuality& q = row.quality;
    std::printf ("| %s | %s | %zu | %.4f | %.3f | %.1fx | %.2e | %.2e | %.2f | %.1f%% | %.4f | %.2f | %.3f |\n", name.c_str (),
                 row.method.c_str (), row.points, row.seconds, 1e6 * row.seconds / std::max<std::size_t> (1, row.points),
                 reference_seconds / row.seconds, q.mean_distance / q.bbox_diagonal, q.rms_distance / q.bbox_diagonal,
                 q.mean_normal_angle, 100.0 * q.flipped / std::max<std::size_t> (1, row.points), q.completeness,
                 q.largest_gap, q.nn_cv);
    std::fflush (stdout);
  }
} // namespace

int
main (int argc, char** argv)
{
  std::size_t throughput_points = 4000000;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "-throughput" && i + 1 < argc)
      throughput_points = std::stoul (argv[++i]);
    else
      meshes.push_back (a);
  }
  std::printf ("| mesh | method | points | seconds | us/point | speed vs MLS RUD | mean dist/diag | RMS dist/diag | "
               "mean normal angle (deg) | flipped | completeness (3 spacings) | largest gap (spacings) | NN CV |\n");
  std::printf ("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> notes;
  for (const std::string& path : meshes)
  {
    const std::string name = path.substr (path.find_last_of ('/') + 1);
    try
    {
      auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
      const double edge = medianEdgeLength (*mesh);
      const std::size_t target = 4 * mesh->numVertices ();
      const Row rud = runMls (*mesh, true, edge, target);
      printRow (name, rud, rud.seconds);
      const Row plane = runMls (*mesh, false, edge, target);
      printRow (name, plane, rud.seconds);

      SparseSurfaceEncoder encoder;
      encoder.setInputMesh (mesh);
      encoder.setNumberOfThreads (1);
      SparseSurfaceEncoderOptions encoder_options;  // as pcl_sparse_resample: paper defaults, 64 footprint angles
      encoder_options.coding.footprint_angles = 64;
      encoder.setOptions (encoder_options);
      auto model = std::make_shared<SparseSurfaceModel> ();
      pcl::StopWatch watch;
      encoder.compute (*model);
      const double encode_seconds = watch.getTimeSeconds ();
      const Row ours = runOurs (*mesh, model, rud.points, 1);
      printRow (name, ours, rud.seconds);
      // Throughput from the encoded model at a large count (quality not measured).
      pcl::PointCloud<pcl::PointNormal> big;
      const Row fast = runOurs (*mesh, model, throughput_points, 1, &big);
      char note[512];
      std::snprintf (note, sizeof (note),
                     "%s: %zu vertices, %zu patches, encode %.3f s (1 thread); %zu points in %.3f s = %.2f million "
                     "points/s on 1 core",
                     name.c_str (), mesh->numVertices (), model->numPatches (), encode_seconds, fast.points, fast.seconds,
                     fast.points / fast.seconds / 1e6);
      notes.push_back (note);
    }
    catch (const std::exception& e)
    {
      notes.push_back (name + ": failed: " + e.what ());
    }
  }
  std::printf ("\n");
  for (const std::string& note : notes)
    std::printf ("- %s\n", note.c_str ());
  return 0;
}
