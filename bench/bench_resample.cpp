// Resampling benchmark: our model -> cloud resampling against pcl::MovingLeastSquares upsampling of the
// mesh vertices (RANDOM_UNIFORM_DENSITY and SAMPLE_LOCAL_PLANE, search radius 3 x the median edge length,
// polynomial order 2), at the same output count (about 4 x the vertex count), single-threaded.
// Runs are timed in CPU seconds of the calling thread (the machine is shared: wall clock would count other
// jobs). Multithreaded output is identical (tested), and is not timed here for the same reason.
// Prints a markdown table (bench/resample.sh writes it to bench/results/resample.md).
//
//   bench_resample [-throughput N] [-angles K] [-basis paper|dct] [-L N] MESH...
//   bench_resample -diagnose [-angles K] [-worst N] [-file T A] MESH...   (stray points, normal-angle
//                  distribution; -file: through a .psm in memory at tolerance T keeping at most A angles)
//   -basis, -L: encoder basis and atoms (default: the library's, dct and 12)
//   bench_resample -cloud CLOUD.pcd MESH                       (quality of any cloud against its mesh)
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/common/time.h>
#include <pcl/io/pcd_io.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include <algorithm>
#include <numeric>
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
    SparseSurfaceResampling<pcl::PointNormal> resampling;
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
    std::printf ("| %s | %s | %zu | %.4f | %.3f | %.1fx | %.2e | %.2e | %.2e | %.2f | %.2f | %.2f | %.1f%% | %.4f | %.2f | %.3f |\n",
                 name.c_str (), row.method.c_str (), row.points, row.seconds, 1e6 * row.seconds / std::max<std::size_t> (1, row.points),
                 reference_seconds / row.seconds, q.mean_distance / q.bbox_diagonal, q.rms_distance / q.bbox_diagonal,
                 q.max_distance / q.bbox_diagonal, q.mean_normal_angle, q.median_normal_angle, q.p90_normal_angle, 100.0 * q.flipped / std::max<std::size_t> (1, row.points), q.completeness,
                 q.largest_gap, q.nn_cv);
    std::fflush (stdout);
  }
  /// Encoder basis and atom bound besides the footprint angles (the library's defaults unless -basis / -L).
  CosineBasisKind diagnose_basis = SparseSurfaceEncoderOptions ().basis;
  int diagnose_atoms = SparseSurfaceEncoderOptions ().coding.max_atoms;

  SparseSurfaceModel::Ptr
  encodeMesh (const std::shared_ptr<TriangleMesh>& mesh, int angles, double* seconds = nullptr)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (mesh);
    encoder.setNumberOfThreads (1);
    SparseSurfaceEncoderOptions encoder_options;  // default options, footprint angles as asked
    encoder_options.coding.footprint_angles = angles;
    encoder_options.basis = diagnose_basis;
    encoder_options.coding.max_atoms = diagnose_atoms;
    encoder.setOptions (encoder_options);
    auto model = std::make_shared<SparseSurfaceModel> ();
    pcl::StopWatch watch;
    encoder.compute (*model);
    if (seconds)
      *seconds = watch.getTimeSeconds ();
    return model;
  }

  /// Where the worst points of a resampled cloud come from, and the normal-angle distribution against
  /// the mesh's own vertex normals (the floor a smooth normal field can reach against flat faces).
  void
  diagnose (const std::string& path, int angles, int worst, double file_tolerance, int file_angles)
  {
    auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
    SparseSurfaceModel::Ptr model = encodeMesh (mesh, angles);
    std::size_t file_bytes = 0;
    if (file_tolerance >= 0.0)
    {
      ModelWriteOptions write;
      write.tolerance = file_tolerance;
      write.max_footprint_angles = file_angles;
      const std::vector<std::uint8_t> bytes = encodeModel (*model, write);
      file_bytes = bytes.size ();
      model = std::make_shared<SparseSurfaceModel> (decodeModel (bytes.data (), bytes.size ()));
    }
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (4 * mesh->numVertices ());
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    CloudQualityOptions options;
    options.keep_per_point = true;
    const CloudQuality q = evaluateCloudQuality (*mesh, cloud, options);
    const std::vector<int>& owner = resampling.getPointPatches ();
    const std::size_t n = q.point_distances.size ();
    std::vector<double> d = q.point_distances;
    std::sort (d.begin (), d.end ());
    const double diag = q.bbox_diagonal;
    // Reference: the mesh's vertices with their area-weighted normals.
    pcl::PointCloud<pcl::PointNormal> vertex_cloud;
    const std::vector<Eigen::Vector3d> vn = computeVertexNormals (*mesh, buildMeshTopology (*mesh));
    for (std::size_t v = 0; v < mesh->numVertices (); ++v)
    {
      pcl::PointNormal point;
      point.getVector3fMap () = mesh->vertices[v].cast<float> ();
      point.getNormalVector3fMap () = vn[v].cast<float> ();
      vertex_cloud.push_back (point);
    }
    const CloudQuality reference = evaluateCloudQuality (*mesh, vertex_cloud);
    if (file_tolerance >= 0.0)
      std::printf ("file tolerance %g, at most %d angles: %zu bytes; ", file_tolerance, file_angles, file_bytes);
    std::printf ("%s (K=%d, %zu patches, %zu points): max dist/diag %.3e, 99.9%% %.3e, 99%% %.3e, mean %.3e; normal angle "
                 "mean %.2f median %.2f p90 %.2f (vertex normals: mean %.2f median %.2f p90 %.2f)\n",
                 path.substr (path.find_last_of ('/') + 1).c_str (), angles, model->numPatches (), n, d.back () / diag,
                 d[std::min (n - 1, n * 999 / 1000)] / diag, d[std::min (n - 1, n * 99 / 100)] / diag, q.mean_distance / diag,
                 q.mean_normal_angle, q.median_normal_angle, q.p90_normal_angle, reference.mean_normal_angle,
                 reference.median_normal_angle, reference.p90_normal_angle);
    // Normal angle vs centrality of the point in its own patch.
    const PatchEvaluator evaluator (*model);
    double band_sum[4] = {0, 0, 0, 0};
    std::size_t band_count[4] = {0, 0, 0, 0};
    std::vector<std::size_t> order (n);
    std::iota (order.begin (), order.end (), 0);
    std::sort (order.begin (), order.end (), [&] (std::size_t a, std::size_t b) { return q.point_distances[a] > q.point_distances[b]; });
    for (std::size_t i = 0; i < n; ++i)
    {
      const PatchCode& code = model->patches[owner[i]];
      const Eigen::Vector3d local = code.frame.transpose () * (cloud[i].getVector3fMap ().cast<double> () - code.origin) / code.radius;
      const double c = evaluator.centrality (owner[i], local.x (), local.y ());
      const int band = c < 0.5 ? 0 : c < 0.8 ? 1 : c < 0.95 ? 2 : 3;
      band_sum[band] += q.point_normal_angles[i];
      ++band_count[band];
    }
    // The analytic gradient against central differences of the height (a scaling bug would show here).
    double worst_gradient = 0.0;
    for (std::size_t i = 0; i < n; i += 97)
    {
      const PatchCode& code = model->patches[owner[i]];
      const Eigen::Vector3d local = code.frame.transpose () * (cloud[i].getVector3fMap ().cast<double> () - code.origin) / code.radius;
      const double e = 1e-5;
      const Eigen::Vector2d numeric ((evaluator.height (owner[i], local.x () + e, local.y ()) - evaluator.height (owner[i], local.x () - e, local.y ())) / (2 * e),
                                     (evaluator.height (owner[i], local.x (), local.y () + e) - evaluator.height (owner[i], local.x (), local.y () - e)) / (2 * e));
      worst_gradient = std::max (worst_gradient, (numeric - evaluator.sample (owner[i], local.x (), local.y ()).gradient).norm ());
    }
    std::printf ("  largest |analytic - numeric gradient|: %.2e\n", worst_gradient);
    std::printf ("  mean normal angle by centrality: <0.5 %.2f (%zu), 0.5-0.8 %.2f (%zu), 0.8-0.95 %.2f (%zu), >=0.95 %.2f (%zu)\n",
                 band_sum[0] / std::max<std::size_t> (1, band_count[0]), band_count[0],
                 band_sum[1] / std::max<std::size_t> (1, band_count[1]), band_count[1],
                 band_sum[2] / std::max<std::size_t> (1, band_count[2]), band_count[2],
                 band_sum[3] / std::max<std::size_t> (1, band_count[3]), band_count[3]);
    for (int w = 0; w < worst && w < static_cast<int> (n); ++w)
    {
      const std::size_t i = order[w];
      const int p = owner[i];
      const PatchCode& code = model->patches[p];
      const Eigen::Vector3d local = code.frame.transpose () * (cloud[i].getVector3fMap ().cast<double> () - code.origin) / code.radius;
      double zmin = 1e300, zmax = -1e300;
      for (int v : code.vertices)
      {
        const double z = code.frame.col (2).dot (mesh->vertices[v] - code.origin) / code.radius;
        zmin = std::min (zmin, z);
        zmax = std::max (zmax, z);
      }
      double cmax = 0.0;
      for (double a : code.coefficients)
        cmax = std::max (cmax, std::abs (a));
      const HeightSample h = evaluator.sample (p, local.x (), local.y ());
      std::printf ("  dist/diag %.3e angle %.1f patch %d (%zu vertices, %zu atoms, max |coef| %.3g, r/diag %.3e) local (%.3f, %.3f) "
                   "h %.3f |grad| %.2f data z [%.3f, %.3f] centrality %.3f\n",
                   q.point_distances[i] / diag, q.point_normal_angles[i], p, code.vertices.size (), code.atoms.size (), cmax,
                   code.radius / diag, local.x (), local.y (), h.value, h.gradient.norm (), zmin, zmax,
                   evaluator.centrality (p, local.x (), local.y ()));
    }
    std::fflush (stdout);
  }
} // namespace

int
main (int argc, char** argv)
{
  std::size_t throughput_points = 4000000;
  int angles = 64, worst = 10, file_angles = 0;
  double file_tolerance = -1.0;
  bool diagnosis = false;
  std::string cloud_path;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "-throughput" && i + 1 < argc)
      throughput_points = std::stoul (argv[++i]);
    else if (a == "-angles" && i + 1 < argc)
      angles = std::stoi (argv[++i]);
    else if (a == "-worst" && i + 1 < argc)
      worst = std::stoi (argv[++i]);
    else if (a == "-file" && i + 2 < argc)
    {
      file_tolerance = std::stod (argv[++i]);
      file_angles = std::stoi (argv[++i]);
    }
    else if (a == "-cloud" && i + 1 < argc)
      cloud_path = argv[++i];
    else if (a == "-basis" && i + 1 < argc)
      diagnose_basis = std::string (argv[++i]) == "paper" ? CosineBasisKind::Paper : CosineBasisKind::Dct;
    else if (a == "-L" && i + 1 < argc)
      diagnose_atoms = std::stoi (argv[++i]);
    else if (a == "-diagnose")
      diagnosis = true;
    else
      meshes.push_back (a);
  }
  if (!cloud_path.empty () && meshes.size () == 1)
  {
    pcl::PointCloud<pcl::PointNormal> cloud;
    if (pcl::io::loadPCDFile (cloud_path, cloud) < 0)
      return 1;
    const TriangleMesh mesh = loadTriangleMesh (meshes[0]);
    const CloudQuality q = evaluateCloudQuality (mesh, cloud);
    std::printf ("%s: %zu points, mesh->cloud largest gap / diag %.3e, max dist/diag %.3e, mean %.3e, normal angle mean %.2f median %.2f p90 %.2f, flipped %zu\n",
                 cloud_path.c_str (), cloud.size (), q.largest_gap * q.spacing / q.bbox_diagonal, q.max_distance / q.bbox_diagonal, q.mean_distance / q.bbox_diagonal,
                 q.mean_normal_angle, q.median_normal_angle, q.p90_normal_angle, q.flipped);
    return 0;
  }
  if (diagnosis)
  {
    for (const std::string& path : meshes)
      diagnose (path, angles, worst, file_tolerance, file_angles);
    return 0;
  }
  std::printf ("| mesh | method | points | seconds | us/point | speed vs MLS RUD | mean dist/diag | RMS dist/diag | max dist/diag | "
               "mean normal angle (deg) | median | p90 | flipped | completeness (3 spacings) | largest gap (spacings) | NN CV |\n");
  std::printf ("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
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

      double encode_seconds = 0.0;
      const SparseSurfaceModel::Ptr model = encodeMesh (mesh, angles, &encode_seconds);
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
