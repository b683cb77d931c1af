#pragma once
/// \file vertex_welding.h
/// Vertices at exactly the same position taken as one ("welding"), for files that repeat a corner in every
/// face that uses it: STL always, and OBJ / PLY / OFF written as a triangle soup (PCL's VTK OBJ reader makes
/// one of a file with per-corner normals). No tolerance: anything else would change the geometry.

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// \brief Of a caller's points, the first added at each exact position (+0 and -0 are the same position;
  /// NaN is never equal). An open-addressing hash table of indices into the points,
  /// at most half full (it grows): one lookup per point. Holds a reference to the points, which may grow
  /// between calls (VertexWelder appends to them).
  class FirstPositionTable
  {
  public:
    /// \param[in] points    the points, indexed as add () is told
    /// \param[in] expected  about how many distinct positions will be added (sizes the table)
    FirstPositionTable (const std::vector<Eigen::Vector3d>& points, std::size_t expected);

    /// \brief The index of an earlier added point at \a position; else \a i, now added, and points[i] must be
    /// \a position from the next call on (VertexWelder appends it only when new).
    std::size_t
    add (const Eigen::Vector3d& position, std::size_t i);

  private:
    void
    grow ();

    const std::vector<Eigen::Vector3d>& points_;
    std::vector<int> slots_;
    std::size_t count_ = 0;
  };

  /// \brief Numbers positions as they come, giving a position equal to an earlier one that one's index
  /// (+0 and -0 are the same position; NaN is never equal, so never welded). An open-addressing hash table:
  /// one lookup per position, several times faster than std::unordered_map (1.2 million corners of a
  /// 400k-triangle STL).
  class VertexWelder
  {
  public:
    /// \param[out] vertices          the distinct positions: emptied here, add () appends new ones
    /// \param[in]  expected_corners  about how many positions will be added (sizes the table)
    VertexWelder (std::vector<Eigen::Vector3d>& vertices, std::size_t expected_corners);

    /// \brief The index in the vertices of \a position: an earlier equal one's, or a new one's (appended).
    int
    add (const Eigen::Vector3d& position);

  private:
    std::vector<Eigen::Vector3d>& vertices_;
    FirstPositionTable first_;
  };

  /// \brief For each vertex of \a mesh, the first vertex at exactly its position (itself if none; a vertex
  /// with a NaN coordinate is always itself). O(#V).
  /// \param[in] mesh  the mesh (only its vertices are read)
  /// \return #V indices, each <= its own index
  std::vector<int>
  findCoincidentVertices (const TriangleMesh& mesh);

  /// \brief Whether no vertex of \a mesh belongs to two of its faces while it has at least two faces: a
  /// triangle soup, with no topology for any stage to work on. O(#V + #F).
  bool
  isTriangleSoup (const TriangleMesh& mesh);
} // namespace pcl_sparse
