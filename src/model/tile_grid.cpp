#include <pcl_sparse/model/tile_grid.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pcl_sparse
{
  TileGrid
  makeTileGrid (const Eigen::AlignedBox3d& box, std::size_t points, const TileGridOptions& options)
  {
    if (box.isEmpty () || !box.min ().allFinite () || !box.max ().allFinite ())
      throw Error ("makeTileGrid: the input's bounding box is empty or not finite");
    if (options.points_per_tile == 0 || options.min_tile_points == 0 || options.tiles_along_longest < 0 ||
        !(options.margin_fraction >= 0.0 && options.margin_fraction <= 0.5))
      throw Error ("makeTileGrid: points_per_tile and min_tile_points must be positive, tiles_along_longest >= 0 and "
                   "margin_fraction in [0, 0.5]");
    const Eigen::Vector3d sides = box.sizes ();
    const double longest = std::max (sides.maxCoeff (), 1e-12);
    std::size_t per_tile = options.points_per_tile;
    if (options.min_tiles > 0)
      per_tile = std::min (per_tile, std::max (points / options.min_tiles, options.min_tile_points));
    double edge = longest;
    if (options.tiles_along_longest > 0)
      edge = longest / options.tiles_along_longest;
    else if (points > per_tile)
    {
      // A surface spread through the box: its area is about the sum of the box's three face areas at
      // worst and the largest one for a height field; the mean of the two keeps tiles near their target
      // on terrain (flat boxes) and on objects alike.
      const double largest_face = std::max ({sides.x () * sides.y (), sides.y () * sides.z (), sides.x () * sides.z ()});
      const double all_faces = sides.x () * sides.y () + sides.y () * sides.z () + sides.x () * sides.z ();
      const double area = std::max (0.5 * (largest_face + all_faces), longest * longest * 1e-12);
      edge = std::sqrt (area * static_cast<double> (per_tile) / static_cast<double> (points));
      edge = std::min (edge, longest);
    }
    // More tiles than points only costs memory (about 600 bytes a tile): a compact input cut into N tiles
    // along its longest side has up to N^3 of them.
    double total = 1.0;
    for (int axis = 0; axis < 3; ++axis)
      total *= std::max (1.0, std::ceil (sides[axis] / edge * (1.0 - 1e-12)));
    if (total > std::max (4096.0, static_cast<double> (points)))
      throw Error ("makeTileGrid: " + std::to_string (static_cast<long long> (total)) + " tiles for " + std::to_string (points) +
                   " points: ask for fewer tiles along the longest side");
    TileGrid grid;
    grid.edge = edge;
    for (int axis = 0; axis < 3; ++axis)
      grid.counts[axis] = std::max (1, static_cast<int> (std::ceil (sides[axis] / edge * (1.0 - 1e-12))));
    grid.origin = box.center () - 0.5 * edge * grid.counts.cast<double> ();
    grid.margin = options.margin_fraction * edge;
    return grid;
  }
} // namespace pcl_sparse
