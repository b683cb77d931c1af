#pragma once
/// \file face_placement.h
/// Placing one face in one of the patches at its corners, under growth's guarantees (ours): what face
/// completion (face_completion.h) does for every face in no patch, and patch merging (patch_merging.h) for
/// the few faces of a patch it hands to its neighbours.
///
/// A patch can take a face when the face lies within the normal cone of the seed (PatchOptions::cone_angle)
/// and, with pairwise_cone, of every patch triangle and does not fold the patch (addingFaceFolds); when it
/// does not flip on the seed's tangent plane; and when it does not overlap the patch's triangles projected
/// there (the patch stays a height field). Among the patches holding a corner of the face, preferred in
/// order: one where the face passes growth's smooth variation test (within delta of the vertex normal of a
/// corner the patch holds, or of a patch triangle across an edge), the one holding the most corners, the one
/// whose seed normal is closest to the face normal, the lowest index. The missing corners join the patch.
///
/// Every placement can be undone (mark / rollback, last in first out), and patches can be set aside
/// (setRemoved): they are no candidate then. Each try costs O(candidates x triangles of the candidate); a
/// patch's projected triangles are built on its first try.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_growth.h>
#include <pcl_sparse/patches/patch_options.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  /// Places faces in patches (see the file comment). Holds references to its arguments.
  class FacePlacer
  {
  public:
    /// \param[in]     mesh      the mesh the patches were grown on
    /// \param[in]     topology  its topology
    /// \param[in]     geometry  computePatchGrowthGeometry (mesh, topology, ...)
    /// \param[in]     options   cone_angle, pairwise_cone and delta, as the patches were grown with
    /// \param[in,out] patches   the partition; placements append to a patch's triangles and vertices
    FacePlacer (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                const PatchOptions& options, std::vector<Patch>& patches);
    ~FacePlacer ();
    FacePlacer (const FacePlacer&) = delete;
    FacePlacer& operator= (const FacePlacer&) = delete;

    /// Where a placement went.
    struct Placement
    {
      int patch = -1;               ///< the patch that took the face, -1 if none could
      bool smooth_variation = false;  ///< whether it took the face with smooth variation
      int num_vertices = 0;           ///< corners the patch gained: the last this many of its vertices
    };

    /// Adds face \a f (area > 0) to the best patch that can take it among those holding a corner of it and
    /// not set aside. \a with_added: count as holding what earlier placements gave a patch too; otherwise
    /// only what the patches held when the placer was built (completion's candidates then do not depend
    /// on its order).
    Placement
    place (int f, bool with_added = false);

    /// Sets patch \a p aside (no candidate while \a removed) or back.
    void
    setRemoved (int p, bool removed);

    /// A point to roll back to: the number of placements made so far.
    std::size_t
    mark () const;

    /// Undoes the placements made after \a mark, the last first.
    void
    rollback (std::size_t mark);

    /// The patches holding vertex \a v as built, ascending.
    std::vector<int>
    holdersOf (int v) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };
} // namespace pcl_sparse
