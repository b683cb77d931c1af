#pragma once
/// \file redundant_patches.h
/// Redundant patches (ours, issue 13): a patch every vertex and triangle of which other patches also hold
/// adds nothing to coverage, yet costs its seed, frame, radius and footprint in the model (120-135 bits a patch
/// in the default files of spot, sword and kitten-53k, as much as its atoms). The sampling loop keeps a patch
/// when it covers some vertex not covered yet, but the patches grown after it often cover all of it again:
/// with default options up to 27 % of the patches of the shared meshes end up redundant (spot 384 of 1426).
///
/// One pass over the patches from the last to the first (the first were grown from the strongest feature
/// responses and are kept in preference): a patch is dropped when each of its vertices and triangles is
/// still held by another patch not dropped. Every vertex and triangle some patch held (in a tile: of its
/// core) is still held by one, and every patch kept holds something no other kept patch holds (it did when it
/// was kept, and drops only lower the counts). Patches beside a face no patch holds (Patch::beside_uncovered_face) are kept: their
/// unclipped footprints are what covers that face. In a tile only the tile's core counts: the margin is
/// the neighbouring tile's to cover, as the sampling's own target. O(V + F + sum of patch sizes).
///
/// Measured (bench/results/redundant_patches.md): default files up to 21.5 % smaller (9.7 % over the 25 shared
/// meshes), their Chamfer distance up to 14 % larger; against Draco's bytes at equal Chamfer every ratio is the
/// same or lower (bench/results/meshes.md).

#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// The patches a pass from the last to the first can drop without uncovering a vertex or a triangle.
  /// \param[in] mesh           the mesh the patches grew on
  /// \param[in] patches        the partition (vertex and triangle indices of \a mesh)
  /// \param[in] seed_vertices  a tile's core (sampleFeatureAwarePatches): per vertex, nonzero where this
  ///                           partition answers for it; the others, and faces with no such corner, are
  ///                           another tile's to cover and count as held. Empty (default): every vertex.
  /// \return one flag per patch, true where it is redundant
  std::vector<bool>
  redundantPatches (const TriangleMesh& mesh, const std::vector<Patch>& patches,
                    const std::vector<std::uint8_t>& seed_vertices = {});
} // namespace pcl_sparse
