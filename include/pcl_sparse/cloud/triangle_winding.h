#pragma once
/// \file triangle_winding.h
/// Winding triangles like the point normals: the mesh stages orient patch frames from face normals.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// Reverses each triangle whose geometric normal points against the sum of its corners' normals.
  ///   returns  the number of triangles reversed
  std::size_t
  windTrianglesLikeNormals (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
                            std::vector<Eigen::Vector3i>& triangles);

  /// The side image-grid triangles face relative to the point normals: +1 if most agree with their corners'
  /// normals as wound, -1 if most disagree.
  double
  imageFacing (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
               const std::vector<Eigen::Vector3i>& triangles);

  /// Triangles of an image grid (triangulateImageGrid) all face the same side of the sensor, so they are
  /// wound as one: all reversed if most point against their corners' normals, then those that still do
  /// are removed (a noise spike or a surface seen edge-on; reversing one alone would break the
  /// consistent winding of its neighbours).
  ///   returns  the number of triangles removed
  std::size_t
  windImageTrianglesLikeNormals (const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<Eigen::Vector3d>& normals, std::vector<Eigen::Vector3i>& triangles);
} // namespace pcl_sparse
