#pragma once
/// \file face_completion.h
/// Face completion (ours): every face of the surface joins some patch, so every point of it, not only every
/// vertex, lies in the footprint of a patch (issue 13 point 1).
///
/// Growth (patch_growth.h) makes a face a patch triangle only when its three corners joined one patch.
/// Where the faces are long and thin (CAD meshes) or cross a crease, the corners of a face often joined
/// different patches, and the face is in none: its points lie outside every footprint and resampling leaves
/// a hole there (85 % of couplingdown's area, 42 % of blade's). Completion adds each such face to one of
/// the patches holding one of its corners, among those where the face keeps the growth's guarantees:
/// within the normal cone of the seed (PatchOptions::cone_angle) and of every patch triangle (with
/// pairwise_cone), no flip on the seed's tangent plane, and no overlap with the patch's triangles
/// projected there (the patch stays a height field). Preferred, in
/// order: a patch where the face passes growth's smooth variation test (within delta of the vertex normal
/// of a corner the patch holds, or of a patch triangle across an edge), the one holding the most corners,
/// the one whose seed normal is closest to the face normal, the lowest index. The missing corners join the
/// patch's vertices. No patch is added by this placement; the extra vertices and triangles are extra
/// samples of the patch's fit and extend its footprint.
///
/// Measured (bench/results/face_completion.md): faces in no patch before / after completion, couplingdown
/// 1767 / 688 of 3714, cheese-cgal 10696 / 4398 of 17786, blade 9627 / 136 of 16222 (what is left: faces
/// outside the cone of every patch holding a corner, on strips between creases: a quarter of couplingdown's
/// and cheese-cgal's area).
///
/// Patches seeded on faces (PatchOptions::seed_patches_on_faces, default on): each face left, in ascending
/// order, grows a patch of its own over faces (PatchGrower::growFromFace: the face's normal is the cone's
/// axis, smooth variation between adjacent faces), kept unless it is a long strip seen from its seed
/// (growth radius r with r^2 > 40 x its area), whose star-shaped footprint would span wedges off the strip.
/// These patches are appended (M grows: they count as coverage patches). Measured on the 25 shared meshes
/// (bench/results/face_seeded_patches.md): area in no patch couplingdown 24.5 % -> 0, cheese-cgal 27 % ->
/// 0.04 %, turbine 1.7 % -> 0.0007 %, 0 on 16 meshes; blade keeps its 0.16 % (fillet strips). The patches
/// at the corners of a face still left out are marked (Patch::beside_uncovered_face): their footprints are
/// not clipped at their border, whose overshoot covers it.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_growth.h>
#include <pcl_sparse/patches/patch_options.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// What completePatchFaces did.
  struct FaceCompletionResult
  {
    std::size_t faces_in_no_patch = 0;  ///< proper faces (area > 0) in no patch before completion
    std::size_t completed = 0;          ///< of those, faces added to a patch
    std::size_t without_smooth_variation = 0;  ///< of those, faces no candidate took with smooth variation
    /// patches appended, each grown from a face no patch could take (PatchOptions::seed_patches_on_faces)
    std::size_t seeded_patches = 0;
    /// faces released from a patch whose seed does not see them (PatchOptions::hidden_triangle_gap) and
    /// taken by a patch seeded on faces
    std::size_t released_faces = 0;
    std::vector<int> uncovered;         ///< proper faces still in no patch, ascending
  };

  /// \brief Adds every proper face that is in no patch to a patch holding one of its corners, and with
  /// PatchOptions::seed_patches_on_faces grows patches on the faces that fit none (see the file comment),
  /// before the frames are fitted (patch.local is not touched).
  /// \param[in]     mesh        the mesh the patches were grown on
  /// \param[in]     topology    its topology
  /// \param[in]     geometry    computePatchGrowthGeometry (mesh, topology, ...): normals of the seeds and faces
  /// \param[in]     options     the growth options the patches were grown with, and seed_patches_on_faces
  /// \param[in,out] patches     grown patches (seed, seed_face, vertices, triangles); faces and corners
  ///                            appended, and the patches seeded on faces after them
  /// \param[in]     must_cover  empty (every face), or #V flags: only faces with a flagged corner are completed
  /// \return counts and the faces left in no patch
  FaceCompletionResult
  completePatchFaces (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                      const PatchOptions& options, std::vector<Patch>& patches, const std::vector<std::uint8_t>& must_cover = {});

  /// \brief Releases the patches' hidden triangles (hidden_triangles.h, PatchOptions::hidden_triangle_gap):
  /// each leaves its patch, with the corners no other triangle of the patch has; the released faces no other
  /// patch holds grow patches of their own from a face, in ascending order, as completion's faces do
  /// (appended); a released face no new patch takes goes back to its patch. Run on the final partition
  /// (after redundant patches are dropped and small ones merged: merging hands faces to neighbours, which can
  /// hide them again).
  /// \param[in]     mesh        the mesh the patches were grown on
  /// \param[in]     topology    its topology
  /// \param[in]     geometry    computePatchGrowthGeometry (mesh, topology, ...)
  /// \param[in]     options     hidden_triangle_gap (0: nothing happens) and the growth options
  /// \param[in,out] patches     the partition (before the frames); patches appended
  /// \param[in]     must_cover  as for completePatchFaces: the seed of a new patch is a flagged corner
  /// \param[in]     num_threads OpenMP threads for finding the hidden triangles (0: all; the result does not
  ///                            depend on it)
  /// \return seeded_patches and released_faces (released and taken by a new patch); uncovered is empty
  FaceCompletionResult
  releaseHiddenPatchTriangles (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                               const PatchOptions& options, std::vector<Patch>& patches,
                               const std::vector<std::uint8_t>& must_cover = {}, int num_threads = 0);

  /// The proper faces (area > 0) of \a mesh that are a triangle of no patch (Patch::triangles), ascending:
  /// the faces completion has to place, or could not.
  std::vector<int>
  facesInNoPatch (const TriangleMesh& mesh, const std::vector<Patch>& patches);

  /// How much of a mesh's surface is a triangle of no patch (facesInNoPatch), for reports: resampling may
  /// leave such faces out (a 12-triangle cube encoded by 2 patches on opposite sides had 4 sides without a
  /// point, and the tool said nothing).
  struct FaceCoverage
  {
    std::size_t faces_in_no_patch = 0;  ///< proper faces that are a triangle of no patch
    double area_fraction = 0.0;         ///< their area / the mesh's area (0 for a mesh without area)
  };

  /// \brief FaceCoverage of \a patches over \a mesh (the surface the patches were grown on).
  FaceCoverage
  faceCoverage (const TriangleMesh& mesh, const std::vector<Patch>& patches);
} // namespace pcl_sparse
