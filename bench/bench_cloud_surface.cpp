/// bench_cloud_surface: the neighbourhood surface of scans (buildCloudSurface, issue 12 points 3, 4, 6).
///   1. normals on simulated scans of analytic surfaces, ours (PCA over the kNN graph or the image window)
///      against pcl::NormalEstimationOMP with the same k: time and angle error to the true normals;
///   2. the shared scans: buildCloudSurface time (wall and CPU), counts, and PCL's normals on the same
///      points (time, median angle to ours); bun000 against the normals of stanford-bunny.obj;
///   3. triangles of unorganized scans: our local Delaunay fans against pcl::GreedyProjectionTriangulation
///      fed with our oriented normals: time, triangles, points referenced, edges with > 2 triangles.
/// Prints a markdown report on stdout.
///
///   bench_cloud_surface CLOUDS_DIR [MESHES_DIR] [REPEATS]
///   (bench/cloud_surface.sh runs it with ../shared/clouds, ../shared/meshes, 5)

#include "bench_main.h"

#include <pcl_sparse/cloud/cloud_surface.h>
#include <pcl_sparse/cloud/grid_neighborhoods.h>
#include <pcl_sparse/cloud/knn_neighborhoods.h>
#include <pcl_sparse/cloud/pca_normals.h>
#include <pcl_sparse/cloud/scan_grid.h>
#include <pcl_sparse/cloud/small_hole_filling.h>
#include <pcl_sparse/cloud/tangent_triangulation.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <pcl/features/normal_3d_omp.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/gp3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  using Clock = std::chrono::steady_clock;
  const int kThreads = 2;

  double
  cpuSeconds ()
  {
    timespec t;
    clock_gettime (CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double> (t.tv_sec) + 1e-9 * static_cast<double> (t.tv_nsec);
  }

  struct Timing
  {
    double wall = 0.0, cpu = 0.0;
  };

  /// Median wall and CPU seconds of \a repeats runs.
  Timing
  measure (int repeats, const std::function<void ()>& run)
  {
    std::vector<double> wall, cpu;
    for (int r = 0; r < repeats; ++r)
    {
      const double c0 = cpuSeconds ();
      const auto t0 = Clock::now ();
      run ();
      wall.push_back (std::chrono::duration<double> (Clock::now () - t0).count ());
      cpu.push_back (cpuSeconds () - c0);
    }
    std::sort (wall.begin (), wall.end ());
    std::sort (cpu.begin (), cpu.end ());
    return {wall[wall.size () / 2], cpu[cpu.size () / 2]};
  }

  double
  loadAverage ()
  {
    double load[1] = {0.0};
    return getloadavg (load, 1) == 1 ? load[0] : -1.0;
  }

  double
  quantile (std::vector<double> values, double q)
  {
    if (values.empty ())
      return NAN;
    const std::size_t k = std::min (values.size () - 1, static_cast<std::size_t> (q * values.size ()));
    std::nth_element (values.begin (), values.begin () + k, values.end ());
    return values[k];
  }

  /// Angle in degrees between two lines (sign ignored).
  double
  lineAngle (const Eigen::Vector3d& a, const Eigen::Vector3d& b)
  {
    return std::acos (std::min (1.0, std::abs (a.dot (b)))) * 180.0 / M_PI;
  }

  // ---- simulated scans ---------------------------------------------------------------------------------

  struct Simulated
  {
    std::string name;
    ScanCloud scan;
    std::vector<Eigen::Vector3d> truth;  ///< true unit normals, oriented (outward / toward the sensor)
  };

  ScanCloud
  unorganized (const std::vector<Eigen::Vector3d>& points)
  {
    ScanCloud scan;
    scan.positions = points;
    scan.width = static_cast<std::uint32_t> (points.size ());
    scan.height = 1;
    return scan;
  }

  /// count random points on the unit sphere, on the cylinder r = 0.5, h = 2, or on [0, 1]^2, with Gaussian
  /// noise of 0.1 spacings along the normal.
  Simulated
  analytic (const std::string& shape, std::size_t count, std::mt19937& rng)
  {
    std::normal_distribution<double> g (0.0, 1.0);
    std::uniform_real_distribution<double> u (0.0, 1.0);
    const double area = shape == "sphere" ? 4.0 * M_PI : shape == "cylinder" ? 2.0 * M_PI : 1.0;
    const double sigma = 0.1 * std::sqrt (area / count);
    std::vector<Eigen::Vector3d> points, truth;
    for (std::size_t i = 0; i < count; ++i)
    {
      Eigen::Vector3d p, n;
      if (shape == "sphere")
      {
        n = Eigen::Vector3d (g (rng), g (rng), g (rng)).normalized ();
        p = n;
      }
      else if (shape == "cylinder")
      {
        const double a = 2.0 * M_PI * u (rng);
        n = Eigen::Vector3d (std::cos (a), std::sin (a), 0.0);
        p = 0.5 * n + Eigen::Vector3d (0.0, 0.0, 2.0 * u (rng));
      }
      else
      {
        n = Eigen::Vector3d::UnitZ ();
        p = Eigen::Vector3d (u (rng), u (rng), 0.0);
      }
      points.push_back (p + sigma * g (rng) * n);
      truth.push_back (n);
    }
    return {shape + " " + std::to_string (count) + " random, noise 0.1 spacing", unorganized (points), truth};
  }

  /// A 640 x 480 depth camera (f = 525 px, at the origin looking along +z) seeing a ball of radius 0.3 at
  /// depth 1.5 in front of a wall z = 2.5 + 0.3 x; depth noise 0.5 mm x z^2 (a third of a Kinect's: with
  /// the full Kinect noise, 9 mm at 2.5 m for a 4.8 mm pixel, no 5 x 5 or 16-point neighbourhood gives a
  /// normal worth comparing).
  Simulated
  depthCamera (std::mt19937& rng)
  {
    std::normal_distribution<double> g (0.0, 1.0);
    const Eigen::Vector3d centre (0.0, 0.0, 1.5);
    const double radius = 0.3, f = 525.0;
    Simulated s{"depth camera 640 x 480: ball before a slanted wall, noise 0.5 mm z^2", ScanCloud (), {}};
    s.scan.width = 640;
    s.scan.height = 480;
    s.scan.has_sensor_pose = true;
    for (int y = 0; y < 480; ++y)
      for (int x = 0; x < 640; ++x)
      {
        const Eigen::Vector3d ray = Eigen::Vector3d ((x - 319.5) / f, (y - 239.5) / f, 1.0).normalized ();
        const double b = ray.dot (centre), c = centre.squaredNorm () - radius * radius, disc = b * b - c;
        double t;
        Eigen::Vector3d n;
        if (disc > 0.0)
        {
          t = b - std::sqrt (disc);
          n = (t * ray - centre).normalized ();
        }
        else
        {
          t = 2.5 / (ray.z () - 0.3 * ray.x ());  // z = 2.5 + 0.3 x on the ray
          n = Eigen::Vector3d (0.3, 0.0, -1.0).normalized ();
        }
        const double z = t * ray.z ();
        const double noisy = z + 0.0005 * z * z * g (rng);
        s.scan.positions.push_back (ray * (noisy / ray.z ()));
        s.scan.indices.push_back (static_cast<std::size_t> (y) * 640 + x);
        s.truth.push_back (n);
      }
    return s;
  }

  /// Our normals alone: neighbourhoods and PCA, as buildCloudSurface computes them.
  std::vector<Eigen::Vector3d>
  ourNormals (const ScanCloud& scan, int k)
  {
    const std::vector<std::uint8_t> all (scan.size (), 1);
    PointNeighborhoods hoods;
    if (scan.isOrganized ())
    {
      const ScanGrid grid = organizedScanGrid (scan, all);
      const GridEdges edges = classifyGridEdges (grid, scan.positions, 3.0, ShadowRule (), kThreads);
      hoods = gridNeighborhoods (grid, scan.positions, edges, 2, 3.0, kThreads);
    }
    else
    {
      KnnEdgeCounts counts;
      hoods = acceptKnnEdges (scan.positions, findKNearestNeighbors (scan.positions, all, k, kThreads), 3.0, ShadowRule (),
                              counts, kThreads);
    }
    std::vector<Eigen::Vector3d> normals;
    estimatePcaNormals (scan.positions, hoods, all, kThreads, normals);
    return normals;
  }

  /// pcl::NormalEstimationOMP with k neighbours (kd-tree), on float copies of \a points (finite ones only).
  std::vector<Eigen::Vector3d>
  pclNormals (const std::vector<Eigen::Vector3d>& points, int k, const Eigen::Vector3d& offset = Eigen::Vector3d::Zero ())
  {
    auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    for (const auto& p : points)
    {
      const Eigen::Vector3f q = (p + offset).cast<float> ();
      cloud->push_back (pcl::PointXYZ (q.x (), q.y (), q.z ()));
    }
    pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> estimation (kThreads);
    estimation.setInputCloud (cloud);
    estimation.setSearchMethod (pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>> ());
    estimation.setKSearch (k);
    pcl::PointCloud<pcl::Normal> normals;
    estimation.compute (normals);
    std::vector<Eigen::Vector3d> out;
    for (const auto& n : normals)
      out.push_back (n.getNormalVector3fMap ().cast<double> ());
    return out;
  }

  void
  simulatedSection (int repeats)
  {
    std::mt19937 rng (42);
    std::vector<Simulated> scans;
    scans.push_back (analytic ("plane", 100000, rng));
    scans.push_back (analytic ("sphere", 100000, rng));
    scans.push_back (analytic ("cylinder", 100000, rng));
    scans.push_back (depthCamera (rng));
    const int k = CloudSurfaceOptions ().k;
    std::printf ("## 1. Normals on simulated scans (k = %d, %d threads, median of %d runs)\n\n", k, kThreads, repeats);
    std::printf ("Angle to the true normal in degrees, sign ignored (PCL's normals are not oriented); \"wrong "
                 "side\": ours pointing against the true oriented normal. Ours alone = neighbourhoods + PCA; whole "
                 "surface = buildCloudSurface (also noise, outliers, orientation, triangles).\n\n");
    std::printf ("| scan | points | ours alone: s (CPU) | PCL NormalEstimationOMP: s (CPU) | ours median / p95 deg | "
                 "PCL median / p95 deg | whole surface: s (CPU) | ours wrong side | noise estimate / true |\n|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& s : scans)
    {
      std::vector<Eigen::Vector3d> ours, pcl_normals;
      const Timing t_ours = measure (repeats, [&] { ours = ourNormals (s.scan, k); });
      const Timing t_pcl = measure (repeats, [&] { pcl_normals = pclNormals (s.scan.positions, k); });
      CloudSurface surface;
      const Timing t_all = measure (repeats, [&] { surface = buildCloudSurface (s.scan); });
      std::vector<double> e_ours, e_pcl;
      std::size_t wrong = 0;
      for (std::size_t i = 0; i < s.truth.size (); ++i)
      {
        e_ours.push_back (lineAngle (ours[i], s.truth[i]));
        e_pcl.push_back (lineAngle (pcl_normals[i], s.truth[i]));
        wrong += surface.normals[i].dot (s.truth[i]) < 0.0 ? 1 : 0;
      }
      const double true_sigma = s.scan.isOrganized () ? NAN : 0.1 * std::sqrt ((s.name.rfind ("sphere", 0) == 0 ? 4.0 * M_PI : s.name.rfind ("cylinder", 0) == 0 ? 2.0 * M_PI : 1.0) / s.scan.size ());
      std::printf ("| %s | %zu | %.3f (%.3f) | %.3f (%.3f) | %.2f / %.2f | %.2f / %.2f | %.3f (%.3f) | %zu | %.2f |\n",
                   s.name.c_str (), s.scan.size (), t_ours.wall, t_ours.cpu, t_pcl.wall, t_pcl.cpu, quantile (e_ours, 0.5),
                   quantile (e_ours, 0.95), quantile (e_pcl, 0.5), quantile (e_pcl, 0.95), t_all.wall, t_all.cpu, wrong,
                   surface.noise / true_sigma);
    }
    std::printf ("\n");
  }

  // ---- shared scans ------------------------------------------------------------------------------------

  std::size_t
  referenced (const CloudSurface& s)
  {
    std::vector<char> used (s.mesh.vertices.size (), 0);
    for (const auto& t : s.mesh.triangles)
      used[t[0]] = used[t[1]] = used[t[2]] = 1;
    return static_cast<std::size_t> (std::count (used.begin (), used.end (), 1));
  }

  /// Edges with more than two triangles.
  std::size_t
  nonManifoldEdges (const TriangleMesh& mesh)
  {
    const MeshTopology topology = buildMeshTopology (mesh);
    std::size_t count = 0;
    for (std::size_t e = 0; e < topology.numEdges (); ++e)
      count += topology.isNonManifoldEdge (static_cast<int> (e)) ? 1 : 0;
    return count;
  }

  const char*
  neighborhoodName (CloudNeighborhood n)
  {
    return n == CloudNeighborhood::ImageGrid ? "image grid" : n == CloudNeighborhood::LidarRings ? "lidar rings" : "kNN";
  }

  const char*
  orientationName (NormalOrientation o)
  {
    switch (o)
    {
      case NormalOrientation::Viewpoint: return "viewpoint";
      case NormalOrientation::SpanningTree: return "spanning tree";
      case NormalOrientation::ImageGrid: return "image grid";
      case NormalOrientation::Given: return "given";
      default: return "auto";
    }
  }

  std::vector<std::string>
  sharedScans (const std::string& dir)
  {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator (dir))
      if (isScanFileExtension (entry.path ().string ()))
        files.push_back (entry.path ().filename ().string ());
    std::sort (files.begin (), files.end ());
    return files;
  }

  void
  surfaceRow (const std::string& name, const ScanCloud& scan, const CloudSurfaceOptions& options, int repeats)
  {
    CloudSurface s;
    const Timing t = measure (repeats, [&] { s = buildCloudSurface (scan, options); });
    std::printf ("| %s | %zu | %s, %s | %.3f (%.3f) | %zu | %.1f | %zu / %zu | %zu of %zu | %zu | %.3g | %.3g | %zu |\n",
                 name.c_str (), scan.size (), neighborhoodName (s.neighborhood), orientationName (s.orientation), t.wall,
                 t.cpu, s.mesh.triangles.size (), 100.0 * referenced (s) / scan.size (), s.outliers, s.isolated,
                 s.refused_edges, s.candidate_edges, s.folded_triangles, s.spacing, s.noise, nonManifoldEdges (s.mesh));
  }

  void
  sharedSurfaceSection (const std::string& dir, int repeats)
  {
    std::printf ("## 2. buildCloudSurface on the shared scans (defaults, %d threads, median of %d runs)\n\n", kThreads,
                 repeats);
    std::printf ("Scans loaded and cleaned by loadScanCloud (not timed). Spacing and noise in the file's units.\n\n");
    std::printf ("| scan | points | neighbourhood, orientation | s (CPU s) | triangles | %% points in a triangle | "
                 "outliers / isolated | refused edges | folded triangles left out | spacing | noise | edges with > 2 triangles |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& file : sharedScans (dir))
    {
      ScanCloud scan;
      loadScanCloud (dir + "/" + file, scan);
      surfaceRow (file, scan, CloudSurfaceOptions (), repeats);
      if (!scan.isOrganized ())
      {
        CloudSurfaceOptions knn;
        knn.use_lidar_rings = false;
        CloudSurface probe = buildCloudSurface (scan, CloudSurfaceOptions ());
        if (probe.neighborhood == CloudNeighborhood::LidarRings)
          surfaceRow (file + " (use_lidar_rings off)", scan, knn, repeats);
      }
    }
    std::printf ("\n");
  }

  void
  sharedNormalsSection (const std::string& dir, int repeats)
  {
    const int k = CloudSurfaceOptions ().k;
    std::printf ("## 3. Normals on the shared scans: ours (buildCloudSurface) and pcl::NormalEstimationOMP (k = %d)\n\n", k);
    std::printf ("PCL runs on float copies of the same points in the local frame (and, for samp11-utm, in the file's UTM "
                 "frame too, as a PCL user would load it). Angle: between our normal and PCL's, sign ignored.\n\n");
    std::printf ("| scan | points | ours, whole surface: s (CPU) | PCL: s (CPU) | median / p90 angle ours-PCL (deg) |\n"
                 "|---|---|---|---|---|\n");
    for (const auto& file : sharedScans (dir))
    {
      ScanCloud scan;
      loadScanCloud (dir + "/" + file, scan);
      CloudSurface s;
      const Timing t_ours = measure (repeats, [&] { s = buildCloudSurface (scan); });
      const bool utm = file.rfind ("samp11", 0) == 0;
      for (const bool world : utm ? std::vector<bool>{false, true} : std::vector<bool>{false})
      {
        std::vector<Eigen::Vector3d> theirs;
        const Timing t_pcl = measure (repeats, [&] { theirs = pclNormals (scan.positions, k, world ? scan.origin : Eigen::Vector3d::Zero ()); });
        std::vector<double> angles;
        for (std::size_t i = 0; i < scan.size (); ++i)
          if (s.kinds[i] == CloudPointKind::Surface && theirs[i].allFinite ())
            angles.push_back (lineAngle (s.normals[i], theirs[i]));
        std::printf ("| %s%s | %zu | %.3f (%.3f) | %.3f (%.3f) | %.2f / %.2f |\n", file.c_str (),
                     world ? " (PCL in UTM coordinates)" : "", scan.size (), t_ours.wall, t_ours.cpu, t_pcl.wall, t_pcl.cpu,
                     quantile (angles, 0.5), quantile (angles, 0.9));
      }
    }
    std::printf ("\n");
  }

  void
  bunnySection (const std::string& clouds, const std::string& meshes)
  {
    const std::string mesh_path = meshes + "/stanford-bunny.obj", scan_path = clouds + "/bun000.ply";
    if (!std::filesystem::exists (mesh_path) || !std::filesystem::exists (scan_path))
      return;
    ScanCloud scan;
    loadScanCloud (scan_path, scan);
    const CloudSurface s = buildCloudSurface (scan);
    const std::vector<Eigen::Vector3d> theirs = pclNormals (scan.positions, CloudSurfaceOptions ().k);
    const TriangleMesh mesh = loadTriangleMesh (mesh_path);
    const std::vector<Eigen::Vector3d> reference = computeVertexNormals (mesh, buildMeshTopology (mesh));
    auto vertices = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    for (const auto& v : mesh.vertices)
      vertices->push_back (pcl::PointXYZ (v.x (), v.y (), v.z ()));
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud (vertices);
    std::vector<double> ours, pcl_angles;
    std::size_t flipped = 0;
    pcl::Indices nearest (1);
    std::vector<float> squared (1);
    for (std::size_t i = 0; i < scan.size (); ++i)
    {
      if (s.kinds[i] != CloudPointKind::Surface)
        continue;
      const Eigen::Vector3d p = scan.worldPosition (i);
      tree.nearestKSearch (pcl::PointXYZ (p.x (), p.y (), p.z ()), 1, nearest, squared);
      const Eigen::Vector3d& r = reference[nearest[0]];
      ours.push_back (lineAngle (s.normals[i], r));
      pcl_angles.push_back (lineAngle (theirs[i], r));
      flipped += s.normals[i].dot (r) < 0.0 ? 1 : 0;
    }
    std::printf ("## 4. bun000.ply against stanford-bunny.obj (the zippered mesh of all ten scans, same frame)\n\n");
    std::printf ("Angle between each point's normal and the area-weighted normal of the nearest mesh vertex (sign ignored), "
                 "degrees; the mesh is smoother than one scan, so this is an upper bound of the error.\n\n");
    std::printf ("| normals | median | p90 | p99 | oriented against the mesh |\n|---|---|---|---|---|\n");
    std::printf ("| ours (5 x 5 image window, image-grid orientation) | %.2f | %.2f | %.2f | %zu of %zu |\n", quantile (ours, 0.5),
                 quantile (ours, 0.9), quantile (ours, 0.99), flipped, ours.size ());
    std::printf ("| pcl::NormalEstimationOMP, k = %d | %.2f | %.2f | %.2f | (not oriented) |\n\n", CloudSurfaceOptions ().k,
                 quantile (pcl_angles, 0.5), quantile (pcl_angles, 0.9), quantile (pcl_angles, 0.99));
  }
} // namespace

namespace
{
  // ---- triangles: ours against GP3 ---------------------------------------------------------------------

  struct Triangles
  {
    std::vector<Eigen::Vector3i> triangles;
    Timing time;
  };

  /// GP3 on the surface points with our oriented normals; radius 3 spacings (our gap rule), mu 2.5,
  /// k neighbours, PCL's usual angles. Sequential (PCL's GP3 has no threads).
  Triangles
  gp3 (const ScanCloud& scan, const CloudSurface& s, int neighbours, int repeats)
  {
    auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointNormal>> ();
    std::vector<int> original;
    for (std::size_t i = 0; i < scan.size (); ++i)
      if (s.kinds[i] == CloudPointKind::Surface)
      {
        pcl::PointNormal p;
        p.getVector3fMap () = scan.positions[i].cast<float> ();
        p.getNormalVector3fMap () = s.normals[i].cast<float> ();
        cloud->push_back (p);
        original.push_back (static_cast<int> (i));
      }
    Triangles out;
    pcl::PolygonMesh polygons;
    out.time = measure (repeats, [&] {
      pcl::GreedyProjectionTriangulation<pcl::PointNormal> gp3;
      gp3.setSearchRadius (3.0 * s.spacing);
      gp3.setMu (2.5);
      gp3.setMaximumNearestNeighbors (neighbours);
      gp3.setMaximumSurfaceAngle (M_PI / 4);
      gp3.setMinimumAngle (M_PI / 18);
      gp3.setMaximumAngle (2 * M_PI / 3);
      gp3.setNormalConsistency (true);
      gp3.setInputCloud (cloud);
      gp3.setSearchMethod (pcl::make_shared<pcl::search::KdTree<pcl::PointNormal>> ());
      gp3.reconstruct (polygons);
    });
    for (const auto& v : polygons.polygons)
      if (v.vertices.size () == 3)
        out.triangles.emplace_back (original[v.vertices[0]], original[v.vertices[1]], original[v.vertices[2]]);
    return out;
  }

  void
  triangleRow (const std::string& name, const std::string& method, const ScanCloud& scan, const Triangles& t)
  {
    CloudSurface as_surface;
    as_surface.mesh.vertices = scan.positions;
    as_surface.mesh.triangles = t.triangles;
    std::printf ("| %s | %s | %.3f (%.3f) | %zu | %.1f | %zu |\n", name.c_str (), method.c_str (), t.time.wall, t.time.cpu,
                 t.triangles.size (), 100.0 * referenced (as_surface) / scan.size (), nonManifoldEdges (as_surface.mesh));
  }

  void
  trianglesSection (const std::string& dir, int repeats)
  {
    std::printf ("## 5. Triangles of unorganized scans: our local Delaunay fans and pcl::GreedyProjectionTriangulation\n\n");
    std::printf ("Both on the same points and oriented normals (buildCloudSurface's; outliers left out). Ours: "
                 "triangulateTangentFans + fillSmallHoles on the symmetric kNN neighbourhoods, %d threads; GP3: search radius "
                 "3 spacings, mu 2.5, k neighbours, 45 degrees surface angle, 10-120 degrees triangle angles, 1 thread (it has "
                 "no other).\n\n", kThreads);
    std::printf ("| scan | method | s (CPU s) | triangles | %% points in a triangle | edges with > 2 triangles |\n"
                 "|---|---|---|---|---|---|\n");
    std::mt19937 rng (7);
    std::vector<std::pair<std::string, ScanCloud>> scans;
    scans.emplace_back ("sphere 20000 random", analytic ("sphere", 20000, rng).scan);
    for (const char* file : {"lamppost.pcd", "milk_color.pcd", "samp11-utm.pcd", "fast_gicp_251370668.pcd"})
      if (std::filesystem::exists (dir + "/" + file))
      {
        ScanCloud scan;
        loadScanCloud (dir + "/" + file, scan);
        scans.emplace_back (file, scan);
      }
    const int k = CloudSurfaceOptions ().k;
    bool gp3_repeatable = true;
    for (const auto& [name, scan] : scans)
    {
      CloudSurfaceOptions options;
      options.use_lidar_rings = false;
      const CloudSurface s = buildCloudSurface (scan, options);
      std::vector<std::uint8_t> usable (scan.size ());
      for (std::size_t i = 0; i < scan.size (); ++i)
        usable[i] = s.kinds[i] == CloudPointKind::Surface ? 1 : 0;
      KnnEdgeCounts counts;
      const PointNeighborhoods hoods = symmetricNeighborhoods (
        acceptKnnEdges (scan.positions, findKNearestNeighbors (scan.positions, usable, k, kThreads), options.gap_factor,
                        ShadowRule (), counts, kThreads), kThreads);
      Triangles ours;
      ours.time = measure (repeats, [&] {
        ours.triangles = triangulateTangentFans (scan.positions, hoods, s.normals, usable, options.gap_factor, ShadowRule (), kThreads);
        fillSmallHoles (scan.positions, s.normals, hoods.spacing, options.gap_factor, 12, ours.triangles);
      });
      triangleRow (name, "ours", scan, ours);
      for (const int neighbours : {k, 100})
      {
        const Triangles theirs = gp3 (scan, s, neighbours, 1), again = gp3 (scan, s, neighbours, 1);
        gp3_repeatable = gp3_repeatable && theirs.triangles == again.triangles;
        triangleRow (name, "GP3, " + std::to_string (neighbours) + " neighbours", scan, theirs);
      }
    }
    std::printf ("\nGP3 twice in a row: %s.\n\n", gp3_repeatable ? "identical triangles every time" : "different triangles");
  }
} // namespace

static int
run (int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf (stderr, "usage: %s CLOUDS_DIR [MESHES_DIR] [REPEATS]\n", argv[0]);
    return 2;
  }
  const std::string clouds = argv[1], meshes = argc > 2 ? argv[2] : "";
  const int repeats = argc > 3 ? std::max (1, std::atoi (argv[3])) : 5;
  std::printf ("# Cloud surface benchmark\n\nGenerated by bench/cloud_surface.sh (bench/bench_cloud_surface.cpp), Release "
               "build, %d OpenMP threads, OMP_WAIT_POLICY=%s. The machine is shared: 1-minute load average %.1f at the "
               "start, so wall times include waiting for a core; CPU seconds (all threads) do not (with a passive wait "
               "policy, threads sleep at barriers instead of spinning).\n\n", kThreads,
               std::getenv ("OMP_WAIT_POLICY") ? std::getenv ("OMP_WAIT_POLICY") : "(default)", loadAverage ());
  simulatedSection (repeats);
  sharedSurfaceSection (clouds, repeats);
  sharedNormalsSection (clouds, repeats);
  bunnySection (clouds, meshes);
  trianglesSection (clouds, repeats);
  std::printf ("1-minute load average at the end: %.1f\n", loadAverage ());
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
