// Scan benchmark (issue 12 point 10): real and simulated sensor scans through our encoder + resampling,
// side by side with pcl::MovingLeastSquares (projection, and RANDOM_UNIFORM_DENSITY upsampling) and
// pcl::NormalEstimationOMP, and the quantised model's bytes against Draco (-point_cloud) and PCL's
// OctreePointCloudCompression at equal distance. bench/scans.sh runs it on every scan and writes
// bench/results/scans.md. Everything is measured in the scan's local frame (ScanCloud: world = origin + p).
//
//   bench_scans simulate DIR MESH           seeded noisy scans with a known truth: DIR/sim_*.pcd + truth .obj
//                                           (a camera, unorganized samples, MESH seen from a sensor, a lidar street)
//   bench_scans compare SCAN [opts]         quality / time rows (TSV lines starting ROW and SPLIT)
//   bench_scans rd SCAN [opts]              bytes against distance (TSV lines starting RD); runs draco_encoder
//   opts: -truth MESH                       the true surface (file frame); else distances are to the scan's
//                                           own neighbourhood surface (rd) or not measured (compare)
//         -viewpoint X,Y,Z | -viewpoint-above H   sensor position in the file's frame, or H above the
//                                           centroid (+z); default: the file's VIEWPOINT if it has one
//         -threads T (default 2) -up F (MLS upsampling target, x kept points; default 2)
//         -radius-factor R (MLS search radius = R x the scan's median local spacing; default 3)
#include <pcl_sparse/cloud/cloud_surface.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/compression/octree_pointcloud_compression.h>
#include <pcl/features/normal_3d.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/filters/filter.h>
#include <pcl/io/pcd_io.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include <Eigen/Eigenvalues>

#include "cloud_measures.h"
#include "generated_clouds.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const double nan_value = std::numeric_limits<double>::quiet_NaN ();

  struct Clock
  {
    std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now ();
    double cpu = cpuNow ();
    static double
    cpuNow ()
    {
      timespec t;
      clock_gettime (CLOCK_PROCESS_CPUTIME_ID, &t);
      return t.tv_sec + 1e-9 * t.tv_nsec;
    }
    double wallSeconds () const { return std::chrono::duration<double> (std::chrono::steady_clock::now () - wall).count (); }
    double cpuSeconds () const { return cpuNow () - cpu; }
  };

  // ---------------------------------------------------------------- simulated scans
  void
  savePcd (const std::string& path, pcl::PointCloud<pcl::PointXYZ>& cloud, const Eigen::Vector3d& viewpoint)
  {
    cloud.sensor_origin_ = Eigen::Vector4f (viewpoint.x (), viewpoint.y (), viewpoint.z (), 0.0f);
    cloud.sensor_orientation_ = Eigen::Quaternionf::Identity ();
    pcl::io::savePCDFileBinaryCompressed (path, cloud);
  }

  void
  writeObj (const std::string& path, const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& t)
  {
    std::ofstream f (path);
    f.precision (17);
    for (const auto& p : v)
      f << "v " << p.x () << ' ' << p.y () << ' ' << p.z () << '\n';
    for (const auto& tri : t)
      f << "f " << tri[0] + 1 << ' ' << tri[1] + 1 << ' ' << tri[2] + 1 << '\n';
  }

  /// Writes the triangles turned away from \a inside (outward) or toward it (a viewpoint).
  void
  writeObj (const std::string& path, const std::vector<Eigen::Vector3d>& v, std::vector<Eigen::Vector3i> t,
            const Eigen::Vector3d& inside, bool outward)
  {
    for (auto& tri : t)
    {
      const Eigen::Vector3d n = (v[tri[1]] - v[tri[0]]).cross (v[tri[2]] - v[tri[0]]);
      const Eigen::Vector3d c = (v[tri[0]] + v[tri[1]] + v[tri[2]]) / 3.0;
      if ((n.dot (c - inside) < 0.0) == outward)
        std::swap (tri[1], tri[2]);
    }
    writeObj (path, v, t);
  }

  /// The lidar street of generated_clouds.h: DIR/sim_lidar_street.pcd and its truth.
  void
  simulateLidarStreet (const std::string& dir)
  {
    const pcl_sparse_test::LidarStreet street = pcl_sparse_test::lidarStreet ();
    pcl::PointCloud<pcl::PointXYZ> cloud;
    for (const Eigen::Vector3d& p : street.scan.positions)
      cloud.push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
    savePcd (dir + "/sim_lidar_street.pcd", cloud, street.scan.sensor_origin);
    writeObj (dir + "/sim_lidar_street_truth.obj", street.truth.vertices, street.truth.triangles);
  }

  int
  simulate (const std::string& dir, const std::string& mesh_path)
  {
    std::mt19937 random (12);
    std::normal_distribution<double> gauss (0.0, 1.0);
    std::uniform_real_distribution<double> uniform (0.0, 1.0);
    const double sigma = 0.003;  // along the ray / normal; about half the spacing of the organized scans
    // Camera at the origin looking along +z, 320 x 240, f = 300 px.
    const int width = 320, height = 240;
    const double f = 300.0;
    const Eigen::Vector3d origin = Eigen::Vector3d::Zero ();
    const Eigen::Vector3d plane_point (0.0, 0.0, 2.0), plane_normal = Eigen::Vector3d (0.3, 0.2, -1.0).normalized ();
    const Eigen::Vector3d centre (0.0, 0.0, 3.0);
    const double radius = 0.8;
    for (int kind = 0; kind < 2; ++kind)
    {
      pcl::PointCloud<pcl::PointXYZ> cloud (width, height);
      for (int v = 0; v < height; ++v)
        for (int u = 0; u < width; ++u)
        {
          const Eigen::Vector3d d = Eigen::Vector3d ((u - 0.5 * width) / f, (v - 0.5 * height) / f, 1.0).normalized ();
          double t = nan_value;
          if (kind == 0)
            t = plane_normal.dot (plane_point) / plane_normal.dot (d);
          else
          {
            const double b = d.dot (centre), c = centre.squaredNorm () - radius * radius, disc = b * b - c;
            if (disc >= 0.0)
              t = b - std::sqrt (disc);
          }
          pcl::PointXYZ& p = cloud.at (u, v);
          if (std::isfinite (t))
          {
            const Eigen::Vector3d q = (t + sigma * gauss (random)) * d;
            p = pcl::PointXYZ (q.x (), q.y (), q.z ());
          }
          else
            p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN ();
        }
      cloud.is_dense = false;
      savePcd (dir + (kind == 0 ? "/sim_plane_organized.pcd" : "/sim_sphere_organized.pcd"), cloud, origin);
    }
    // Unorganized: 60k points on the plane's 2 x 1.5 rectangle, and the sphere's side facing the sensor,
    // noise along the normal.
    {
      const Eigen::Vector3d e1 = plane_normal.cross (Eigen::Vector3d::UnitY ()).normalized (), e2 = plane_normal.cross (e1);
      pcl::PointCloud<pcl::PointXYZ> plane, sphere;
      for (int i = 0; i < 60000; ++i)
      {
        const Eigen::Vector3d q = plane_point + (2.0 * uniform (random) - 1.0) * e1 + (1.5 * uniform (random) - 0.75) * e2 +
                                  sigma * gauss (random) * plane_normal;
        plane.push_back (pcl::PointXYZ (q.x (), q.y (), q.z ()));
      }
      while (sphere.size () < 60000)
      {
        const Eigen::Vector3d n = Eigen::Vector3d (gauss (random), gauss (random), gauss (random)).normalized ();
        if (n.dot (origin - (centre + radius * n)) <= 0.0)
          continue;
        const Eigen::Vector3d q = centre + (radius + sigma * gauss (random)) * n;
        sphere.push_back (pcl::PointXYZ (q.x (), q.y (), q.z ()));
      }
      savePcd (dir + "/sim_plane.pcd", plane, origin);
      savePcd (dir + "/sim_sphere.pcd", sphere, origin);
      // Truths: a 6 x 6 quad facing the camera, a 256 x 128 UV sphere (chord error 7e-5, 0.02 sigma).
      std::vector<Eigen::Vector3d> v;
      for (int a : {-3, 3})
        for (int b : {-3, 3})
          v.push_back (plane_point + a * e1 + b * e2);
      writeObj (dir + "/sim_plane_truth.obj", v, {{0, 1, 3}, {0, 3, 2}}, origin, false);
      v.clear ();
      std::vector<Eigen::Vector3i> t;
      const int slices = 256, stacks = 128;
      for (int i = 0; i <= stacks; ++i)
        for (int j = 0; j < slices; ++j)
        {
          const double th = M_PI * i / stacks, ph = 2.0 * M_PI * j / slices;
          v.push_back (centre + radius * Eigen::Vector3d (std::sin (th) * std::cos (ph), std::sin (th) * std::sin (ph), std::cos (th)));
        }
      for (int i = 0; i < stacks; ++i)
        for (int j = 0; j < slices; ++j)
        {
          const int a = i * slices + j, b = i * slices + (j + 1) % slices, c = a + slices, d = b + slices;
          if (i > 0)
            t.emplace_back (a, b, d);
          if (i + 1 < stacks)
            t.emplace_back (a, d, c);
        }
      writeObj (dir + "/sim_sphere_truth.obj", v, t, centre, true);
    }
    // A shared mesh: 100k points by area on the faces that face the sensor (no occlusion test), noise
    // sigma 0.001 x diagonal along the face normal; sensor 2 diagonals in front (+z) of the box centre.
    {
      const TriangleMesh mesh = loadTriangleMesh (mesh_path);
      Eigen::Vector3d lo = mesh.vertices[0], hi = lo;
      for (const auto& p : mesh.vertices)
        lo = lo.cwiseMin (p), hi = hi.cwiseMax (p);
      const double diag = (hi - lo).norm ();
      const Eigen::Vector3d eye = 0.5 * (lo + hi) + Eigen::Vector3d (0.0, 0.0, 2.0 * diag);
      std::vector<double> cumulative;
      std::vector<int> faces;
      double total = 0.0;
      for (std::size_t i = 0; i < mesh.triangles.size (); ++i)
      {
        const Eigen::Vector3i& tri = mesh.triangles[i];
        const Eigen::Vector3d n = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).cross (mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
        if (n.dot (eye - mesh.vertices[tri[0]]) <= 0.0)
          continue;
        total += 0.5 * n.norm ();
        cumulative.push_back (total);
        faces.push_back (static_cast<int> (i));
      }
      pcl::PointCloud<pcl::PointXYZ> cloud;
      for (int i = 0; i < 100000; ++i)
      {
        const int k = static_cast<int> (std::lower_bound (cumulative.begin (), cumulative.end (), uniform (random) * total) - cumulative.begin ());
        const Eigen::Vector3i& tri = mesh.triangles[faces[std::min<std::size_t> (k, faces.size () - 1)]];
        double a = uniform (random), b = uniform (random);
        if (a + b > 1.0)
          a = 1.0 - a, b = 1.0 - b;
        const Eigen::Vector3d& p0 = mesh.vertices[tri[0]];
        const Eigen::Vector3d n = (mesh.vertices[tri[1]] - p0).cross (mesh.vertices[tri[2]] - p0).normalized ();
        const Eigen::Vector3d q = p0 + a * (mesh.vertices[tri[1]] - p0) + b * (mesh.vertices[tri[2]] - p0) + 0.001 * diag * gauss (random) * n;
        cloud.push_back (pcl::PointXYZ (q.x (), q.y (), q.z ()));
      }
      std::string base = mesh_path.substr (mesh_path.find_last_of ('/') + 1);
      base = base.substr (0, base.find_last_of ('.'));
      savePcd (dir + "/sim_" + base + ".pcd", cloud, eye);
    }
    simulateLidarStreet (dir);
    return 0;
  }

  // ---------------------------------------------------------------- the scan under test
  struct Scan
  {
    std::string name;
    ScanCloud::Ptr scan = std::make_shared<ScanCloud> ();
    std::shared_ptr<TriangleMesh> truth;  // local frame
    bool has_viewpoint = false;
    Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero ();  // local frame
    pcl::PointCloud<pcl::PointXYZ>::Ptr points = pcl::PointCloud<pcl::PointXYZ>::Ptr (new pcl::PointCloud<pcl::PointXYZ>);
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    std::vector<float> local_spacing;  // per kept point: mean distance to its 6 nearest others
    int threads = 2;
    double up = 2.0, radius_factor = 3.0;
  };

  void
  loadScan (int argc, char** argv, Scan& s)
  {
    const std::string path = argv[2];
    s.name = path.substr (path.find_last_of ('/') + 1);
    loadScanCloud (path, *s.scan);
    std::string truth;
    double above = -1.0;
    for (int i = 3; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "-truth" && i + 1 < argc)
        truth = argv[++i];
      else if (a == "-viewpoint" && i + 1 < argc)
      {
        double x, y, z;
        if (std::sscanf (argv[++i], "%lf,%lf,%lf", &x, &y, &z) != 3)
          throw std::runtime_error ("-viewpoint X,Y,Z");
        s.has_viewpoint = true;
        s.viewpoint = Eigen::Vector3d (x, y, z) - s.scan->origin;
      }
      else if (a == "-viewpoint-above" && i + 1 < argc)
        above = std::stod (argv[++i]);
      else if (a == "-threads" && i + 1 < argc)
        s.threads = std::stoi (argv[++i]);
      else if (a == "-up" && i + 1 < argc)
        s.up = std::stod (argv[++i]);
      else if (a == "-radius-factor" && i + 1 < argc)
        s.radius_factor = std::stod (argv[++i]);
      else
        throw std::runtime_error ("unknown option " + a);
    }
    for (const Eigen::Vector3d& p : s.scan->positions)
      s.points->push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
    if (above >= 0.0)
    {
      Eigen::Vector3d c = Eigen::Vector3d::Zero ();
      for (const Eigen::Vector3d& p : s.scan->positions)
        c += p;
      s.has_viewpoint = true;
      s.viewpoint = c / static_cast<double> (s.scan->size ()) + Eigen::Vector3d (0.0, 0.0, above);
    }
    else if (!s.has_viewpoint && s.scan->has_sensor_pose)
    {
      s.has_viewpoint = true;
      s.viewpoint = s.scan->sensor_origin - s.scan->origin;
    }
    if (!truth.empty ())
    {
      s.truth = std::make_shared<TriangleMesh> (loadTriangleMesh (truth));
      for (Eigen::Vector3d& v : s.truth->vertices)
        v -= s.scan->origin;
    }
    s.tree.setInputCloud (s.points);
    s.local_spacing = pcl_sparse_bench::localSpacings (*s.points, s.tree);
  }

  /// Encoder options for a scan: defaults, the viewpoint when known.
  CloudSurfaceOptions
  surfaceOptions (const Scan& s)
  {
    CloudSurfaceOptions options;
    if (s.has_viewpoint)
    {
      options.has_viewpoint = true;
      options.viewpoint = s.viewpoint + s.scan->origin;  // file frame
    }
    options.num_threads = s.threads;
    return options;
  }

  struct Encoded
  {
    SparseSurfaceModel::Ptr model = std::make_shared<SparseSurfaceModel> ();  // in the local frame
    std::shared_ptr<const CloudSurface> surface;
    EncoderTimings timings;
    double wall = 0.0, cpu = 0.0;
  };

  Encoded
  encodeScan (const Scan& s)
  {
    Encoded e;
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputScan (s.scan);
    encoder.setCloudSurfaceOptions (surfaceOptions (s));
    encoder.setNumberOfThreads (s.threads);
    const Clock clock;
    encoder.compute (*e.model);
    e.wall = clock.wallSeconds ();
    e.cpu = clock.cpuSeconds ();
    e.surface = encoder.getCloudSurface ();
    e.timings = encoder.getTimings ();
    return e;
  }

  pcl::PointCloud<pcl::PointNormal>
  resample (const SparseSurfaceModel::ConstPtr& model, std::size_t count, int threads, double* wall = nullptr, double* cpu = nullptr)
  {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (count);
    resampling.setNumberOfThreads (threads);
    pcl::PointCloud<pcl::PointNormal> out;
    const Clock clock;
    resampling.compute (out);
    if (wall)
      *wall = clock.wallSeconds ();
    if (cpu)
      *cpu = clock.cpuSeconds ();
    return out;
  }

  // ---------------------------------------------------------------- measures
  struct Measures
  {
    std::size_t points = 0, valid = 0, flipped_viewpoint = 0, flipped_clearly = 0, flipped_truth = 0, invented = 0;
    double mean_distance = nan_value, rms_distance = nan_value, roughness = nan_value, normal_mean = nan_value,
           normal_median = nan_value, completeness = nan_value, nn_cv = nan_value;
  };

  Measures
  measure (const Scan& s, const pcl::PointCloud<pcl::PointNormal>& cloud)
  {
    Measures m;
    m.points = cloud.size ();
    pcl::PointCloud<pcl::PointXYZ>::Ptr xyz (new pcl::PointCloud<pcl::PointXYZ>);
    for (const pcl::PointNormal& p : cloud)
    {
      if (!std::isfinite (p.x) || !std::isfinite (p.y) || !std::isfinite (p.z))
        continue;
      xyz->push_back (pcl::PointXYZ (p.x, p.y, p.z));
      const Eigen::Vector3f n = p.getNormalVector3fMap ();
      if (!n.allFinite () || n.squaredNorm () == 0.0f)
        continue;
      ++m.valid;
      if (s.has_viewpoint && n.dot (s.viewpoint.cast<float> () - p.getVector3fMap ()) < 0.0f)
        ++m.flipped_viewpoint;
      // clearly: more than 10 degrees past perpendicular to the line of sight
      if (s.has_viewpoint && n.normalized ().dot ((s.viewpoint.cast<float> () - p.getVector3fMap ()).normalized ()) < -0.17f)
        ++m.flipped_clearly;
    }
    if (s.truth)
    {
      CloudQualityOptions options;
      options.probes = 1000;  // completeness against the whole truth is not the question (one view)
      const CloudQuality q = evaluateCloudQuality (*s.truth, cloud, options);
      m.mean_distance = q.mean_distance;
      m.rms_distance = q.rms_distance;
      m.normal_mean = q.mean_normal_angle;
      m.normal_median = q.median_normal_angle;
      m.flipped_truth = q.flipped;
    }
    if (xyz->empty ())
      return m;
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud (xyz);
    std::vector<int> k_indices;
    std::vector<float> k_squared;
    // Roughness: mean over up to 40k points of the RMS distance of their 16 nearest neighbours to
    // their own PCA plane.
    {
      const std::size_t stride = std::max<std::size_t> (1, xyz->size () / 40000);
      std::vector<double> r;
      for (std::size_t i = 0; i < xyz->size (); i += stride)
      {
        const int found = tree.nearestKSearch ((*xyz)[i], 16, k_indices, k_squared);
        if (found < 5)
          continue;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero ();
        for (int k = 0; k < found; ++k)
          mean += (*xyz)[k_indices[k]].getVector3fMap ().cast<double> ();
        mean /= found;
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero ();
        for (int k = 0; k < found; ++k)
        {
          const Eigen::Vector3d d = (*xyz)[k_indices[k]].getVector3fMap ().cast<double> () - mean;
          cov += d * d.transpose ();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig (cov / found, Eigen::EigenvaluesOnly);
        r.push_back (std::sqrt (std::max (0.0, eig.eigenvalues ()[0])));
      }
      double sum = 0.0;
      for (double x : r)
        sum += x;
      m.roughness = r.empty () ? nan_value : sum / r.size ();
    }
    // Spacing uniformity: CV of nearest-neighbour distances (up to 100k points).
    {
      const std::size_t stride = std::max<std::size_t> (1, xyz->size () / 100000);
      double sum = 0.0, sum2 = 0.0;
      std::size_t n = 0;
      for (std::size_t i = 0; i < xyz->size (); i += stride)
        if (tree.nearestKSearch ((*xyz)[i], 2, k_indices, k_squared) == 2)
        {
          const double d = std::sqrt (k_squared[1]);
          sum += d, sum2 += d * d, ++n;
        }
      const double mean = sum / n;
      m.nn_cv = std::sqrt (std::max (0.0, sum2 / n - mean * mean)) / mean;
    }
    // Completeness: kept input points (up to 100k) with an output point within 3 of their local spacings.
    m.completeness = pcl_sparse_bench::completeness (*s.points, s.local_spacing, tree,
                                                    std::max<std::size_t> (1, s.points->size () / 100000));
    // Invented surface: output points farther than 3 local spacings (of the nearest input point) from
    // every input point.
    for (const pcl::PointXYZ& p : *xyz)
      if (s.tree.nearestKSearch (p, 1, k_indices, k_squared) == 1 && std::sqrt (k_squared[0]) > 3.0f * s.local_spacing[k_indices[0]])
        ++m.invented;
    return m;
  }

  void
  printRow (const Scan& s, const std::string& method, const Measures& m, double wall, double cpu)
  {
    std::printf ("ROW\t%s\t%s\t%zu\t%zu\t%.4f\t%.4f\t%.6g\t%.6g\t%.6g\t%.4g\t%.4g\t%s\t%s\t%s\t%.5f\t%zu\t%.4f\t%zu\n",
                 s.name.c_str (), method.c_str (), m.points, m.valid, wall, cpu, m.mean_distance, m.rms_distance, m.roughness,
                 m.normal_mean, m.normal_median, s.has_viewpoint ? std::to_string (m.flipped_viewpoint).c_str () : "-",
                 s.has_viewpoint ? std::to_string (m.flipped_clearly).c_str () : "-",
                 s.truth ? std::to_string (m.flipped_truth).c_str () : "-", m.completeness, m.invented, m.nn_cv,
                 s.points->size ());
    std::fflush (stdout);
  }

  void
  orient (const Scan& s, pcl::PointCloud<pcl::PointNormal>& cloud)
  {
    // A careful user: normals toward the sensor (PCL's default viewpoint, the file's origin, without one).
    const Eigen::Vector3f vp = (s.has_viewpoint ? s.viewpoint : Eigen::Vector3d (-s.scan->origin)).cast<float> ();
    for (pcl::PointNormal& p : cloud)
      pcl::flipNormalTowardsViewpoint (p, vp.x (), vp.y (), vp.z (), p.normal_x, p.normal_y, p.normal_z);
  }

  pcl::PointCloud<pcl::PointNormal>
  runMls (const Scan& s, double radius, int density, double& wall, double& cpu)
  {
    pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
    mls.setInputCloud (s.points);
    mls.setSearchMethod (pcl::search::KdTree<pcl::PointXYZ>::Ptr (new pcl::search::KdTree<pcl::PointXYZ>));
    mls.setSearchRadius (radius);
    mls.setPolynomialOrder (2);
    mls.setComputeNormals (true);
    mls.setNumberOfThreads (s.threads);
    if (density > 0)
    {
      mls.setUpsamplingMethod (pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal>::RANDOM_UNIFORM_DENSITY);
      mls.setPointDensity (density);
    }
    pcl::PointCloud<pcl::PointNormal> out;
    const Clock clock;
    mls.process (out);
    orient (s, out);
    wall = clock.wallSeconds ();
    cpu = clock.cpuSeconds ();
    return out;
  }

  int
  compare (int argc, char** argv)
  {
    Scan s;
    loadScan (argc, argv, s);
    const std::size_t n = s.points->size ();
    std::fprintf (stderr, "== %s: %zu kept points\n", s.name.c_str (), n);

    // Ours: encode (neighbourhood surface inside), resample 1 x the kept points.
    Encoded e = encodeScan (s);
    e.model->translate (-s.scan->origin);
    const double spacing = e.surface->spacing;
    double rs_wall = 0.0, rs_cpu = 0.0;
    const pcl::PointCloud<pcl::PointNormal> ours = resample (e.model, n, s.threads, &rs_wall, &rs_cpu);

    // The scan's own points with our PCA normals (the baseline of every distance and of the roughness).
    pcl::PointCloud<pcl::PointNormal> own;
    for (std::size_t i = 0; i < n; ++i)
    {
      pcl::PointNormal p;
      p.getVector3fMap () = s.scan->positions[i].cast<float> ();
      const Eigen::Vector3d& nn = e.surface->normals[i];
      p.getNormalVector3fMap () = nn.squaredNorm () > 0.0 ? Eigen::Vector3f (nn.cast<float> ()) : Eigen::Vector3f::Constant (NAN);
      own.push_back (p);
    }
    printRow (s, "scan points (our PCA normals)", measure (s, own), nan_value, nan_value);

    // PCL's NormalEstimationOMP on the same points, k = 16, toward the viewpoint.
    {
      pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> ne (s.threads);
      ne.setInputCloud (s.points);
      ne.setSearchMethod (pcl::search::KdTree<pcl::PointXYZ>::Ptr (new pcl::search::KdTree<pcl::PointXYZ>));
      ne.setKSearch (16);
      const Eigen::Vector3f vp = (s.has_viewpoint ? s.viewpoint : Eigen::Vector3d (-s.scan->origin)).cast<float> ();
      ne.setViewPoint (vp.x (), vp.y (), vp.z ());
      pcl::PointCloud<pcl::Normal> normals;
      const Clock clock;
      ne.compute (normals);
      const double wall = clock.wallSeconds (), cpu = clock.cpuSeconds ();
      pcl::PointCloud<pcl::PointNormal> cloud = own;
      for (std::size_t i = 0; i < n; ++i)
        cloud[i].getNormalVector3fMap () = normals[i].getNormalVector3fMap ();
      printRow (s, "PCL NormalEstimationOMP k16", measure (s, cloud), wall, cpu);
    }
    printRow (s, "ours 1x", measure (s, ours), e.wall + rs_wall, e.cpu + rs_cpu);

    const double radius = s.radius_factor * spacing;
    double wall = 0.0, cpu = 0.0;
    const pcl::PointCloud<pcl::PointNormal> projected = runMls (s, radius, 0, wall, cpu);
    printRow (s, "MLS projection", measure (s, projected), wall, cpu);

    // MLS RANDOM_UNIFORM_DENSITY: a point with c neighbours within the radius adds floor(D / 2 / c)
    // points (its own projection when 0); D chosen for up x the kept points in total.
    int density = 0;
    {
      std::vector<int> counts (n), k_indices;
      std::vector<float> k_squared;
      for (std::size_t i = 0; i < n; ++i)
        counts[i] = std::max (1, s.tree.radiusSearch ((*s.points)[i], radius, k_indices, k_squared));
      const double target = s.up * n;
      double low = 1.0, high = 1e6;
      for (int iteration = 0; iteration < 50; ++iteration)
      {
        const double d = 0.5 * (low + high);
        double total = 0.0;
        for (int c : counts)
          total += std::max (1.0, std::floor (d / 2.0 / c));
        (total < target ? low : high) = d;
      }
      density = static_cast<int> (std::ceil (high));
    }
    const pcl::PointCloud<pcl::PointNormal> upsampled = runMls (s, radius, density, wall, cpu);
    printRow (s, "MLS RANDOM_UNIFORM_DENSITY", measure (s, upsampled), wall, cpu);
    double up_wall = 0.0, up_cpu = 0.0;
    const pcl::PointCloud<pcl::PointNormal> ours_up = resample (e.model, upsampled.size (), s.threads, &up_wall, &up_cpu);
    printRow (s, "ours at MLS RUD count", measure (s, ours_up), e.wall + up_wall, e.cpu + up_cpu);

    // Where our time goes: the neighbourhood surface and Harris 3D again on their own, the encoder's
    // timings, coding the model file, resampling.
    const Clock surface_clock;
    const CloudSurface surface = buildCloudSurface (*s.scan, surfaceOptions (s));
    const double surface_wall = surface_clock.wallSeconds ();
    const MeshTopology topology = buildMeshTopology (surface.mesh);
    Harris3DOptions harris;
    harris.num_threads = s.threads;
    const Clock harris_clock;
    computeHarris3DResponses (surface.mesh, topology, harris);
    const double harris_wall = harris_clock.wallSeconds ();
    ModelWriteOptions write;
    write.tolerance = 1e-3;
    const Clock file_clock;
    const std::size_t bytes = encodeModel (*e.model, write).size ();
    const double file_wall = file_clock.wallSeconds ();
    std::printf ("SPLIT\t%s\t%zu\t%zu\t%.4f\t%.4f\t%.4f\t%.4f\t%.4f\t%.4f\t%.4f\t%.4f\t%zu\t%.6g\t%.6g\t%.6g\t%d\t%zu\n", s.name.c_str (),
                 s.scan->report.input_points, n, e.wall, e.cpu, surface_wall, harris_wall, e.timings.patches, e.timings.coding,
                 file_wall, rs_wall, bytes, spacing, e.surface->noise, radius, density, e.model->numPatches ());
    std::fflush (stdout);
    return 0;
  }

  // ---------------------------------------------------------------- rate-distortion
  double
  meanDistance (const TriangleMesh& reference, const std::vector<Eigen::Vector3f>& points)
  {
    pcl::PointCloud<pcl::PointNormal> cloud;
    for (const Eigen::Vector3f& p : points)
    {
      pcl::PointNormal q;
      q.getVector3fMap () = p;
      q.getNormalVector3fMap () = Eigen::Vector3f::UnitZ ();
      cloud.push_back (q);
    }
    CloudQualityOptions options;
    options.probes = 100;
    return evaluateCloudQuality (reference, cloud, options).mean_distance;
  }

  std::vector<Eigen::Vector3f>
  positionsOf (const pcl::PointCloud<pcl::PointNormal>& cloud)
  {
    std::vector<Eigen::Vector3f> p;
    for (const auto& q : cloud)
      p.push_back (q.getVector3fMap ());
    return p;
  }

  int
  rateDistortion (int argc, char** argv)
  {
    Scan s;
    loadScan (argc, argv, s);
    const std::size_t n = s.points->size ();
    std::fprintf (stderr, "== rd %s: %zu kept points\n", s.name.c_str (), n);
    Encoded e = encodeScan (s);  // model in the file's frame, as a user would save it
    // The encoder's getCloudSurface () holds no mesh (the encoder keeps the surface it worked on): build it.
    const TriangleMesh scan_mesh = s.truth ? TriangleMesh () : buildCloudSurface (*s.scan, surfaceOptions (s)).mesh;
    const TriangleMesh& reference = s.truth ? *s.truth : scan_mesh;
    const char* against = s.truth ? "truth" : "scan surface";
    const double spacing = e.surface->spacing;
    std::vector<Eigen::Vector3f> input;
    for (const auto& p : *s.points)
      input.push_back (p.getVector3fMap ());
    std::printf ("RD\t%s\t%s\tscan\t-\t-\t%zu\t%.6g\n", s.name.c_str (), against, n, meanDistance (reference, input));
    for (double tolerance : {0.0, 3e-5, 1e-4, 3e-4, 1e-3, 3e-3})
    {
      ModelWriteOptions write;
      write.tolerance = tolerance;
      const std::vector<std::uint8_t> bytes = encodeModel (*e.model, write);
      auto model = std::make_shared<SparseSurfaceModel> (decodeModel (bytes.data (), bytes.size ()));
      model->translate (-s.scan->origin);
      const pcl::PointCloud<pcl::PointNormal> cloud = resample (model, n, s.threads);
      std::printf ("RD\t%s\t%s\tours\t%g\t%zu\t%zu\t%.6g\n", s.name.c_str (), against, tolerance, bytes.size (), cloud.size (),
                   meanDistance (reference, positionsOf (cloud)));
      std::fflush (stdout);
    }
    // PCL OctreePointCloudCompression, no voxel down-sampling, octree resolution 2 spacings, point
    // resolution swept.
    for (double factor : {2.0, 1.0, 0.5, 0.25, 0.125, 0.0625})
    {
      pcl::io::OctreePointCloudCompression<pcl::PointXYZ> encoder (pcl::io::MANUAL_CONFIGURATION, false, factor * spacing,
                                                                   2.0 * spacing, false, 1, false, 6);
      std::stringstream stream;
      encoder.encodePointCloud (s.points, stream);
      const std::size_t bytes = stream.str ().size ();
      pcl::io::OctreePointCloudCompression<pcl::PointXYZ> decoder;
      pcl::PointCloud<pcl::PointXYZ>::Ptr decoded (new pcl::PointCloud<pcl::PointXYZ>);
      decoder.decodePointCloud (stream, decoded);
      std::vector<Eigen::Vector3f> p;
      for (const auto& q : *decoded)
        p.push_back (q.getVector3fMap ());
      std::printf ("RD\t%s\t%s\toctree\t%g\t%zu\t%zu\t%.6g\n", s.name.c_str (), against, factor, bytes, p.size (),
                   meanDistance (reference, p));
      std::fflush (stdout);
    }
    // Draco point cloud of the kept points (local frame: Draco quantises over the bounding box anyway).
    const std::string tmp = std::string (std::getenv ("TMPDIR") ? std::getenv ("TMPDIR") : "/tmp") + "/bench_scans_" +
                            std::to_string (getpid ());
    {
      std::ofstream f (tmp + ".ply");
      f << "ply\nformat ascii 1.0\nelement vertex " << n << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
      f.precision (9);
      for (const auto& p : *s.points)
        f << p.x << ' ' << p.y << ' ' << p.z << '\n';
    }
    for (int qp : {8, 10, 11, 12, 13, 14, 16})
    {
      const std::string command = "draco_encoder -point_cloud -cl 7 -qp " + std::to_string (qp) + " -i " + tmp + ".ply -o " + tmp +
                                  ".drc > /dev/null && draco_decoder -i " + tmp + ".drc -o " + tmp + "_d.ply > /dev/null";
      if (std::system (command.c_str ()) != 0)
      {
        std::fprintf (stderr, "draco failed (qp %d)\n", qp);
        break;
      }
      std::ifstream drc (tmp + ".drc", std::ios::binary | std::ios::ate);
      const std::size_t bytes = static_cast<std::size_t> (drc.tellg ());
      ScanCloud decoded;
      ScanLoadOptions load;
      load.clean = false;
      loadScanCloud (tmp + "_d.ply", decoded, load);
      std::vector<Eigen::Vector3f> p;
      for (std::size_t i = 0; i < decoded.size (); ++i)
        p.push_back (decoded.worldPosition (i).cast<float> ());
      std::printf ("RD\t%s\t%s\tdraco\t%d\t%zu\t%zu\t%.6g\n", s.name.c_str (), against, qp, bytes, p.size (), meanDistance (reference, p));
      std::fflush (stdout);
    }
    std::remove ((tmp + ".ply").c_str ());
    std::remove ((tmp + ".drc").c_str ());
    std::remove ((tmp + "_d.ply").c_str ());
    return 0;
  }
  /// Writes the finite points of an organized .pcd as an unorganized one (WIDTH = N, HEIGHT = 1, its
  /// viewpoint kept): what a frame is after a NaN filter, or as a tile of it, which the encoder takes
  /// through its kNN surface (and kNN depth-step removal) instead of the image grid.
  int
  unorganize (const std::string& in, const std::string& out)
  {
    pcl::PointCloud<pcl::PointXYZRGB> organized, unorganized;
    if (pcl::io::loadPCDFile (in, organized) != 0)
      throw std::runtime_error ("cannot read " + in);
    std::vector<int> kept;
    pcl::removeNaNFromPointCloud (organized, unorganized, kept);
    if (pcl::io::savePCDFileBinary (out, unorganized) != 0)
      throw std::runtime_error ("cannot write " + out);
    std::fprintf (stderr, "%s: %zu of %zu points, unorganized\n", out.c_str (), unorganized.size (), organized.size ());
    return 0;
  }
} // namespace

int
main (int argc, char** argv)
{
  try
  {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "simulate" && argc == 4)
      return simulate (argv[2], argv[3]);
    if (mode == "compare" && argc >= 3)
      return compare (argc, argv);
    if (mode == "rd" && argc >= 3)
      return rateDistortion (argc, argv);
    if (mode == "unorganize" && argc == 4)
      return unorganize (argv[2], argv[3]);
    std::fprintf (stderr, "usage: bench_scans simulate DIR MESH | compare SCAN [opts] | rd SCAN [opts] | unorganize IN.pcd OUT.pcd\n");
    return 1;
  }
  catch (const std::exception& e)
  {
    std::fprintf (stderr, "bench_scans: %s\n", e.what ());
    return 1;
  }
}
