#pragma once
/// \file non_manifold_split.h
/// Cutting a mesh along its non-manifold edges and vertices, so that patches never cross them
/// (docs/METHOD.md step 1).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

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
  /// \param[in]  mesh         the input
  /// \param[in]  topology     its topology
  /// \param[out] split        the split mesh and the map to input vertices
  /// \param[in]  num_threads  OpenMP threads (0: all); the split does not depend on it
  /// \return false (and \a split untouched) when every vertex has at most one umbrella
  bool
  splitNonManifoldVertices (const TriangleMesh& mesh, const MeshTopology& topology, NonManifoldSplit& split,
                            int num_threads = 0);

  /// Per-vertex vectors of the input (a scan's normals) on the split mesh: each copy takes its original's.
  /// \param[in] split   the split
  /// \param[in] values  #V_input values, or empty
  /// \return #V_split values (empty for empty \a values)
  std::vector<Eigen::Vector3d>
  valuesOnSplit (const NonManifoldSplit& split, const std::vector<Eigen::Vector3d>& values);
} // namespace pcl_sparse
