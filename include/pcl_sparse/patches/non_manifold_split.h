#pragma once
/// \file non_manifold_split.h
/// Cutting a mesh along its non-manifold edges and vertices, so that patches never cross them
/// (docs/METHOD.md step 1).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// A mesh whose vertices were split into one copy per umbrella (fan of incident faces connected across
  /// manifold edges). Faces keep their index; vertex v keeps index v for its first umbrella (lowest face),
  /// further copies are appended.
  struct NonManifoldSplit
  {
    TriangleMesh mesh;          ///< the split mesh
    std::vector<int> original;  ///< #V_split: input index of each vertex (identity on the first #V_input)
  };

  /// Splits the vertices that have more than one umbrella (non-manifold edges and vertices, "bow ties").
  /// Degenerate faces (a repeated corner, zero or non-finite area) belong to no umbrella of their own:
  /// they stay with the vertex's first umbrella.
  /// \param[in]  mesh      the input
  /// \param[in]  topology  its topology
  /// \param[out] split     the split mesh and the map to input vertices
  /// \return false (and \a split untouched) when every vertex has at most one umbrella
  bool
  splitNonManifoldVertices (const TriangleMesh& mesh, const MeshTopology& topology, NonManifoldSplit& split);
} // namespace pcl_sparse
