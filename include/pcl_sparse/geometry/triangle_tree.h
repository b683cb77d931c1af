#pragma once
/// \file triangle_tree.h
/// Exact nearest-triangle queries on a mesh: a bounding-box tree over its triangles (median splits along the
/// longest side of the centroids' box, up to 4 triangles a leaf), searched nearest box first and pruned by the
/// distance found so far. Build O(T log T), the halves of large nodes in parallel; a query visits O(log T) boxes on
/// meshes of evenly sized triangles.
/// Unlike a k-d tree over points drawn on the triangles, it needs no sampling and misses no triangle, however
/// long and thin: the distance is exact.

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  class TriangleTree
  {
  public:
    /// The nearest triangle of a query.
    struct Nearest
    {
      double distance = 0.0;  ///< exact distance to it
      int triangle = -1;      ///< its index in the mesh (the first found among equally near ones); -1 for a
                              ///< query whose distances are not finite (a coordinate NaN, infinite or over 1e75)
    };

    /// \brief Builds the tree over \a mesh's triangles (their corners copied).
    /// \throws pcl_sparse::Error for a mesh without triangles, a corner index out of range, a non-finite corner
    ///         or a corner coordinate over 1e75 in magnitude (distances to it overflow a double)
    /// \param[in] mesh         the surface
    /// \param[in] num_threads  OpenMP threads of the build (0: all, resolveThreadCount); the same tree on any
    explicit TriangleTree (const TriangleMesh& mesh, int num_threads = 1);

    /// Number of triangles.
    std::size_t size () const { return triangle_.size (); }

    /// \brief The triangle nearest \a p and its distance. Thread-safe; deterministic (the same triangle for the
    /// same point, whatever the thread).
    Nearest nearest (const Eigen::Vector3d& p) const;

    /// \brief nearest (p), and in \a tied what within (p, nearest (p).distance + \a margin, tied) gives (in another
    /// order), in one walk of the tree instead of two (NearestFaceNormal: the faces tied at the nearest edge
    /// or corner). Thread-safe.
    /// \param[in] p       the query point
    /// \param[in] margin  how much farther than the nearest a triangle may be (>= 0)
    /// \param[out] tied   the triangles within the nearest distance + \a margin, cleared first
    Nearest nearestAndTied (const Eigen::Vector3d& p, double margin, std::vector<Nearest>& tied) const;

    /// \brief Every triangle within \a radius of \a p (distance <= radius) and its exact distance, in the
    /// tree's order (the same for the same point). With radius = nearest (p).distance + a rounding margin it
    /// gives every triangle tied at the nearest distance: those sharing the edge or corner nearest \a p.
    /// Thread-safe.
    /// \param[in] p       the query point
    /// \param[in] radius  the largest distance found (none for a negative or NaN radius)
    /// \param[out] found  the triangles, cleared first
    void within (const Eigen::Vector3d& p, double radius, std::vector<Nearest>& found) const;

  private:
    struct Node
    {
      Eigen::Vector3d lo, hi;  ///< the box of the node's triangles
      int first = 0;           ///< leaf: first triangle in corners_; inner: index of the first child
      int count = 0;           ///< leaf: number of triangles; 0 for an inner node (children first, first + 1)
    };

    /// Pushes the children of inner node \a node with their squared box distances from \a p, the nearer last
    /// (searched first, so that it prunes the other).
    void pushChildren (const Node& node, const Eigen::Vector3d& p, std::array<std::pair<int, double>, 64>& stack, int& size) const;

    /// Nodes below a node of \a triangles triangles (its descendants), as build splits it; \a below memoises
    /// them by triangle count (at most two counts a level).
    static int nodesBelow (int triangles, std::map<int, int>& below);
    /// Fills node \a node over order[begin, end) and its descendants, which take nodes_[first_free ...] in
    /// depth-first order (\a below: nodesBelow's counts); the halves of large nodes as OpenMP tasks.
    void build (int node, int begin, int end, int first_free, const std::vector<Eigen::Vector3d>& centroids,
                const std::map<int, int>& below, std::vector<int>& order);

    std::vector<Node> nodes_;
    std::vector<std::array<Eigen::Vector3d, 3>> corners_;  ///< the triangles in leaf order
    std::vector<int> triangle_;                            ///< their indices in the mesh
  };
} // namespace pcl_sparse
