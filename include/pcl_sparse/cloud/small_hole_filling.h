#pragma once
/// \file small_hole_filling.h
/// Closing the small holes a local triangulation leaves where neighbouring points disagree on the
/// Delaunay triangles (near co-circular neighbours): boundary loops of a few edges, filled by ears whose
/// new edges pass the same gap rule, so no hole in the data is ever bridged beyond what the rule allows.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// Fills the boundary loops of at most \a max_edges edges of an oriented manifold triangle set.
  ///   positions  #P positions
  ///   normals    #P oriented unit normals
  ///   spacing    #P local spacing
  ///   triangles  wound consistently, every directed edge used at most once; new triangles are appended
  /// A loop is followed along the boundary edges reversed (so new triangles keep the winding); loops
  /// through a vertex where two boundary loops meet are left alone. A loop is filled only as a whole, by
  /// repeatedly cutting the ear (v_k, v_k+1, v_k+2) with the shortest new edge v_k+2 - v_k among those whose
  /// new edge is not in the mesh yet and passes |v_k+2 - v_k| <= gap_factor x min (s_k, s_k+2), and whose
  /// geometric normal agrees with its corners' normals. Loops are visited in a fixed order, so the result
  /// is deterministic.
  ///   returns  the number of loops filled
  std::size_t
  fillSmallHoles (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
                  const std::vector<double>& spacing, double gap_factor, std::size_t max_edges,
                  std::vector<Eigen::Vector3i>& triangles);
} // namespace pcl_sparse
