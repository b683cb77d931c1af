#pragma once
/// \file polygon_mesh_conversion.h
/// Between the library's TriangleMesh and PCL's pcl::PolygonMesh (kept apart from mesh_io.h so that PCL's
/// heavy headers are only compiled where they are used).

#include <pcl_sparse/io/mesh_io.h>

#include <pcl/PolygonMesh.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Converts a mesh to PCL's mesh type. Coordinates are rounded to float, PCL's precision.
  /// \param[in] mesh  the mesh
  /// \return an x y z float cloud (width = #V, height = 1, dense) and one 3-index polygon per triangle
  pcl::PolygonMesh
  toPolygonMesh (const TriangleMesh& mesh);

  /// Converts PCL's mesh type to a TriangleMesh; polygons with more than 3 vertices are fan-triangulated.
  /// \param[in] polygon_mesh  a mesh whose cloud has x, y, z fields of any numeric type (read at their own
  ///                          precision)
  /// \return the triangle mesh
  /// \throws pcl_sparse::Error if x/y/z are missing, the cloud data is shorter than its header says, a
  ///         polygon has fewer than 3 vertices or an index is out of range
  TriangleMesh
  fromPolygonMesh (const pcl::PolygonMesh& polygon_mesh);

  /// The x, y, z fields of every point of a PCLPointCloud2, in storage order.
  /// \param[in] cloud  the cloud (x, y, z of any numeric type, read at its own precision)
  /// \param[in] what   names the cloud in error messages
  /// \return the positions
  /// \throws pcl_sparse::Error naming \a what if a field is missing or the data is shorter than width,
  ///         height and row_step say
  std::vector<Eigen::Vector3d>
  positionsFromCloud (const pcl::PCLPointCloud2& cloud, const std::string& what = "PolygonMesh");

  /// The vertices of a mesh as a point cloud.
  /// \param[in] mesh  the mesh
  /// \return the vertices at float precision, unorganised; is_dense is false when any vertex is not finite
  pcl::PointCloud<pcl::PointXYZ>
  verticesToCloud (const TriangleMesh& mesh);

  /// loadTriangleMesh followed by toPolygonMesh: the same formats and the same errors.
  /// \param[in]  path          the file
  /// \param[out] polygon_mesh  the mesh
  /// \param[in]  options       as for loadTriangleMesh
  /// \throws pcl_sparse::Error as loadTriangleMesh
  void
  loadPolygonMesh (const std::string& path, pcl::PolygonMesh& polygon_mesh, const MeshLoadOptions& options = MeshLoadOptions ());
} // namespace pcl_sparse
