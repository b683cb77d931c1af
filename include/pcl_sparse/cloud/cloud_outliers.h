#pragma once
/// \file cloud_outliers.h
/// Outliers: points far from every local surface, so that they neither pull patches nor enter triangles.
///
/// Why the tangent plane of every neighbour and not one plane fit: at a sharp edge or corner a point lies
/// on the planes of the neighbours of its own face, while a plane fitted across the edge misses it by
/// about a spacing; a stray point is far from all of them.

#include <pcl_sparse/cloud/point_neighborhoods.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Flags the usable points whose distance |(p_i - p_j) . n_j| to the tangent plane of every usable
  /// neighbour j with a normal exceeds max (noise_factor x noise, spacing_factor x spacing_j) (the
  /// neighbour's spacing: a stray point's own is large, its neighbours being far). Points with no such
  /// neighbour are not flagged (they are isolated, not outliers). When \a only is given, its points are
  /// tested (usable or not) instead of the usable ones.
  ///   returns  #P flags, 1 for an outlier
  std::vector<std::uint8_t>
  findCloudOutliers (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                     const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                     double noise, double noise_factor, double spacing_factor, int num_threads,
                     const std::vector<int>* only = nullptr);
} // namespace pcl_sparse
