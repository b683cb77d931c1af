#include <pcl_sparse/tiles/tile_statistics.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pcl_sparse
{
  std::vector<std::size_t>
  neighbourTiles (const TileGrid& grid, std::size_t t, int reach)
  {
    const Eigen::Vector3i c = grid.coordinates (t);
    std::vector<std::size_t> tiles;
    for (int k = std::max (0, c.z () - reach); k <= std::min (grid.counts.z () - 1, c.z () + reach); ++k)
      for (int j = std::max (0, c.y () - reach); j <= std::min (grid.counts.y () - 1, c.y () + reach); ++j)
        for (int i = std::max (0, c.x () - reach); i <= std::min (grid.counts.x () - 1, c.x () + reach); ++i)
          tiles.push_back ((static_cast<std::size_t> (k) * grid.counts.y () + j) * grid.counts.x () + i);
    std::sort (tiles.begin (), tiles.end ());
    return tiles;
  }

  namespace
  {
    /// Where the encoder of \a moved's tile coded point \a number, at \a position in the input.
    Eigen::Vector3d
    codedPosition (const MovedPoints* moved, std::size_t number, const Eigen::Vector3d& position)
    {
      if (!moved)
        return position;
      const auto at = std::lower_bound (moved->numbers.begin (), moved->numbers.end (), number);
      if (at == moved->numbers.end () || *at != number)
        return position;
      return position + moved->offsets[static_cast<std::size_t> (at - moved->numbers.begin ())].cast<double> ();
    }
  } // namespace

  TileErrors
  TiledErrorSums::measureTile (const TileSource& source, std::size_t t, const std::vector<TilePatches>& near)
  {
    TileErrors result;
    const TileInput input = source.loadTile (t);
    if (input.empty ())
      return result;
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
    for (const TilePatches& span : near)
    {
      if (span.moved && span.moved->offsets.size () != span.moved->numbers.size ())
        throw Error ("tiledModelStatistics: " + std::to_string (span.moved->offsets.size ()) + " offsets for " +
                     std::to_string (span.moved->numbers.size ()) + " moved points");
      for (const PatchCode* code = span.first; code != span.first + span.count; ++code)
      {
        for (const int vertex : code->vertices)
        {
          const auto at = std::lower_bound (numbers.begin (), numbers.end (), static_cast<std::size_t> (vertex));
          if (at == numbers.end () || *at != static_cast<std::size_t> (vertex))
            continue;
          const std::size_t v = static_cast<std::size_t> (at - numbers.begin ());
          // (x', y') from the point where the patch's tile coded it, as the encoder made them (Patch::toLocal
          // over the radius codePatch stores, support_scale included): the same up to the last bits, so held
          // vertex lists need not keep them.
          const Eigen::Vector2d xy = code->toLocal (codedPosition (span.moved, numbers[v], positions[v])).head<2> ();
          const double h = span.basis ? span.basis->evaluateCodeValue (code->atoms, code->coefficients, xy.x (), xy.y ()) : 0.0;
          sum[v] += code->toWorld (Eigen::Vector3d (xy.x (), xy.y (), h));
          ++count[v];
        }
      }
    }
    for (std::size_t v = 0; v < numbers.size (); ++v)
      if (count[v] == 0)
        ++result.uncovered;
      else
      {
        const double e = (Eigen::Vector3d (sum[v] / count[v]) - positions[v]).norm ();
        result.squares += e * e;
        result.absolute += e;
        result.largest = std::max (result.largest, e);
        ++result.covered;
      }
    return result;
  }

  void
  TiledErrorSums::add (const TileErrors& tile)
  {
    uncovered_ += tile.uncovered;
    squares_ += tile.squares;
    absolute_ += tile.absolute;
    largest_ = std::max (largest_, tile.largest);
    covered_ += tile.covered;
  }

  ModelStatistics
  TiledErrorSums::statistics (const SparseSurfaceModel& model, std::size_t total_points) const
  {
    ModelStatistics stats;
    stats.num_vertices = total_points;
    stats.num_patches = model.patches.size ();
    stats.num_nonzeros = model.numNonZeros ();
    stats.compression_ratio = model.compressionRatio ();
    // Tiles hold the faces' vertices only: a mesh's vertices in no face are in no tile, so never measured.
    stats.uncovered = std::max (uncovered_, total_points > covered_ ? total_points - covered_ : 0);
    stats.max_error = largest_;
    stats.rmse = covered_ > 0 ? std::sqrt (squares_ / static_cast<double> (covered_)) : 0.0;
    const double diagonal = model.bbox_diagonal;
    stats.rmse_over_diagonal = diagonal > 0.0 ? stats.rmse / diagonal : 0.0;
    stats.mean_error_over_diagonal =
      diagonal > 0.0 && covered_ > 0 ? absolute_ / static_cast<double> (covered_) / diagonal : 0.0;
    return stats;
  }

  ModelStatistics
  tiledModelStatistics (const TileSource& source, TiledModel& tiled, const TiledStatisticsOptions& options)
  {
    const TileGrid& grid = source.grid ();
    if (grid.size () != tiled.grid.size () || grid.origin != tiled.grid.origin || grid.edge != tiled.grid.edge)
      throw Error ("tiledModelStatistics: the model's grid is not the source's");
    SparseSurfaceModel& model = tiled.model;
    std::vector<TileRange*> range_of (grid.size (), nullptr);
    for (TileRange& range : tiled.tiles)
      range_of.at (range.tile) = &range;
    // The last tile measured that needs each tile's patches: their vertex lists can go after it.
    std::vector<std::size_t> last_use (grid.size (), 0);
    std::vector<bool> used (grid.size (), false);
    for (std::size_t t = 0; t < grid.size (); ++t)
      if (source.corePoints (t) > 0)
        for (const std::size_t u : neighbourTiles (grid, t, options.reach))
        {
          last_use[u] = t;
          used[u] = true;
        }
    TiledErrorSums sums;
    for (std::size_t t = 0; t < grid.size (); ++t)
    {
      if (source.corePoints (t) == 0)
        continue;
      std::vector<TilePatches> near;
      for (const std::size_t u : neighbourTiles (grid, t, options.reach))
        if (range_of[u])
          near.push_back ({model.patches.data () + range_of[u]->first_patch, range_of[u]->num_patches, model.basis.get (),
                           &range_of[u]->moved});
      sums.addTile (source, t, near);
      for (const std::size_t u : neighbourTiles (grid, t, options.reach))
        if (options.drop_vertices && range_of[u] && used[u] && last_use[u] == t)
        {
          for (std::size_t p = range_of[u]->first_patch; p < range_of[u]->first_patch + range_of[u]->num_patches; ++p)
          {
            std::vector<int> ().swap (model.patches[p].vertices);
            std::vector<Eigen::Vector2d> ().swap (model.patches[p].vertex_xy);
          }
          range_of[u]->moved = MovedPoints ();
        }
    }
    return sums.statistics (model, source.totalPoints ());
  }
} // namespace pcl_sparse
