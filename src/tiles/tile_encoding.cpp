#include <pcl_sparse/tiles/tile_encoding.h>

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cmath>
#include <memory>
#include <mutex>
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
    const Eigen::Vector3i here = grid.coordinates (t);
    result.reach = 1;
    for (PatchCode& patch : result.model.patches)
      if (grid.tileOf (patch.origin) == t)
      {
        // How far the points it lists lie (TiledSurfaceEncoder relies on phase-0 patches listing points of
        // the neighbours' cores only).
        for (const int v : patch.vertices)
        {
          const std::size_t i = static_cast<std::size_t> (v);
          const Eigen::Vector3d p = input.scan ? input.scan->worldPosition (i) : input.mesh->vertices[i];
          result.reach = std::max (result.reach, (grid.coordinates (grid.tileOf (p)) - here).cwiseAbs ().maxCoeff ());
        }
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

  namespace
  {
    /// The order the wavefront measures tiles in: slab by slab along the axis with the most tiles (ties: the
    /// later axis, z before y before x, so that the order stays closer to the tiles' numbers), ascending
    /// within a slab. Tiles with core points only.
    std::vector<std::size_t>
    measuringOrder (const TileGrid& grid, const std::vector<std::size_t>& core)
    {
      int axis = 2;
      for (int a = 1; a >= 0; --a)
        if (grid.counts[a] > grid.counts[axis])
          axis = a;
      std::vector<std::size_t> order;
      for (std::size_t t = 0; t < grid.size (); ++t)
        if (core[t] > 0)
          order.push_back (t);
      std::stable_sort (order.begin (), order.end (), [&] (std::size_t a, std::size_t b) {
        return grid.coordinates (a)[axis] < grid.coordinates (b)[axis];
      });
      return order;
    }

    /// The order the wavefront encodes tiles in: for each tile of \a measured in turn, the tiles around it
    /// not yet listed, a phase-1 tile after the phase-0 tiles around it.
    std::vector<std::size_t>
    encodingOrder (const TileGrid& grid, const std::vector<std::size_t>& core, const std::vector<std::size_t>& measured)
    {
      std::vector<bool> listed (grid.size (), false);
      std::vector<std::size_t> order;
      const auto list = [&] (std::size_t u) {
        if (core[u] > 0 && !listed[u])
        {
          listed[u] = true;
          order.push_back (u);
        }
      };
      for (const std::size_t t : measured)
        for (const std::size_t u : neighbourTiles (grid, t))
        {
          if (tilePhase (grid, u) == 1 && core[u] > 0 && !listed[u])
            for (const std::size_t w : neighbourTiles (grid, u))
              if (tilePhase (grid, w) == 0)
                list (w);
          list (u);
        }
      return order;
    }

    /// What a wavefront encoding gives.
    struct Wavefront
    {
      std::vector<TileEncoding> tiles;  ///< by tile number
      TiledErrorSums sums;              ///< errors of the tiles measured, in ascending order
      double measurement_seconds = 0.0;
      std::size_t peak_held_tiles = 0, peak_held_vertices = 0;
      std::size_t peak_pending_errors = 0;  ///< most errors of measured tiles waiting for a lower tile's
      bool far_reaching = false;        ///< a phase-0 tile's patches list points beyond its neighbours
    };

    /// Vertex listings of a tile's patches.
    std::size_t
    listings (const TileEncoding& tile)
    {
      std::size_t n = 0;
      for (const PatchCode& patch : tile.model.patches)
        n += patch.vertices.size ();
      return n;
    }

    /// Encodes (and measures, with \a measure) every tile with core points in the wavefront order (see
    /// TiledSurfaceEncoder::compute); stops early, with far_reaching set, if a phase-0 tile's patches list
    /// points beyond its neighbours. The threads share one lock: each measures the next tile when it can
    /// (one at a time, in order), else encodes the next tile it can, else waits.
    class WavefrontRun
    {
    public:
      WavefrontRun (const TileSource& source, const SparseSurfaceEncoderOptions& options, int threads, bool measure,
                    bool drop_vertices, const std::function<void (double)>& progress, Wavefront& result)
        : source_ (source), grid_ (source.grid ()), options_ (options), threads_ (threads), measure_ (measure),
          drop_ (drop_vertices), progress_ (progress), result_ (result)
      {
        const std::size_t n = grid_.size ();
        std::vector<std::size_t> core (n);
        for (std::size_t t = 0; t < n; ++t)
          core[t] = source.corePoints (t);
        measured_ = measuringOrder (grid_, core);
        order_ = encodingOrder (grid_, core, measured_);
        // For each tile, the tiles with core points around it; the last tile measured that needs each tile's
        // patches (their vertex lists can go after it), as a position in measured_; the tiles in the order
        // their errors are added (ascending, as tiledModelStatistics adds them: the same bits).
        near_.resize (n);
        last_use_.assign (n, 0);
        for (std::size_t m = 0; m < measured_.size (); ++m)
          for (const std::size_t u : neighbourTiles (grid_, measured_[m]))
            if (core[u] > 0)
            {
              near_[measured_[m]].push_back (u);
              last_use_[u] = m;
            }
        for (std::size_t t = 0; t < n; ++t)
          if (core[t] > 0)
            ascending_.push_back (t);
        pending_.resize (n);
        result_.tiles.assign (n, TileEncoding ());
        state_.assign (n, State::open);
        held_.assign (n, 0);
        errors_.resize (n);
      }

      /// Runs the threads; throws the error of the lowest tile that failed.
      void
      run ()
      {
#pragma omp parallel num_threads(threads_)
        {
          std::unique_lock<std::mutex> lock (mutex_);
          while (!stop_)
          {
            if (measureNext (lock) || encodeNext (lock))
            {
              changed_.notify_all ();
              continue;
            }
            if (encoded_ == order_.size () && (!measure_ || next_measure_ == measured_.size ()))
              break;
            changed_.wait (lock);
          }
        }
        for (const std::string& e : errors_)
          if (!e.empty ())
            throw Error (e);
      }

    private:
      enum class State : unsigned char { open, busy, done };

      /// Whether the tiles around \a t (the phase-0 ones only, if asked) are encoded.
      bool
      encodedAround (std::size_t t, bool phase0_only) const
      {
        for (const std::size_t u : near_[t])
          if ((!phase0_only || tilePhase (grid_, u) == 0) && state_[u] != State::done)
            return false;
        return true;
      }

      /// Measures the next tile in order if the tiles around it are encoded and no other thread is measuring
      /// (the lock is released meanwhile); then adds what can be added in tile order and drops the vertex
      /// lists no tile left to measure needs. Returns whether it measured.
      bool
      measureNext (std::unique_lock<std::mutex>& lock)
      {
        if (!measure_ || measuring_ || next_measure_ >= measured_.size () || !encodedAround (measured_[next_measure_], false))
          return false;
        const std::size_t t = measured_[next_measure_];
        measuring_ = true;
        std::vector<TilePatches> spans;
        for (const std::size_t u : near_[t])
          if (!result_.tiles[u].model.patches.empty ())
            spans.push_back ({result_.tiles[u].model.patches.data (), result_.tiles[u].model.patches.size (),
                              result_.tiles[u].model.basis.get ()});
        lock.unlock ();
        const auto start = std::chrono::steady_clock::now ();
        std::string failure;
        std::unique_ptr<TileErrors> measurement;
        try
        {
          measurement = std::make_unique<TileErrors> (TiledErrorSums::measureTile (source_, t, spans));
          measurement->errors.shrink_to_fit ();
        }
        catch (const std::exception& e)
        {
          failure = e.what ();
        }
        const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
        lock.lock ();
        result_.measurement_seconds += seconds;
        measuring_ = false;
        if (!failure.empty ())
        {
          errors_[t] = failure;
          stop_ = true;
        }
        else
          addInOrder (t, std::move (measurement));
        if (drop_)
          for (const std::size_t u : near_[t])
            if (last_use_[u] == next_measure_ && held_[u] > 0)
              dropVertices (u);
        ++next_measure_;
        return true;
      }

      /// Keeps tile \a t's errors until every lower tile's are added, and adds what it can.
      void
      addInOrder (std::size_t t, std::unique_ptr<TileErrors> measurement)
      {
        pending_points_ += measurement->errors.size ();
        pending_[t] = std::move (measurement);
        while (next_add_ < ascending_.size () && pending_[ascending_[next_add_]])
        {
          const std::unique_ptr<TileErrors> ready = std::move (pending_[ascending_[next_add_++]]);
          result_.sums.add (*ready);
          pending_points_ -= ready->errors.size ();
        }
        result_.peak_pending_errors = std::max (result_.peak_pending_errors, pending_points_);
      }

      /// Clears tile \a u's vertex lists.
      void
      dropVertices (std::size_t u)
      {
        for (PatchCode& patch : result_.tiles[u].model.patches)
        {
          std::vector<int> ().swap (patch.vertices);
          std::vector<Eigen::Vector2d> ().swap (patch.vertex_xy);
        }
        --held_tiles_;
        held_vertices_ -= held_[u];
        held_[u] = 0;
      }

      /// Encodes the first of the next few tiles not started whose phase-0 neighbours are encoded (the lock
      /// is released meanwhile). Returns whether it encoded one.
      bool
      encodeNext (std::unique_lock<std::mutex>& lock)
      {
        // The next few, not just the next: enough for the threads to find work while a phase-1 tile waits for
        // the phase-0 tiles around it.
        const std::size_t window = 2 * static_cast<std::size_t> (threads_) + 2;
        std::size_t pick = order_.size ();
        for (std::size_t k = first_open_; k < order_.size () && k < first_open_ + window; ++k)
          if (state_[order_[k]] == State::open && (tilePhase (grid_, order_[k]) == 0 || encodedAround (order_[k], true)))
          {
            pick = k;
            break;
          }
        if (pick == order_.size ())
          return false;
        const std::size_t t = order_[pick];
        state_[t] = State::busy;
        while (first_open_ < order_.size () && state_[order_[first_open_]] != State::open)
          ++first_open_;
        lock.unlock ();
        TileEncoding tile;
        std::string failure;
        try
        {
          tile = encodeTile (source_, t, options_, 1, tilePhase (grid_, t) == 1 ? coveredAround (t) : std::vector<std::size_t> ());
        }
        catch (const std::exception& e)
        {
          failure = e.what ();
        }
        lock.lock ();
        if (!failure.empty ())
        {
          errors_[t] = failure;
          stop_ = true;
        }
        else if (tilePhase (grid_, t) == 0 && tile.reach > 1)
          result_.far_reaching = stop_ = true;
        held_[t] = listings (tile);
        if (held_[t] > 0)
        {
          ++held_tiles_;
          held_vertices_ += held_[t];
          result_.peak_held_tiles = std::max (result_.peak_held_tiles, held_tiles_);
          result_.peak_held_vertices = std::max (result_.peak_held_vertices, held_vertices_);
        }
        result_.tiles[t] = std::move (tile);
        state_[t] = State::done;
        ++encoded_;
        if (progress_)
          progress_ (static_cast<double> (encoded_) / static_cast<double> (order_.size ()));
        return true;
      }

      /// What the phase-0 tiles around phase-1 tile \a t cover (their vertex lists stay until \a t is
      /// measured, and no thread writes them meanwhile).
      std::vector<std::size_t>
      coveredAround (std::size_t t) const
      {
        std::vector<std::size_t> covered;
        for (const std::size_t u : near_[t])
          if (tilePhase (grid_, u) == 0)
            for (const PatchCode& patch : result_.tiles[u].model.patches)
              for (const int v : patch.vertices)
                covered.push_back (static_cast<std::size_t> (v));
        std::sort (covered.begin (), covered.end ());
        covered.erase (std::unique (covered.begin (), covered.end ()), covered.end ());
        return covered;
      }

      const TileSource& source_;
      const TileGrid& grid_;
      const SparseSurfaceEncoderOptions& options_;
      const int threads_;
      const bool measure_, drop_;
      const std::function<void (double)>& progress_;
      Wavefront& result_;
      std::vector<std::size_t> measured_, order_, ascending_, last_use_;
      std::vector<std::vector<std::size_t>> near_;
      std::vector<std::unique_ptr<TileErrors>> pending_;  ///< errors of tiles measured before a lower tile
      std::vector<State> state_;
      std::vector<std::size_t> held_;  ///< vertex listings held per tile
      std::vector<std::string> errors_;
      std::size_t encoded_ = 0, next_measure_ = 0, next_add_ = 0, first_open_ = 0;
      std::size_t held_tiles_ = 0, held_vertices_ = 0, pending_points_ = 0;
      bool measuring_ = false, stop_ = false;
      std::mutex mutex_;
      std::condition_variable changed_;
    };
  } // namespace

  void
  TiledSurfaceEncoder::compute (TiledModel& model)
  {
    if (!source_)
      fail ("no input: setTileSource");
    options_.validate ();
    const TileGrid& grid = source_->grid ();
    tile_seconds_.assign (grid.size (), 0.0);
    statistics_ = ModelStatistics ();
    measurement_seconds_ = 0.0;
    const int threads = num_threads_ > 0 ? num_threads_ : omp_get_max_threads ();
    const bool drop = measure_ && statistics_options_.drop_vertices;
    {
      Wavefront wavefront;
      WavefrontRun (*source_, options_, threads, measure_, drop, [&] (double fraction) { reportProgress ("tiles", fraction); },
                    wavefront)
        .run ();
      if (!wavefront.far_reaching)
      {
        std::vector<TileEncoding> tiles;
        for (std::size_t t = 0; t < grid.size (); ++t)
          if (source_->corePoints (t) > 0)
          {
            tile_seconds_[t] = wavefront.tiles[t].seconds;
            tiles.push_back (std::move (wavefront.tiles[t]));
          }
        model = mergeTileEncodings (grid, source_->totalPoints (), std::move (tiles));
        if (measure_)
          statistics_ = wavefront.sums.statistics (model.model, source_->totalPoints ());
        measurement_seconds_ = wavefront.measurement_seconds;
        peak_held_tiles_ = wavefront.peak_held_tiles;
        peak_held_vertices_ = wavefront.peak_held_vertices;
        peak_pending_errors_ = wavefront.peak_pending_errors;
        return;
      }
    }
    // A phase-0 tile's patches list points beyond the tiles around it: phase by phase, every phase-1 tile
    // knowing what the whole phase 0 covers, and measured after (every vertex list held till then).
    std::vector<TileEncoding> tiles;
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
    peak_held_tiles_ = peak_held_vertices_ = peak_pending_errors_ = 0;
    for (const TileEncoding& tile : tiles)
    {
      peak_held_tiles_ += listings (tile) > 0;
      peak_held_vertices_ += listings (tile);
    }
    model = mergeTileEncodings (grid, source_->totalPoints (), std::move (tiles));
    if (measure_)
    {
      const auto start = std::chrono::steady_clock::now ();
      statistics_ = tiledModelStatistics (*source_, model, statistics_options_);
      measurement_seconds_ = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
    }
  }
} // namespace pcl_sparse
