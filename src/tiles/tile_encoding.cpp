#include <pcl_sparse/tiles/tile_encoding.h>

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include <omp.h>

namespace pcl_sparse
{
  namespace
  {
    /// Scan tiles with fewer input points than this may fail to make a surface without failing the encoding.
    constexpr std::size_t kSmallScanTile = 256;

    /// Union of two attribute channel lists of the same channels (ranges widened).
    void
    widenChannels (std::vector<AttributeChannelInfo>& into, const std::vector<AttributeChannelInfo>& from, std::size_t t)
    {
      if (into.size () != from.size ())
        throw Error ("mergeTileEncodings: tile " + std::to_string (t) + " has other attribute channels");
      for (std::size_t c = 0; c < into.size (); ++c)
      {
        if (into[c].channel != from[c].channel)
          throw Error ("mergeTileEncodings: tile " + std::to_string (t) + " has other attribute channels");
        into[c].lower = std::min (into[c].lower, from[c].lower);
        into[c].upper = std::max (into[c].upper, from[c].upper);
      }
    }

    /// Whether two bases are the same atoms (same cosine kind and size; another basis: the same object).
    bool
    sameBasis (const SurfaceBasis::ConstPtr& a, const SurfaceBasis::ConstPtr& b)
    {
      if (!a || !b)
        return false;
      const auto* ca = dynamic_cast<const CosineAtoms*> (a.get ());
      const auto* cb = dynamic_cast<const CosineAtoms*> (b.get ());
      if (ca && cb)
        return ca->kind () == cb->kind () && ca->frequencies () == cb->frequencies ();
      return a == b;
    }
  } // namespace

  std::vector<std::size_t>
  coveredPoints (const std::vector<TileEncoding>& tiles)
  {
    std::vector<std::size_t> points;
    for (const TileEncoding& tile : tiles)
      for (const PatchCode& patch : tile.model.patches)
        for (int v : patch.vertices)
          points.push_back (static_cast<std::size_t> (v));
    std::sort (points.begin (), points.end ());
    points.erase (std::unique (points.begin (), points.end ()), points.end ());
    return points;
  }

  TileEncoding
  encodeTile (const TileSource& source, std::size_t t, const SparseSurfaceEncoderOptions& options, int num_threads,
              const std::vector<std::size_t>& covered)
  {
    const auto start = std::chrono::steady_clock::now ();
    const TileGrid& grid = source.grid ();
    TileEncoding result;
    result.tile = t;
    if (source.corePoints (t) == 0)
      return result;
    const TileInput input = source.loadTile (t);
    if (input.empty ())
      return result;
    const std::size_t num_points = input.scan ? input.scan->size () : input.mesh->vertices.size ();
    if (!input.point_numbers.empty () && input.point_numbers.size () != num_points)
      throw Error ("encodeTile: tile " + std::to_string (t) + " has " + std::to_string (input.point_numbers.size ()) +
                   " point numbers for " + std::to_string (num_points) + " points");
    auto seeds = std::make_shared<std::vector<std::uint8_t>> (num_points, 0);
    bool any = false;
    for (std::size_t i = 0; i < num_points; ++i)
    {
      const Eigen::Vector3d p = input.scan ? input.scan->worldPosition (i) : input.mesh->vertices[i];
      if (grid.tileOf (p) == t)
      {
        result.core_bounds.extend (p);
        // Points another tile's patches cover need no patch here (without point numbers: all do).
        const bool done = !input.point_numbers.empty () &&
                          std::binary_search (covered.begin (), covered.end (), input.point_numbers[i]);
        (*seeds)[i] = done ? 0 : 1;
        any = any || !done;
      }
    }
    if (!any)
      return result;
    if (input.mesh && !hasSurfaceArea (*input.mesh))
      return result;

    SparseSurfaceEncoderOptions tile_options = options;
    tile_options.patches.rho = options.patches.rho * static_cast<double> (source.totalPoints ()) / static_cast<double> (num_points);
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    if (input.scan)
      encoder.setInputScan (input.scan);
    else
      encoder.setInputMesh (input.mesh);
    encoder.setOptions (tile_options);
    encoder.setSeedVertices (seeds);
    encoder.setNumberOfThreads (num_threads);
    try
    {
      encoder.compute (result.model);
    }
    catch (const Error& e)
    {
      // A few stray points of a scan in a tile of their own may make no surface (no neighbours close enough):
      // they stay in no patch (statistics count them as uncovered) rather than failing the whole encoding.
      if (input.scan && num_points < kSmallScanTile)
        return result;
      throw Error ("tile " + std::to_string (t) + ": " + e.what ());
    }
    // Every patch is seeded in the core (setSeedVertices); the test guards the ownership rule.
    std::vector<PatchCode> owned;
    owned.reserve (result.model.patches.size ());
    for (PatchCode& patch : result.model.patches)
      if (grid.tileOf (patch.origin) == t)
      {
        for (int& v : patch.vertices)
          v = input.point_numbers.empty () ? v : static_cast<int> (input.point_numbers[static_cast<std::size_t> (v)]);
        if (input.point_numbers.empty ())
        {
          patch.vertices.clear ();
          patch.vertex_xy.clear ();
        }
        // Held until the statistics (a few tens of bytes per input point over the whole model): no slack.
        patch.vertices.shrink_to_fit ();
        patch.vertex_xy.shrink_to_fit ();
        owned.push_back (std::move (patch));
      }
    result.model.patches = std::move (owned);
    result.seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
    return result;
  }

  std::vector<TileEncoding>
  encodeTiles (const TileSource& source, const std::vector<std::size_t>& tiles, const SparseSurfaceEncoderOptions& options,
               int num_threads, const std::vector<std::size_t>& covered, const std::function<void (std::size_t)>& progress)
  {
    const int threads = num_threads > 0 ? num_threads : omp_get_max_threads ();
    const long count = static_cast<long> (tiles.size ());
    std::vector<TileEncoding> result (tiles.size ());
    std::vector<std::string> errors (tiles.size ());
    std::atomic<std::size_t> done (0);
    // Tiles side by side, one thread each, when there are enough of them; else one tile with all threads.
    const bool side_by_side = threads > 1 && count > 1;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if(side_by_side)
    for (long i = 0; i < count; ++i)
    {
      try
      {
        result[i] = encodeTile (source, tiles[i], options, side_by_side ? 1 : threads, covered);
      }
      catch (const std::exception& e)
      {
        errors[i] = e.what ();
      }
      const std::size_t finished = ++done;
      if (progress && omp_get_thread_num () == 0)
        progress (finished);
    }
    for (const std::string& e : errors)
      if (!e.empty ())
        throw Error (e);
    return result;
  }

  TiledModel
  mergeTileEncodings (const TileGrid& grid, std::size_t total_points, std::vector<TileEncoding> tiles)
  {
    std::sort (tiles.begin (), tiles.end (), [] (const TileEncoding& a, const TileEncoding& b) { return a.tile < b.tile; });
    TiledModel tiled;
    tiled.grid = grid;
    SparseSurfaceModel& model = tiled.model;
    model.num_input_vertices = total_points;
    Eigen::AlignedBox3d bounds;
    bool first = true;
    for (std::size_t i = 0; i < tiles.size (); ++i)
    {
      TileEncoding& tile = tiles[i];
      if (i > 0 && tiles[i - 1].tile == tile.tile)
        throw Error ("mergeTileEncodings: tile " + std::to_string (tile.tile) + " given twice");
      if (tile.tile >= grid.size ())
        throw Error ("mergeTileEncodings: tile " + std::to_string (tile.tile) + " out of range");
      if (!tile.core_bounds.isEmpty ())
        bounds.extend (tile.core_bounds);
      if (tile.model.patches.empty ())
        continue;
      if (first)
      {
        model.basis = tile.model.basis;
        model.attribute_channels = tile.model.attribute_channels;
        model.attribute_basis = tile.model.attribute_basis;
        first = false;
      }
      else
      {
        if (!sameBasis (tile.model.basis, model.basis))
          throw Error ("mergeTileEncodings: tile " + std::to_string (tile.tile) + " has another basis");
        widenChannels (model.attribute_channels, tile.model.attribute_channels, tile.tile);
      }
      TileRange range;
      range.tile = tile.tile;
      range.first_patch = model.patches.size ();
      range.num_patches = tile.model.patches.size ();
      tiled.tiles.push_back (range);
      for (PatchCode& patch : tile.model.patches)
        model.patches.push_back (std::move (patch));
    }
    model.bbox_diagonal = bounds.isEmpty () ? 0.0 : bounds.diagonal ().norm ();
    tiled.total_patches = model.patches.size ();
    return tiled;
  }

  void
  TiledSurfaceEncoder::compute (TiledModel& model)
  {
    if (!source_)
      fail ("no input: setTileSource");
    options_.validate ();
    const TileGrid& grid = source_->grid ();
    std::vector<TileEncoding> tiles;
    tile_seconds_.assign (grid.size (), 0.0);
    std::size_t done = 0, todo = 0;
    for (std::size_t t = 0; t < grid.size (); ++t)
      todo += source_->corePoints (t) > 0;
    std::vector<std::size_t> covered;
    for (int phase = 0; phase < 2; ++phase)
    {
      if (phase == 1)
        covered = coveredPoints (tiles);
      std::vector<std::size_t> these;
      for (std::size_t t = 0; t < grid.size (); ++t)
        if (source_->corePoints (t) > 0 && tilePhase (grid, t) == phase)
          these.push_back (t);
      for (TileEncoding& tile : encodeTiles (*source_, these, options_, num_threads_, covered, [&] (std::size_t finished) {
             reportProgress ("tiles", static_cast<double> (done + finished) / static_cast<double> (todo));
           }))
      {
        tile_seconds_[tile.tile] = tile.seconds;
        tiles.push_back (std::move (tile));
      }
      done += these.size ();
    }
    model = mergeTileEncodings (grid, source_->totalPoints (), std::move (tiles));
  }
} // namespace pcl_sparse
