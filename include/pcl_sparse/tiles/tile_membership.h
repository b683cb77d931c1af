#pragma once
/// \file tile_membership.h
/// Which tiles a point belongs to (issue 16): one rule for every TileSource, so that a tile cut from an
/// input in memory and a tile read back from a spill file hold the same points.

#include <pcl_sparse/model/tile_grid.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// \brief The tiles whose input holds the point \a p: every tile t with grid.marginBox (t).contains (p)
  /// (boxes closed on every side, computed exactly as marginBox computes them), and always the tile that
  /// owns it, grid.tileOf (p) (so that no finite point is lost to rounding at a border, even with a zero
  /// margin). At most 8 tiles when the margin is at most half an edge.
  /// \param[in]  grid   the tile grid
  /// \param[in]  p      a finite position, in the grid's frame
  /// \param[out] tiles  the tile indices, ascending (cleared first); empty for a non-finite \a p
  void
  tilesHolding (const TileGrid& grid, const Eigen::Vector3d& p, std::vector<std::size_t>& tiles);
} // namespace pcl_sparse
