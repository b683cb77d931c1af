#pragma once
// A bent knife-edge mesh: two sides meeting at a wedge, for the knife-edge clearance of resampling
// (PatchOwnershipOptions::opposite_clearance).

#include <pcl_sparse/mesh/mesh_primitives.h>

#include <cmath>
#include <vector>

namespace pcl_sparse_test
{
  /// A bent knife: two height fields z = w(x, y) +- s (1 - x) over [-1, 1]^2 welded along their common edge
  /// x = 1, a 2 atan (s) wedge there. w bends the blade so that the codes are not exact.
  inline pcl_sparse::TriangleMesh
  makeKnife (int n, double wedge_degrees)
  {
    const double s = std::tan (0.5 * wedge_degrees * M_PI / 180.0);
    auto bend = [] (double x, double y) { return 0.3 * std::sin (3.0 * y) * std::cos (2.0 * x); };
    const pcl_sparse::TriangleMesh top =
      pcl_sparse::makeHeightFieldGrid (n, n, 1.0, 1.0, [&] (double x, double y) { return bend (x, y) + s * (1.0 - x); });
    const pcl_sparse::TriangleMesh bottom =
      pcl_sparse::makeHeightFieldGrid (n, n, 1.0, 1.0, [&] (double x, double y) { return bend (x, y) - s * (1.0 - x); });
    pcl_sparse::TriangleMesh knife = top;
    // Bottom vertices on the edge x = 1 are the top's; the others are appended. Bottom faces are reversed.
    std::vector<int> index (bottom.vertices.size ());
    for (std::size_t v = 0; v < bottom.vertices.size (); ++v)
    {
      int same = -1;
      if (std::abs (bottom.vertices[v].x () - 1.0) < 1e-12)
        for (std::size_t u = 0; u < top.vertices.size () && same < 0; ++u)
          if ((top.vertices[u] - bottom.vertices[v]).norm () < 1e-12)
            same = static_cast<int> (u);
      if (same < 0)
      {
        same = static_cast<int> (knife.vertices.size ());
        knife.vertices.push_back (bottom.vertices[v]);
      }
      index[v] = same;
    }
    for (const Eigen::Vector3i& t : bottom.triangles)
      knife.triangles.emplace_back (index[t[0]], index[t[2]], index[t[1]]);
    return knife;
  }
} // namespace pcl_sparse_test
