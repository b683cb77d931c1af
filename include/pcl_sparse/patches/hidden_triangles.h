#pragma once
/// \file hidden_triangles.h
/// Triangles of a patch that its seed does not see over the surface (ours, issue 13: no flipped normal).
///
/// A patch's footprint is star-shaped around its seed (patch_footprint.h): on the seed's tangent plane it
/// holds every place between the seed and a patch triangle. A patch that holds triangles beyond a stretch
/// of that plane where the mesh has no surface on the patch's side (it reached round a bay through a row of
/// vertices whose faces turn away) gets a footprint spanning the bay, where its code is fitted to no sample
/// and runs off the surface: blade's patch 298, a comb of long thin triangles, put points 1.7 spacings
/// off the mesh there, nearer the part's other side, with 5 flipped normals.
///
/// A patch triangle is hidden when it is not edge-connected (through patch triangles) to a triangle at the
/// seed, and the segment from the seed to its centroid, projected on the seed's tangent plane, runs for more
/// than min_gap x R outside both the patch's triangles and every face at a patch vertex that faces the
/// seed's side (n . n_s > 0); R is the largest distance on that plane from the seed to a patch triangle's
/// corner. Counted at min_gap 0.3 on the final partitions of the 25 shared meshes (default options but no
/// release): blade 13 faces in 2 of 302 patches (patch 298's 7 among them), cheese-cgal 62 in 31 of 1386,
/// stanford-bunny and nefertiti-35k 1 face each, none elsewhere; with the release (face_completion.h,
/// releaseHiddenPatchTriangles) 1 face each on blade and cheese-cgal, given back to their patches. Without
/// the faces at the patch's vertices (the patch triangles' own gaps only) blade had 213 such patches at
/// 0.2: its combs of thin triangles leave gaps that the neighbouring patches' faces fill.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_growth.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Finds the hidden triangles of patches on one mesh. Its scratch (one slot per face) is sized once and
  /// only the entries a patch touched are reset, so a patch of T triangles none of which is detached from
  /// the seed's costs O(T); D detached triangles add O(D x (T + F)), F the faces at the patch's vertices. Not
  /// thread-safe: one object per thread.
  class HiddenTriangleFinder
  {
  public:
    /// All arguments must outlive the finder.
    /// \param[in] mesh      the mesh the patches were grown on
    /// \param[in] topology  its topology
    /// \param[in] geometry  computePatchGrowthGeometry (mesh, topology, ...): face and seed normals, areas
    HiddenTriangleFinder (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry);

    /// \brief The hidden triangles of \a patch (see the file comment), in the order of patch.triangles.
    /// \param[in] patch    the patch (seed, seed_face, vertices, triangles)
    /// \param[in] min_gap  the gap, in units of R, beyond which a triangle is hidden
    std::vector<int>
    find (const Patch& patch, double min_gap);

  private:
    /// Per patch triangle, whether it is edge-connected (through patch triangles) to a triangle at the seed.
    std::vector<std::uint8_t>
    connectedToSeed (const Patch& patch);

    const TriangleMesh& mesh_;
    const MeshTopology& topology_;
    const PatchGrowthGeometry& geometry_;
    std::vector<int> slot_;  ///< #F: the face's index in the current patch's triangles, -1 if none
  };

  /// \brief The hidden triangles of \a patch (HiddenTriangleFinder::find, with a finder of its own: for one
  /// patch; a loop over patches keeps one finder).
  std::vector<int>
  hiddenPatchTriangles (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                        const Patch& patch, double min_gap);

  /// \brief Removes \a faces from \a patch's triangles, and from its vertices the corners no remaining
  /// triangle of the patch has (the seed stays); completed_triangles counts the completion's triangles left.
  void
  removePatchTriangles (const TriangleMesh& mesh, const std::vector<int>& faces, Patch& patch);
} // namespace pcl_sparse
