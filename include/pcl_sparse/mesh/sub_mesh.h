#pragma once
/// \file sub_mesh.h
/// \brief The part of a mesh on a subset of its vertices (what setIndices selects in the surface stages).

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief The vertices listed in \a indices, in that order, and the faces whose three corners are all
  /// listed, renumbered to positions in \a indices.
  /// \param[in] mesh the whole mesh
  /// \param[in] indices vertex indices of \a mesh, each at most once
  /// \param[in] what names the caller in error messages ("what: index 7 out of range ...")
  /// \return the sub-mesh: vertex i is mesh.vertices[indices[i]]
  /// Throws pcl_sparse::Error for an index out of range or listed twice.
  TriangleMesh
  extractSubMesh (const TriangleMesh& mesh, const std::vector<int>& indices, const std::string& what);
} // namespace pcl_sparse
