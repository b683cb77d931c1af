#pragma once
/// \file element_holders.h
/// How many patches of a partition hold each vertex and each face: what redundantPatches and
/// mergeSmallPatches weigh to tell what a patch holds alone. In a tile, what another tile answers for
/// counts as always held.

#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Holder counts of a partition.
  struct ElementHolders
  {
    std::vector<int> vertices;  ///< per vertex, the patches holding it
    std::vector<int> faces;     ///< per face, the patches holding it (Patch::triangles)

    /// A patch of the partition dropped: its vertices and faces lose a holder.
    void
    release (const Patch& patch)
    {
      for (int v : patch.vertices)
        --vertices[v];
      for (int f : patch.triangles)
        --faces[f];
    }
  };

  /// \brief Counts the patches holding each vertex and face.
  /// \param[in] mesh           the mesh the patches grew on
  /// \param[in] patches        the partition
  /// \param[in] seed_vertices  a tile's core: per vertex, nonzero where this partition answers for it; the
  ///                           others, and faces with no such corner, start at a count no partition reaches
  ///                           (always held). Empty: every vertex.
  ElementHolders
  countElementHolders (const TriangleMesh& mesh, const std::vector<Patch>& patches,
                       const std::vector<std::uint8_t>& seed_vertices = {});
} // namespace pcl_sparse
