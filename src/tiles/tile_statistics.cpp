#include <pcl_sparse/tiles/tile_statistics.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// The tiles within one step of tile \a t along each axis (t included), ascending.
    std::vector<std::size_t>
    neighbourTiles (const TileGrid& grid, std::size_t t)
    {
      const Eigen::Vector3i c = grid.coordinates (t);
      std::vector<std::size_t> tiles;
      for (int k = std::max (0, c.z () - 1); k <= std::min (grid.counts.z () - 1, c.z () + 1); ++k)
        for (int j = std::max (0, c.y () - 1); j <= std::min (grid.counts.y () - 1, c.y () + 1); ++j)
          for (int i = std::max (0, c.x () - 1); i <= std::min (grid.counts.x () - 1, c.x () + 1); ++i)
            tiles.push_back ((static_cast<std::size_t> (k) * grid.counts.y () + j) * grid.counts.x () + i);
      std::sort (tiles.begin (), tiles.end ());
      return tiles;
    }

    /// Running sums of the errors.
    struct ErrorSums
    {
      double squares = 0.0, absolute = 0.0, largest = 0.0;
      std::size_t covered = 0, uncovered = 0;
    };

    /// Adds the errors of tile \a t's core points, reconstructed by the patches of \a near (tile ranges).
    void
    measureTile (const TileSource& source, const SparseSurfaceModel& model, std::size_t t,
                 const std::vector<const TileRange*>& near, ErrorSums& sums)
    {
      const TileInput input = source.loadTile (t);
      if (input.empty ())
        return;
      const std::size_t n = input.scan ? input.scan->size () : input.mesh->vertices.size ();
      if (input.point_numbers.size () != n)
        throw Error ("tiledModelStatistics: tile " + std::to_string (t) + " has no point numbers");
      // Core points, by number (a mesh tile lists its vertices in order of first use).
      std::vector<std::pair<std::size_t, Eigen::Vector3d>> core;
      for (std::size_t i = 0; i < n; ++i)
      {
        const Eigen::Vector3d p = input.scan ? input.scan->worldPosition (i) : input.mesh->vertices[i];
        if (source.grid ().tileOf (p) == t)
          core.emplace_back (input.point_numbers[i], p);
      }
      std::sort (core.begin (), core.end (), [] (const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<std::size_t> numbers (core.size ());
      std::vector<Eigen::Vector3d> positions (core.size ());
      for (std::size_t i = 0; i < core.size (); ++i)
      {
        numbers[i] = core[i].first;
        positions[i] = core[i].second;
        if (i > 0 && numbers[i] == numbers[i - 1])
          throw Error ("tiledModelStatistics: tile " + std::to_string (t) + " lists point " + std::to_string (numbers[i]) + " twice");
      }
      std::vector<Eigen::Vector3d> sum (numbers.size (), Eigen::Vector3d::Zero ());
      std::vector<int> count (numbers.size (), 0);
      for (const TileRange* range : near)
        for (std::size_t p = range->first_patch; p < range->first_patch + range->num_patches; ++p)
        {
          const PatchCode& code = model.patches[p];
          const std::size_t m = std::min (code.vertices.size (), code.vertex_xy.size ());
          for (std::size_t k = 0; k < m; ++k)
          {
            const auto at = std::lower_bound (numbers.begin (), numbers.end (), static_cast<std::size_t> (code.vertices[k]));
            if (at == numbers.end () || *at != static_cast<std::size_t> (code.vertices[k]))
              continue;
            const Eigen::Vector2d& xy = code.vertex_xy[k];
            const double h = model.basis ? model.basis->evaluateCodeValue (code.atoms, code.coefficients, xy.x (), xy.y ()) : 0.0;
            const std::size_t v = static_cast<std::size_t> (at - numbers.begin ());
            sum[v] += code.toWorld (Eigen::Vector3d (xy.x (), xy.y (), h));
            ++count[v];
          }
        }
      for (std::size_t v = 0; v < numbers.size (); ++v)
      {
        if (count[v] == 0)
        {
          ++sums.uncovered;
          continue;
        }
        const double e = (Eigen::Vector3d (sum[v] / count[v]) - positions[v]).norm ();
        sums.squares += e * e;
        sums.absolute += e;
        sums.largest = std::max (sums.largest, e);
        ++sums.covered;
      }
    }
  } // namespace

  ModelStatistics
  tiledModelStatistics (const TileSource& source, TiledModel& tiled, const TiledStatisticsOptions& options)
  {
    const TileGrid& grid = source.grid ();
    if (grid.size () != tiled.grid.size () || grid.origin != tiled.grid.origin || grid.edge != tiled.grid.edge)
      throw Error ("tiledModelStatistics: the model's grid is not the source's");
    SparseSurfaceModel& model = tiled.model;
    std::vector<const TileRange*> range_of (grid.size (), nullptr);
    for (const TileRange& range : tiled.tiles)
      range_of.at (range.tile) = &range;
    // The last tile measured that needs each tile's patches: their vertex lists can go after it.
    std::vector<std::size_t> last_use (grid.size (), 0);
    std::vector<bool> used (grid.size (), false);
    for (std::size_t t = 0; t < grid.size (); ++t)
      if (source.corePoints (t) > 0)
        for (const std::size_t u : neighbourTiles (grid, t))
        {
          last_use[u] = t;
          used[u] = true;
        }
    ErrorSums sums;
    for (std::size_t t = 0; t < grid.size (); ++t)
    {
      if (source.corePoints (t) == 0)
        continue;
      std::vector<const TileRange*> near;
      for (const std::size_t u : neighbourTiles (grid, t))
        if (range_of[u])
          near.push_back (range_of[u]);
      measureTile (source, model, t, near, sums);
      for (const std::size_t u : neighbourTiles (grid, t))
        if (options.drop_vertices && range_of[u] && used[u] && last_use[u] == t)
          for (std::size_t p = range_of[u]->first_patch; p < range_of[u]->first_patch + range_of[u]->num_patches; ++p)
          {
            std::vector<int> ().swap (model.patches[p].vertices);
            std::vector<Eigen::Vector2d> ().swap (model.patches[p].vertex_xy);
          }
    }
    ModelStatistics stats;
    stats.num_vertices = source.totalPoints ();
    stats.num_patches = model.patches.size ();
    stats.num_nonzeros = model.numNonZeros ();
    stats.compression_ratio = model.compressionRatio ();
    stats.uncovered = sums.uncovered;
    stats.max_error = sums.largest;
    stats.rmse = sums.covered > 0 ? std::sqrt (sums.squares / static_cast<double> (sums.covered)) : 0.0;
    const double diagonal = model.bbox_diagonal;
    stats.rmse_over_diagonal = diagonal > 0.0 ? stats.rmse / diagonal : 0.0;
    stats.mean_error_over_diagonal =
      diagonal > 0.0 && sums.covered > 0 ? sums.absolute / static_cast<double> (sums.covered) / diagonal : 0.0;
    return stats;
  }
} // namespace pcl_sparse
