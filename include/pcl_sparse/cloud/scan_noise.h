#pragma once
/// \file scan_noise.h
/// The noise level of a scan, so that noise is not taken for detail: a robust estimate of the standard
/// deviation of the points along the surface normal, in the scan's units.
///
/// Why leave-one-out quadric residuals: the residual of a plane fit also measures the curvature (on a
/// sphere of radius R sampled at spacing h it is about h^2 / R, noise or not); a height quadric absorbs
/// the curvature, and predicting each point from its neighbours alone, divided by sqrt (1 + leverage),
/// gives residuals whose spread is exactly the noise's for any neighbourhood layout.

#include <pcl_sparse/cloud/point_neighborhoods.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Median over points of |r_i| / sqrt (1 + h_i) / 0.6745 (the median absolute value of a normal
  /// deviate), where r_i is the height of point i above the least-squares height quadric of its
  /// neighbours in the tangent frame of its normal, and h_i that prediction's leverage. Points are taken
  /// with a deterministic stride so that at most \a max_samples are used; a point counts when it is
  /// usable, has a normal, and has at least 7 usable neighbours. 0 when no point counts.
  double
  estimateScanNoise (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                     const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                     int num_threads, std::size_t max_samples = 20000);
} // namespace pcl_sparse
