#pragma once
/// \file triangle_mesh.h
/// The library's own compact triangle mesh: plain arrays, no topology (see mesh_topology.h).

#include <Eigen/Core>

#include <memory>
#include <vector>

/// \namespace pcl_sparse
/// The feature-aware sparse mesh representation of Fuentes Perez et al. (Pacific Graphics 2020) in the
/// style of PCL: stages as classes with setters and compute (), the mathematics as free functions.
/// docs/METHOD.md describes the method step by step.
namespace pcl_sparse
{
  /// An indexed triangle mesh: plain arrays of vertex positions and corner indices.
  struct TriangleMesh
  {
    using Ptr = std::shared_ptr<TriangleMesh>;
    using ConstPtr = std::shared_ptr<const TriangleMesh>;

    /// #V positions (double precision: the geometry stages fit quadrics in local frames).
    std::vector<Eigen::Vector3d> vertices;
    /// #F triples of vertex indices, counter-clockwise seen from outside.
    std::vector<Eigen::Vector3i> triangles;

    /// Number of vertices, #V.
    std::size_t numVertices () const { return vertices.size (); }
    /// Number of triangles, #F.
    std::size_t numTriangles () const { return triangles.size (); }
    /// True when the mesh has no triangle (it may still have vertices).
    bool empty () const { return triangles.empty (); }
  };
} // namespace pcl_sparse
