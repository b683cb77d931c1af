#pragma once
/// \file morton_order.h
/// Points sorted along a Morton (Z-order) curve over their bounding box: neighbours in the order are
/// mostly neighbours in space. Harris 3D processes vertices in this order (cache locality); the encoder
/// orders its patches so (the file codes each seed as a small step from the previous one).

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// \brief The indices \a indices of \a points, sorted by the Morton code of their point (21 bits per axis
  /// over the bounding box of the finite ones), ties by index; repeated indices appear once.
  /// Non-finite points take code 0. O(n log n).
  /// \param[in] points   the points
  /// \param[in] indices  which of them (each < points.size ())
  std::vector<int>
  mortonOrder (const std::vector<Eigen::Vector3d>& points, std::vector<int> indices);

  /// \brief mortonOrder over every point: 0 .. points.size () - 1 sorted.
  std::vector<int>
  mortonOrder (const std::vector<Eigen::Vector3d>& points);
} // namespace pcl_sparse
