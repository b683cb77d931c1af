// Cloud quality for bench/meshes.sh (issue 13 point 5): how completely a resampled cloud covers its mesh and
// how many of its normals are flipped, printed as one JSON object.
//
//   bench_meshes MESH CLOUD.pcd [-probes N] [-seed S]
//
// Completeness: N probes (default max(200000, #points)) drawn uniformly by area on the mesh (seeded, so the
// result is deterministic); each probe's distance to the nearest cloud point (kd-tree), in units of the
// spacing sqrt(mesh area / #points). Prints the 50th, 99th, 99.9th percentile and the largest of these
// distances, and the fraction of probes within 3 spacings.
// Flipped normals: pcl_sparse::evaluateCloudQuality (angle to the nearest face's normal over 120 degrees),
// with its own completeness (50k probes, 3 spacings) for reference.
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/resampling/cloud_quality.h>

#include "generated_clouds.h"

#include <pcl/kdtree/kdtree_flann.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

using namespace pcl_sparse;
using pcl_sparse_test::sampleSurface;

namespace
{
  double
  percentile (std::vector<double> sorted, double q)
  {
    std::sort (sorted.begin (), sorted.end ());
    const std::size_t i = std::min (sorted.size () - 1, static_cast<std::size_t> (std::ceil (q * sorted.size ())) - 1);
    return sorted[i];
  }
} // namespace

int
main (int argc, char** argv)
{
  if (argc < 3)
  {
    std::fprintf (stderr, "usage: %s MESH CLOUD.pcd [-probes N] [-seed S]\n", argv[0]);
    return 2;
  }
  try
  {
    std::size_t probes_wanted = 0;
    std::uint64_t seed = 1;
    for (int i = 3; i + 1 < argc; i += 2)
    {
      const std::string a = argv[i];
      if (a == "-probes")
        probes_wanted = std::stoul (argv[i + 1]);
      else if (a == "-seed")
        seed = std::stoull (argv[i + 1]);
    }
    const TriangleMesh mesh = loadTriangleMesh (argv[1]);
    // loadScanCloud reads the double x y z that pcl_sparse_resample writes for meshes far from the origin
    // (pcl::io::loadPCDFile into PointNormal leaves them 0). The kd-tree holds float positions relative to
    // the mesh's first vertex.
    ScanCloud scan;
    loadScanCloud (argv[2], scan);
    const Eigen::Vector3d centre = mesh.vertices.empty () ? Eigen::Vector3d::Zero () : mesh.vertices.front ();
    pcl::PointCloud<pcl::PointNormal>::Ptr cloud (new pcl::PointCloud<pcl::PointNormal>);
    pcl::PointCloud<pcl::PointXYZ>::Ptr xyz (new pcl::PointCloud<pcl::PointXYZ>);
    for (std::size_t i = 0; i < scan.positions.size (); ++i)
    {
      const Eigen::Vector3d p = scan.origin + scan.positions[i];
      const Eigen::Vector3d n = scan.normals.empty () ? Eigen::Vector3d (NAN, NAN, NAN) : scan.normals[i];
      pcl::PointNormal q;
      q.getVector3fMap () = p.cast<float> ();
      q.getNormalVector3fMap () = n.cast<float> ();
      cloud->push_back (q);
      if (p.allFinite ())
        xyz->push_back (pcl::PointXYZ ((p - centre).x (), (p - centre).y (), (p - centre).z ()));
    }
    const std::size_t points = cloud->size ();
    const std::size_t n = probes_wanted > 0 ? probes_wanted : std::max<std::size_t> (200000, points);
    double area = 0.0;
    const std::vector<Eigen::Vector3d> probes = sampleSurface (mesh, n, seed, area);
    const double spacing = std::sqrt (area / static_cast<double> (points));

    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud (xyz);
    std::vector<double> gaps (probes.size ());
    std::size_t within3 = 0;
#pragma omp parallel for reduction(+ : within3) schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (probes.size ()); ++i)
    {
      std::vector<int> index (1);
      std::vector<float> squared (1);
      const Eigen::Vector3d q = probes[i] - centre;
      tree.nearestKSearch (pcl::PointXYZ (q.x (), q.y (), q.z ()), 1, index, squared);
      gaps[i] = (q - xyz->points[index[0]].getVector3fMap ().cast<double> ()).norm () / spacing;
      within3 += gaps[i] <= 3.0 ? 1 : 0;
    }

    const CloudQuality quality = evaluateCloudQuality (mesh, *cloud);
    const std::size_t valid = points - quality.invalid;
    std::printf ("{\"points\": %zu, \"probes\": %zu, \"spacing\": %.9g, \"p50_spacings\": %.6g, \"p99_spacings\": %.6g, "
                 "\"p999_spacings\": %.6g, \"max_spacings\": %.6g, \"completeness3\": %.6f, \"flipped\": %zu, "
                 "\"flipped_fraction\": %.6g, \"invalid\": %zu, \"quality_completeness\": %.6f, "
                 "\"mean_normal_angle\": %.4f, \"mean_distance_over_diag\": %.6g}\n",
                 points, probes.size (), spacing, percentile (gaps, 0.5), percentile (gaps, 0.99), percentile (gaps, 0.999),
                 *std::max_element (gaps.begin (), gaps.end ()), static_cast<double> (within3) / probes.size (),
                 quality.flipped, static_cast<double> (quality.flipped) / std::max<std::size_t> (1, valid), quality.invalid,
                 quality.completeness, quality.mean_normal_angle, quality.mean_distance / quality.bbox_diagonal);
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "bench_meshes: " << e.what () << "\n";
    return 1;
  }
}
