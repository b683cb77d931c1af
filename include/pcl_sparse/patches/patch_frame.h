#pragma once
/// \file patch_frame.h
/// The local frame of a grown patch (docs/METHOD.md step 6): R = (T1, T2, N) from a degree-2 jet fitted in the
/// seed's tangent frame, the radius r_P and the local scaled coordinates p' = R^T (p - s) / r_P.

#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>

#include <Eigen/Core>

namespace pcl_sparse
{
  /// How computePatchFrame chose the frame.
  enum class PatchFrameKind
  {
    Jet,          ///< the jet's principal directions and normal (the method)
    SeedNormal,   ///< N = the seed's vertex normal, T1 = the jet's max direction projected on its plane:
                  ///< used when the jet normal would flip a patch triangle in projection, or tilt the
                  ///< steepest one past PatchOptions::steep_frame_angle (72 degrees on meshes; 50 for
                  ///< patches grown from faces, face_steep_frame_angle) and
                  ///< past its tilt on the seed's plane
    NormalOnly    ///< N = the seed's vertex normal, any tangent basis: fewer than 6 vertices or a
                  ///< degenerate layout (jet underdetermined)
  };

  /// Computes the local frame of a grown patch (docs/METHOD.md step 6). N is oriented like the seed
  /// normal. Every patch triangle projects on the frame's tangent plane with positive signed area when it
  /// does so on the seed's tangent plane (which growth guarantees).
  /// \param[in]     mesh          the mesh
  /// \param[in]     seed_normal   unit vertex normal of the seed (the growth's tangent plane); zero for a
  ///                              vertex without a surface, then +z is used
  /// \param[in]     radius_guard  r_P used when every vertex lies on the normal line through the seed
  ///                              (one-vertex patches): must be > 0, for instance the seed's mean edge length
  /// \param[in,out] patch         vertices, triangles and origin set; receives frame, radius and local
  /// \param[in]     steep_angle   a jet that makes the steepest triangle steeper than this (radians) and
  ///                              steeper than the seed's plane does is refused (PatchOptions::
  ///                              steep_frame_angle); 0 = only a jet that flips a triangle
  /// \return how the frame was chosen
  PatchFrameKind
  computePatchFrame (const TriangleMesh& mesh, const Eigen::Vector3d& seed_normal, double radius_guard, Patch& patch,
                     double steep_angle);

  /// Signed area of a triangle projected on a plane.
  /// \param[in] mesh    the mesh
  /// \param[in] f       face index
  /// \param[in] normal  unit normal of the plane
  /// \return the projected area; positive when the face is oriented like \a normal
  double
  projectedSignedArea (const TriangleMesh& mesh, int f, const Eigen::Vector3d& normal);
} // namespace pcl_sparse
