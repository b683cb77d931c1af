#include <pcl_sparse/tiles/tile_membership.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  void
  tilesHolding (const TileGrid& grid, const Eigen::Vector3d& p, std::vector<std::size_t>& tiles)
  {
    tiles.clear ();
    if (!p.allFinite ())
      return;
    // Per axis, the tile coordinates whose closed margin interval holds p. Candidates come from a division
    // (a cell or two either side, for rounding); the test itself uses marginBox's own arithmetic:
    // low = origin + edge * i, [low - margin, (low + edge) + margin].
    int first[3], last[3];
    int holding[3][16];
    int count[3] = {0, 0, 0};
    // (Margins up to 6 edges; makeTileGrid allows half an edge.)
    const int reach = static_cast<int> (std::min (7.0, 1.0 + std::ceil (grid.margin / grid.edge)));
    for (int axis = 0; axis < 3; ++axis)
    {
      const double cell = std::floor ((p[axis] - grid.origin[axis]) / grid.edge);
      const double clamped = std::clamp (cell, -1.0, static_cast<double> (grid.counts[axis]));
      first[axis] = std::max (0, static_cast<int> (clamped) - reach);
      last[axis] = std::min (grid.counts[axis] - 1, static_cast<int> (clamped) + reach);
      for (int i = first[axis]; i <= last[axis] && count[axis] < 16; ++i)
      {
        const double low = grid.origin[axis] + grid.edge * static_cast<double> (i);
        if (low - grid.margin <= p[axis] && p[axis] <= (low + grid.edge) + grid.margin)
          holding[axis][count[axis]++] = i;
      }
    }
    const std::size_t nx = static_cast<std::size_t> (grid.counts.x ());
    const std::size_t nxy = nx * static_cast<std::size_t> (grid.counts.y ());
    for (int c = 0; c < count[2]; ++c)
      for (int b = 0; b < count[1]; ++b)
        for (int a = 0; a < count[0]; ++a)
          tiles.push_back (static_cast<std::size_t> (holding[0][a]) + nx * static_cast<std::size_t> (holding[1][b]) +
                           nxy * static_cast<std::size_t> (holding[2][c]));
    const std::size_t owner = grid.tileOf (p);
    const auto at = std::lower_bound (tiles.begin (), tiles.end (), owner);
    if (at == tiles.end () || *at != owner)
      tiles.insert (at, owner);
  }
} // namespace pcl_sparse
