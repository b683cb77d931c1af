#pragma once
/// \file patch_checks.h
/// Checking the invariants a partition into patches must satisfy (issue 4; used by the tests and by
/// pcl_sparse_patches): each patch is a height field over its tangent plane and meets the growth
/// conditions of docs/METHOD.md step 5, and every vertex is covered.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/non_manifold_split.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_growth.h>
#include <pcl_sparse/patches/patch_options.h>

#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Checks patches of one mesh against the options they were built with. Normals are computed as the
  /// growth computes them (after the same non-manifold split).
  class PatchInvariantChecker
  {
  public:
    /// Prepares the checks (normals, topology, the same non-manifold split as the growth).
    /// \param[in] mesh     the mesh the patches were built on; must outlive the checker
    /// \param[in] options  the options they were built with
    /// \param[in] point_normals the normals they were grown with (a scan's; sampleFeatureAwarePatches), or
    ///            empty for the mesh's own
    PatchInvariantChecker (const TriangleMesh& mesh, const PatchOptions& options,
                           const std::vector<Eigen::Vector3d>& point_normals = {});

    /// Checks one patch against the invariants of a partition:
    /// - seed first, distinct valid vertices;
    /// - frame orthonormal and right-handed with N . n_s > 0; radius > 0;
    ///   local = R^T (p - s) / r_P with |(x', y')| <= 1;
    /// - every triangle has its three corners in the patch, positive area, positive signed area projected
    ///   on the frame's tangent plane and on the seed's, angle(n_t, n_s) < cone_angle, and
    ///   angle(n_t, n_w) < delta for some corner w;
    /// - any two triangles differ by less than cone_angle, and no face with its three corners among a
    ///   vertex-grown patch's vertices faces away from n_s (when options.pairwise_cone);
    /// - A_p / A <= rho or A_p / A_p^proj <= eta.
    ///
    /// Triangles added by face completion (Patch::completed_triangles) are not held to smooth variation
    /// and the area bound, which are growth's.
    /// Face-grown coverage patches (seed_face >= 0) use n_{seed_face} for n_s, and smooth variation means
    /// every triangle is reached from the seed face through adjacent patch triangles less than delta apart.
    /// \param[in] patch  a patch with frame, radius and local coordinates
    /// \return empty if it satisfies them all, otherwise a one-line description of the first violation
    std::string check (const Patch& patch) const;

    /// Referenced vertices (in some face) that no patch contains.
    /// \param[in] patches  the partition
    /// \return vertex indices, ascending
    std::vector<int> uncoveredVertices (const std::vector<Patch>& patches) const;

    /// Normals and areas the checks use (those of the growth).
    const PatchGrowthGeometry& geometry () const { return geometry_; }

  private:
    const TriangleMesh& mesh_;
    PatchOptions options_;
    NonManifoldSplit split_;
    bool is_split_ = false;
    const TriangleMesh* grown_mesh_ = nullptr;  // the mesh the growth ran on (split or input)
    MeshTopology topology_;
    PatchGrowthGeometry geometry_;
  };
} // namespace pcl_sparse
