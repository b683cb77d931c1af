#pragma once
/// \file nearest_face_normal.h
/// How far a direction is from the surface normal at the nearest point of a mesh: the yardstick of flipped
/// normals (evaluateCloudQuality) and of the encoder's check for places whose code points the wrong way
/// (trimFlippedPlaces).

#include <pcl_sparse/geometry/triangle_tree.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// A mesh's triangle tree and face normals, to compare directions with the surface normal nearest a point.
  class NearestFaceNormal
  {
  public:
    /// \param[in] mesh  the surface (kept by reference: it must outlive this object)
    /// \param[in] num_threads  OpenMP threads of the triangle tree's build (TriangleTree)
    /// \throws pcl_sparse::Error as TriangleTree (no triangle, a corner out of range or not finite)
    explicit NearestFaceNormal (const TriangleMesh& mesh, int num_threads = 1);

    /// The nearest triangle of \a p, and the largest cosine between \a direction (unit) and the normals of
    /// the faces nearest \a p. Where the nearest surface point lies on an edge or a corner, every face
    /// sharing it is nearest (the distances agree up to rounding) and the surface normal there is any of
    /// theirs: the closest of their normals counts, so that a point just past a knife edge matches the face
    /// it came from, not the one the search happened to find first. Thread-safe.
    /// \param[in] p          the point
    /// \param[in] direction  unit vector
    /// \param[out] cosine    the largest cosine (-1 .. 1; 0 against a degenerate face)
    /// \param[in,out] tied   scratch space (reused between calls, so a query allocates nothing)
    /// \return the nearest triangle and its distance (TriangleTree::nearest)
    TriangleTree::Nearest
    nearest (const Eigen::Vector3d& p, const Eigen::Vector3d& direction, double& cosine,
             std::vector<TriangleTree::Nearest>& tied) const;

    const TriangleTree& tree () const { return tree_; }
    /// Unit face normals (computeFaceNormals; zero for degenerate faces).
    const std::vector<Eigen::Vector3d>& faceNormals () const { return face_normals_; }

  private:
    TriangleTree tree_;  // first: it refuses corner indices out of range, which the normals would read
    std::vector<Eigen::Vector3d> face_normals_;
    double tie_ = 0.0;  ///< two faces' distances to their shared edge differ by this much rounding at most
  };
} // namespace pcl_sparse
