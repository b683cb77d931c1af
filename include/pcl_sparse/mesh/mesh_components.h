#pragma once
/// \file mesh_components.h
/// Face components of a mesh: faces joined through shared vertices.

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace pcl_sparse
{
  /// \brief Union-find with path halving; joins attach the larger root under the smaller one, so the root of
  /// a set is its smallest element (deterministic, and it does not depend on the join order).
  class DisjointSets
  {
  public:
    explicit DisjointSets (std::size_t n) : parent_ (n) { std::iota (parent_.begin (), parent_.end (), 0); }

    /// The root (smallest element) of \a x's set.
    int
    find (int x)
    {
      while (parent_[x] != x)
        x = parent_[x] = parent_[parent_[x]];
      return x;
    }

    /// Merges the sets of \a a and \a b.
    void
    join (int a, int b)
    {
      a = find (a);
      b = find (b);
      if (a != b)
        parent_[std::max (a, b)] = std::min (a, b);
    }

  private:
    std::vector<int> parent_;
  };

  /// \brief For each vertex, the number of vertices of its face component (faces joined through shared
  /// vertices); 0 for a vertex in no face. O(V + F).
  /// \param[in] mesh  the mesh (indices in range)
  std::vector<int>
  faceComponentSizes (const TriangleMesh& mesh);
} // namespace pcl_sparse
