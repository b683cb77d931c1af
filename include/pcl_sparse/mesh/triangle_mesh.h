#pragma once
/// \file triangle_mesh.h
/// The library's own compact triangle mesh: plain arrays, no topology (see mesh_topology.h).

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace pcl_sparse
{
  /// An indexed triangle mesh.
  ///   vertices   #V positions (double precision: the geometry stages fit quadrics in local frames)
  ///   triangles  #F triples of vertex indices, counter-clockwise seen from outside
  struct TriangleMesh
  {
    using Ptr = std::shared_ptr<TriangleMesh>;
    using ConstPtr = std::shared_ptr<const TriangleMesh>;

    std::vector<Eigen::Vector3d> vertices;
    std::vector<Eigen::Vector3i> triangles;

    std::size_t numVertices () const { return vertices.size (); }
    std::size_t numTriangles () const { return triangles.size (); }
    bool empty () const { return triangles.empty (); }
  };
} // namespace pcl_sparse
