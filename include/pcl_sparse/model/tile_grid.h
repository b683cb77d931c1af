#pragma once
/// \file tile_grid.h
/// The regular grid of tiles a large input is cut into (issue 16): axis-aligned boxes of one edge
/// length over the input's bounding box, numbered x fastest, then y, then z. Each tile is encoded from
/// the points of its box grown by a margin on every side, and owns the patches whose seed lies in its
/// own (core) box, so that every place belongs to exactly one tile.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>

namespace pcl_sparse
{
  /// Options of makeTileGrid.
  struct TileGridOptions
  {
    /// Points a tile should hold, on average over the tiles that hold any (the grid's edge is chosen
    /// from it, treating the input as a surface: points per tile grow with the square of the edge).
    std::size_t points_per_tile = 2000000;
    /// Cut into at least about this many tiles (by area: 400 is 20 x 20 on a height field), smaller than
    /// points_per_tile asks, as long as a tile keeps min_tile_points: so that a region (a box of a
    /// hundredth of the area) is read from a few tiles (0: off, tiles from points_per_tile only).
    std::size_t min_tiles = 0;
    /// Fewest points a tile is cut down to for min_tiles: smaller tiles pay their framing and
    /// compression in bytes (docs/TILES.md, "Measured"); 50,000 points are about 300 patches of a terrain.
    std::size_t min_tile_points = 50000;
    /// Forces the number of tiles along the longest side of the box (0: from points_per_tile).
    int tiles_along_longest = 0;
    /// Margin around each tile's core box, as a fraction of the tile edge: the points a tile's encoder
    /// sees beyond its core box, so that patches seeded near the border grow as they would untiled.
    double margin_fraction = 0.1;
  };

  /// A regular grid of cubic tiles.
  struct TileGrid
  {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero ();  ///< min corner of tile (0, 0, 0)
    double edge = 1.0;                                  ///< edge length of every tile (> 0)
    Eigen::Vector3i counts = Eigen::Vector3i::Ones ();   ///< tiles along x, y, z (each >= 1)
    double margin = 0.0;                                ///< the margin, in world units

    /// Number of tiles.
    std::size_t
    size () const
    {
      return static_cast<std::size_t> (counts.x ()) * counts.y () * counts.z ();
    }

    /// Tile holding \a p (points outside the grid go to the nearest tile; ties to the higher index).
    std::size_t
    tileOf (const Eigen::Vector3d& p) const
    {
      std::size_t index = 0;
      for (int axis = 2; axis >= 0; --axis)
      {
        const double cell = (p[axis] - origin[axis]) / edge;
        const int clamped = cell < 0.0 ? 0 : (cell >= counts[axis] ? counts[axis] - 1 : static_cast<int> (cell));
        index = index * static_cast<std::size_t> (counts[axis]) + static_cast<std::size_t> (clamped);
      }
      return index;
    }

    /// Integer coordinates (i, j, k) of tile \a t.
    Eigen::Vector3i
    coordinates (std::size_t t) const
    {
      const int i = static_cast<int> (t % counts.x ());
      const int j = static_cast<int> ((t / counts.x ()) % counts.y ());
      const int k = static_cast<int> (t / (static_cast<std::size_t> (counts.x ()) * counts.y ()));
      return Eigen::Vector3i (i, j, k);
    }

    /// Core box of tile \a t: the places it owns.
    Eigen::AlignedBox3d
    coreBox (std::size_t t) const
    {
      const Eigen::Vector3d low = origin + edge * coordinates (t).cast<double> ();
      return Eigen::AlignedBox3d (low, low + Eigen::Vector3d::Constant (edge));
    }

    /// Core box grown by the margin on every side: the points tile \a t is encoded from.
    Eigen::AlignedBox3d
    marginBox (std::size_t t) const
    {
      const Eigen::AlignedBox3d core = coreBox (t);
      const Eigen::Vector3d m = Eigen::Vector3d::Constant (margin);
      return Eigen::AlignedBox3d (core.min () - m, core.max () + m);
    }
  };

  /// \brief The grid for \a points points in \a box: cubic tiles whose edge gives about
  /// options.points_per_tile points per tile, or fewer for options.min_tiles (or options.tiles_along_longest
  /// along the longest side).
  /// The grid is centred on the box; a single tile when everything fits in one.
  /// Throws pcl_sparse::Error for an empty or non-finite box, options out of range, or more tiles than
  /// max(4096, points).
  TileGrid
  makeTileGrid (const Eigen::AlignedBox3d& box, std::size_t points, const TileGridOptions& options = TileGridOptions ());
} // namespace pcl_sparse
