#pragma once
/// \file point_triangle_distance.h
/// The exact distance from a point to a triangle.

#include <Eigen/Core>

namespace pcl_sparse
{
  /// Exact distance from a point to a triangle (Ericson's closest point on a triangle).
  /// \param[in] p        the point
  /// \param[in] a, b, c  the triangle's corners
  /// \return the distance
  double
  pointTriangleDistance (const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);
} // namespace pcl_sparse
