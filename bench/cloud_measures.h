#pragma once
/// \file cloud_measures.h
/// Measures of a resampled cloud against the scan it came from, as bench/results/scans.md defines them, for
/// every bench that reports them: each input point's local spacing, and the completeness.

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace pcl_sparse_bench
{
  /// \brief Mean distance of each point of \a points to its 6 nearest others.
  /// \param[in] points the points
  /// \param[in] tree   a tree over \a points
  inline std::vector<float>
  localSpacings (const pcl::PointCloud<pcl::PointXYZ>& points, const pcl::KdTreeFLANN<pcl::PointXYZ>& tree)
  {
    std::vector<float> spacing (points.size ());
    std::vector<int> k_indices;
    std::vector<float> k_squared;
    for (std::size_t i = 0; i < points.size (); ++i)
    {
      const int found = tree.nearestKSearch (points[i], 7, k_indices, k_squared);
      double sum = 0.0;
      for (int k = 1; k < found; ++k)
        sum += std::sqrt (k_squared[k]);
      spacing[i] = static_cast<float> (found > 1 ? sum / (found - 1) : 0.0);
    }
    return spacing;
  }

  /// \brief Completeness: the fraction of the input points (every \a stride-th) with an output point within 3
  /// of their local spacings.
  /// \param[in] input   the input points
  /// \param[in] spacing their local spacings (localSpacings)
  /// \param[in] output  a tree over the output points
  /// \param[in] stride  every how many input points to measure (1: all)
  /// \return the fraction (NaN without input points)
  inline double
  completeness (const pcl::PointCloud<pcl::PointXYZ>& input, const std::vector<float>& spacing,
                const pcl::KdTreeFLANN<pcl::PointXYZ>& output, std::size_t stride = 1)
  {
    std::vector<int> k_indices;
    std::vector<float> k_squared;
    std::size_t covered = 0, n = 0;
    for (std::size_t i = 0; i < input.size (); i += stride, ++n)
      if (output.nearestKSearch (input[i], 1, k_indices, k_squared) == 1 && std::sqrt (k_squared[0]) <= 3.0f * spacing[i])
        ++covered;
    return n > 0 ? static_cast<double> (covered) / static_cast<double> (n) : std::numeric_limits<double>::quiet_NaN ();
  }
} // namespace pcl_sparse_bench
