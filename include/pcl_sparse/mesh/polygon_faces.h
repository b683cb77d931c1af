#pragma once
/// \file polygon_faces.h
/// \brief Triangles from PCL's polygons (pcl::Vertices, as pcl::PolygonMesh holds them).

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/Vertices.h>

#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief The triangles of \a polygons: each polygon with k corners is fanned into k - 2 triangles
  /// (corner 0 with every following pair), in polygon order.
  /// \param[in] polygons the faces, point indices of each
  /// \param[in] num_points number of points the indices refer to
  /// \param[in] what names the input in error messages (e.g. "PolygonMesh")
  /// \return the triangles
  /// Throws pcl_sparse::Error for a polygon with fewer than 3 corners or an index out of range.
  std::vector<Eigen::Vector3i>
  trianglesFromPolygons (const std::vector<pcl::Vertices>& polygons, std::size_t num_points, const std::string& what);
} // namespace pcl_sparse
