#pragma once
// Holes in a resampled cloud, measured as bench/bench_meshes does: probes uniform by area on the mesh, the
// distance from each to its nearest cloud point in spacings sqrt(area / #points).

#include "generated_clouds.h"

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pcl_sparse_test
{
  /// Distances from \a probes points drawn uniformly by area on \a mesh (seed \a seed) to their nearest
  /// point of \a cloud, in spacings, ascending.
  inline std::vector<double>
  probeGapsInSpacings (const pcl_sparse::TriangleMesh& mesh, const pcl::PointCloud<pcl::PointNormal>& cloud,
                       std::size_t probes = 20000, std::uint64_t seed = 1)
  {
    double area = 0.0;
    const std::vector<Eigen::Vector3d> points = sampleSurface (mesh, probes, seed, area);
    const double spacing = std::sqrt (area / static_cast<double> (cloud.size ()));
    pcl::PointCloud<pcl::PointXYZ>::Ptr xyz (new pcl::PointCloud<pcl::PointXYZ>);
    for (const auto& p : cloud)
      xyz->push_back (pcl::PointXYZ (p.x, p.y, p.z));
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud (xyz);
    std::vector<double> gaps;
    std::vector<int> index (1);
    std::vector<float> squared (1);
    for (const Eigen::Vector3d& q : points)
    {
      tree.nearestKSearch (pcl::PointXYZ (q.x (), q.y (), q.z ()), 1, index, squared);
      gaps.push_back ((q - xyz->points[index[0]].getVector3fMap ().cast<double> ()).norm () / spacing);
    }
    std::sort (gaps.begin (), gaps.end ());
    return gaps;
  }

  /// The 99th percentile of ascending \a gaps.
  inline double
  percentile99 (const std::vector<double>& gaps)
  {
    return gaps[static_cast<std::size_t> (std::ceil (0.99 * gaps.size ())) - 1];
  }
} // namespace pcl_sparse_test
