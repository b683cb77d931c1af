#pragma once
/// \file patch.h
/// One surface patch: a disk-like set of mesh vertices around a seed, seen as a height field over the
/// seed's tangent plane (docs/METHOD.md steps 5 and 6).

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// A patch of the partition: its vertices and triangles, seed, frame, radius and local coordinates.
  struct Patch
  {
    int seed = -1;                                      ///< seed vertex index
    /// -1 for patches grown by the method (tangent plane of the seed's vertex normal). Coverage patches
    /// grown from a face (FeatureAwarePatchSampling's coverage pass, growFromFace) hold that face here:
    /// its normal stands for the seed normal, and smooth variation is measured between adjacent faces.
    int seed_face = -1;
    std::vector<int> vertices;                          ///< vertex indices, seed first, in growth order
    /// Faces whose three corners are all in the patch, as indices into the stage's surface (SurfaceStage::
    /// getSurface: the input mesh, or its indexed part, without the extra copies of repeated faces).
    std::vector<int> triangles;
    /// The last this many entries of `triangles` were added by face completion (face_completion.h), not by
    /// growth: they keep the cone and no-flip conditions, not smooth variation nor the area bound.
    std::size_t completed_triangles = 0;
    /// A corner of the patch belongs to a face that face completion could put in no patch: the patch's
    /// footprint is then not clipped at its border (SparseCodingOptions::clip_footprints_at_border), whose
    /// overshoot is what covers that face.
    bool beside_uncovered_face = false;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero ();  ///< s: the seed's position
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity ();  ///< R = (T1, T2, N): jet principal directions, normal
    double radius = 0.0;  ///< r_P: largest tangent-plane distance from s to a patch vertex (> 0)
    /// p' = R^T (p - s) / r_P for every entry of `vertices` (same order): x', y' in the unit disk, z' the height.
    std::vector<Eigen::Vector3d> local;

    /// Number of vertices.
    std::size_t size () const { return vertices.size (); }
    /// Local coordinates R^T (p - s) / r_P of the world point \a p.
    Eigen::Vector3d toLocal (const Eigen::Vector3d& p) const { return frame.transpose () * (p - origin) / radius; }
    /// World point s + r_P R q of the local point \a q.
    Eigen::Vector3d toWorld (const Eigen::Vector3d& q) const { return origin + radius * (frame * q); }
  };
} // namespace pcl_sparse
