#pragma once
/// \file tangent_triangulation.h
/// Triangles of an unorganized scan from local Delaunay fans: each point projects its accepted neighbours
/// on its tangent plane and proposes the Delaunay triangles around itself (Gopi, Krishnan and Silva 2000;
/// Linsen and Prautzsch 2001). A triangle is taken when its corners agree on it and it overlaps no triangle
/// taken before.
///
/// Why not pcl::GreedyProjectionTriangulation: it is sequential, and its result depends on the order in
/// which it grows the front; the fans are computed per point in parallel, the vote and the merge are
/// deterministic, and every edge of the result has at most two triangles (bench/results/cloud_surface.md
/// compares the two).

#include <pcl_sparse/cloud/edge_rules.h>
#include <pcl_sparse/cloud/point_neighborhoods.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Local Delaunay triangulation.
  ///   neighborhoods  symmetric neighbour lists (symmetricNeighborhoods): a triangle can only get the votes
  ///                  of corners that see the other two
  ///   normals  #P oriented unit normals (zero for points without one)
  ///   usable   #P flags; only usable points with normals are corners
  /// Point i's fan: its usable neighbours j with n_i . n_j > 0.25 (75 degrees: not across a thin sheet),
  /// projected on its tangent plane, perturbed by 1e-7 spacings in a direction fixed per point index (so
  /// that co-circular neighbours, as on a regular grid, are ordered the same way by every point); its
  /// Voronoi cell among them gives its Delaunay neighbours, and two consecutive ones a and b give the
  /// triangle (i, a, b) if the edge a-b passes the gap rule (<= gap_factor x min (s_a, s_b)) and the shadow
  /// rule. Each triangle gets one vote per corner that proposes it; taken in the order (more votes,
  /// shorter longest edge, indices), wound like the normals, and only when none of its directed edges is
  /// used already (so no edge has more than two triangles and no two overlap across one).
  std::vector<Eigen::Vector3i>
  triangulateTangentFans (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                          const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                          double gap_factor, const ShadowRule& shadow, int num_threads);
} // namespace pcl_sparse
