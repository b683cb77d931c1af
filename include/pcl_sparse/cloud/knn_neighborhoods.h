#pragma once
/// \file knn_neighborhoods.h
/// Neighbourhoods of an unorganized scan: the k nearest neighbours of every point (PointKdTree:
/// FLANN as PCL searches it), then the gap rule against the local spacing and the shadow rule.

#include <pcl_sparse/cloud/edge_rules.h>
#include <pcl_sparse/cloud/point_neighborhoods.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// The k nearest other points of every point.
  ///   neighbors  #P x k indices, each row by increasing distance then index; -1 pads rows of points with
  ///              fewer than k candidates and fills the rows of points that were not searched
  ///   distances  #P x k their distances (double, from the double positions)
  struct KnnGraph
  {
    int k = 0;
    std::vector<int> neighbors;
    std::vector<double> distances;
  };

  /// The k nearest neighbours of every point with searched[i] != 0, among those points. The kd-tree holds
  /// float copies of the positions (local frame: small numbers, so float picks the right neighbours);
  /// the distances and the order are then recomputed in double, ties broken by index, so the result is
  /// the same for any number of threads.
  ///   positions  #P local positions
  ///   searched   #P flags: 0 for points to leave out (non-finite)
  KnnGraph
  findKNearestNeighbors (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& searched,
                         int k, int num_threads);

  /// Edge counts of acceptKnnEdges, over ordered pairs (i, j) with j among the k nearest of i (a mutual
  /// pair counts twice).
  struct KnnEdgeCounts
  {
    std::size_t candidates = 0;
    std::size_t refused = 0;   ///< by the gap rule or the shadow rule
    std::size_t shadowed = 0;  ///< by the shadow rule alone (the gap rule passed)
  };

  /// The accepted kNN neighbourhoods. Spacing of point i: the median over i and its k nearest of their
  /// mean distance to their (up to) 6 nearest neighbours; that mean is about the square root of the area
  /// per point for regular, hexagonal and random samplings alike, and the median keeps a tight cluster
  /// of a random sampling, or a stray point far from a surface, from having a spacing of its own. The
  /// neighbour j of i is kept when |p_i - p_j| <= gap_factor x min (s_i, s_j) and the shadow rule passes.
  PointNeighborhoods
  acceptKnnEdges (const std::vector<Eigen::Vector3d>& positions, const KnnGraph& graph, double gap_factor,
                  const ShadowRule& shadow, KnnEdgeCounts& counts, int num_threads);
} // namespace pcl_sparse
