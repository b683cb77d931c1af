#pragma once
/// \file patch_merging.h
/// Patch merging (ours, issue 13 point 2, "merge into a neighbour"): after redundant patches are dropped
/// (redundant_patches.h), many kept patches still hold only one or two vertices or triangles no other patch
/// holds (spot 167 of 1042, sword 212 of 1241), yet each costs the model its seed, frame, radius and
/// footprint (120-135 bits in a default file, as much as its atoms).
///
/// One pass from the last patch to the first: a patch holding at most `max_own_elements` vertices and
/// triangles of its own (held by no other patch still kept) is set aside and its own triangles are placed
/// in the neighbouring patches under face completion's rules (face_placement.h: the neighbour's normal cone,
/// no flip, no overlap on its seed's plane, the pairwise cone); a triangle that fits no neighbour at first is
/// tried again once the others are placed. The patch is merged (dropped) when all its own triangles found a
/// neighbour and its own vertices went with them; otherwise its placements are undone and it stays. What any
/// patch held stays held, so coverage (vertices and faces) does not change. Patches beside a face no patch
/// holds (Patch::beside_uncovered_face) stay: their unclipped footprints cover that face. In a tile only the
/// core counts, as in redundantPatches. O(sum of patch sizes + merged candidates' triangles x their
/// neighbours' triangles).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_growth.h>
#include <pcl_sparse/patches/patch_options.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// \brief Merges the patches with few elements of their own into their neighbours (see the file comment).
  /// \param[in]     mesh              the mesh the patches were grown on
  /// \param[in]     topology          its topology
  /// \param[in]     geometry          computePatchGrowthGeometry (mesh, topology, ...)
  /// \param[in]     options           cone_angle, pairwise_cone and delta, as the patches were grown with
  /// \param[in]     max_own_elements  candidates hold at most this many vertices plus triangles of their own
  /// \param[in,out] patches           the partition: neighbours gain the merged patches' triangles and vertices
  ///                                  (appended, counted in Patch::completed_triangles); merged patches are
  ///                                  left in place for the caller to drop
  /// \param[in]     seed_vertices     a tile's core (as for redundantPatches); empty: every vertex
  /// \return one flag per patch, true where it was merged
  std::vector<bool>
  mergeSmallPatches (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                     const PatchOptions& options, int max_own_elements, std::vector<Patch>& patches,
                     const std::vector<std::uint8_t>& seed_vertices = {});
} // namespace pcl_sparse
