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
  /// A PolygonMesh with an x y z float cloud (width = #V, height = 1, dense) and one 3-index polygon per
  /// triangle. Coordinates are rounded to float, PCL's precision.
  pcl::PolygonMesh
  toPolygonMesh (const TriangleMesh& mesh);

  /// A TriangleMesh from a PolygonMesh whose cloud has x, y, z fields of any numeric type (values are read
  /// at their own precision); polygons with more than 3 vertices are fan-triangulated. Throws
  /// pcl_sparse::Error if x/y/z are missing, the cloud data is shorter than its header says, a polygon has
  /// fewer than 3 vertices or an index is out of range.
  TriangleMesh
  fromPolygonMesh (const pcl::PolygonMesh& polygon_mesh);

  /// The x, y, z fields of every point of \a cloud (any numeric field type, read at its own precision), in
  /// storage order. Throws pcl_sparse::Error naming \a what if a field is missing or the data is shorter than
  /// width, height and row_step say.
  std::vector<Eigen::Vector3d>
  positionsFromCloud (const pcl::PCLPointCloud2& cloud, const std::string& what = "PolygonMesh");

  /// The vertices of \a mesh as a cloud (float precision, unorganised); is_dense is false when any vertex
  /// is not finite.
  pcl::PointCloud<pcl::PointXYZ>
  verticesToCloud (const TriangleMesh& mesh);

  /// loadTriangleMesh (path, options) followed by toPolygonMesh: the same formats and the same errors.
  void
  loadPolygonMesh (const std::string& path, pcl::PolygonMesh& polygon_mesh, const MeshLoadOptions& options = MeshLoadOptions ());
} // namespace pcl_sparse
