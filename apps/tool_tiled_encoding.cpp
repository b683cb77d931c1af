#include "tool_tiled_encoding.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/tile_encoding_bytes.h>
#include <pcl_sparse/tiles/tile_encoding.h>
#include <pcl_sparse/tiles/wavefront_measurement.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>

namespace pcl_sparse
{
  namespace tools
  {
    namespace
    {
      /// Encodes \a tiles (a rank's share of one phase) into a message: a flag (0 tiles, 1 an error), the
      /// seconds taken, then the tiles' bytes or the error text. \a keep_xy as for encodeTile.
      std::vector<std::uint8_t>
      encodeShare (const TileSource& source, const std::vector<std::size_t>& tiles, const SparseSurfaceEncoderOptions& options,
                   int threads, const std::vector<std::size_t>& covered, bool keep_xy, const ProcessGroup& group, bool quiet)
      {
        const auto start = std::chrono::steady_clock::now ();
        std::vector<TileEncoding> encodings;
        std::string failure;
        try
        {
          const bool report = !quiet && group.rank () == 0;
          encodings = encodeTiles (source, tiles, options, threads, covered, [&] (std::size_t done) {
            if (report)  // progress goes to stderr, as the single-process progress does
              std::fprintf (stderr, "\rtiles: %zu / %zu of rank 0 (%d ranks)", done, tiles.size (), group.size ()), std::fflush (stderr);
          }, keep_xy);
          if (report && !tiles.empty ())
            std::fputc ('\n', stderr);
        }
        catch (const std::exception& e)
        {
          failure = e.what ();
        }
        const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
        std::vector<std::uint8_t> message (1 + sizeof seconds, failure.empty () ? 0 : 1);
        std::memcpy (message.data () + 1, &seconds, sizeof seconds);
        std::vector<std::uint8_t> body = failure.empty () ? encodeTileEncodings (encodings, source.totalPoints ())
                                                          : std::vector<std::uint8_t> (failure.begin (), failure.end ());
        std::vector<TileEncoding> ().swap (encodings);  // the bytes hold them now
        message.reserve (message.size () + body.size ());
        message.insert (message.end (), body.begin (), body.end ());
        return message;
      }

      /// Decodes the messages of every rank into \a tiles, freeing each once decoded (so the bytes and the
      /// tiles of all ranks are not held twice over); returns the largest seconds. Throws the first rank's
      /// error.
      double
      decodeShares (std::vector<std::vector<std::uint8_t>> messages, std::vector<TileEncoding>& tiles)
      {
        double slowest = 0.0;
        for (std::size_t r = 0; r < messages.size (); ++r)
        {
          const std::vector<std::uint8_t> m = std::move (messages[r]);
          double seconds = 0.0;
          if (m.size () < 1 + sizeof seconds)
            throw Error ("rank " + std::to_string (r) + " sent no tiles");
          std::memcpy (&seconds, m.data () + 1, sizeof seconds);
          slowest = std::max (slowest, seconds);
          const std::uint8_t* data = m.data () + 1 + sizeof seconds;
          const std::size_t size = m.size () - 1 - sizeof seconds;
          if (m[0] != 0)
            throw Error (std::string (reinterpret_cast<const char*> (data), size) + (r > 0 ? " (rank " + std::to_string (r) + ")" : ""));
          decodeTileEncodings (data, size, "tiles of rank " + std::to_string (r), tiles);
        }
        return slowest;
      }

      /// The step at which the ranks encode tile \a t, by groups of \a group slabs along wavefrontAxis: a
      /// phase-0 tile of group g at step g, a phase-1 tile at step g + 2, once the phase-0 tiles of the slabs
      /// around its group (those of groups g - 1 to g + 1) are encoded and what they cover is known.
      std::size_t
      encodingStep (const TileGrid& grid, int axis, int group, std::size_t t)
      {
        return static_cast<std::size_t> (grid.coordinates (t)[axis] / group + 2 * tilePhase (grid, t));
      }

      /// Slabs a step takes: enough that every step gives each rank about two phase-0 tiles, or ranks sit idle
      /// while one encodes (2 M points in 3 x 3 tiles, a slab a step: 1.41x on 2 ranks); one on large grids,
      /// where a slab holds many tiles, so that the band held stays narrow.
      int
      slabsPerStep (const TileSource& source, int axis, int ranks)
      {
        const TileGrid& grid = source.grid ();
        std::size_t phase0 = 0;
        for (std::size_t t = 0; t < grid.size (); ++t)
          phase0 += tilePhase (grid, t) == 0 && source.corePoints (t) > 0;
        const double per_slab = static_cast<double> (phase0) / grid.counts[axis];
        return per_slab > 0.0 ? std::max (1, std::min (grid.counts[axis], static_cast<int> (std::ceil (2.0 * ranks / per_slab)))) : 1;
      }

      /// What a rank says of its tiles of a step, first in each of its messages.
      enum class StepStatus : std::uint8_t { encoded = 0, failed = 1, far_reaching = 2 };

      /// The ranks encode the tiles step by step (encodingStep), each its share of every step's tiles, and
      /// after each step send one message to every rank: what their new phase-0 tiles cover, to the ranks
      /// whose phase-1 tiles lie around them, and to rank 0 the tiles, which it measures as soon as the
      /// tiles around them are in (WavefrontMeasurement). So every rank holds a few slabs of tiles at most,
      /// and sends their vertex lists without (x', y') unless \a keep_xy (encodeTile).
      class SlabRun
      {
      public:
        SlabRun (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                 int threads, bool keep_xy, bool quiet)
          : group_ (group), source_ (source), grid_ (source.grid ()), axis_ (wavefrontAxis (grid_)), options_ (options),
            threads_ (threads), keep_xy_ (keep_xy), quiet_ (quiet)
        {
          // Each step's tiles shared out by points: static, the same on every rank.
          slabs_ = slabsPerStep (source, axis_, group.size ());
          steps_ = static_cast<std::size_t> ((grid_.counts[axis_] + slabs_ - 1) / slabs_) + 2;
          rank_of_.assign (grid_.size (), -1);
          for (std::size_t s = 0; s < steps_; ++s)
          {
            std::vector<std::size_t> points (grid_.size (), 0);
            for (std::size_t t = 0; t < grid_.size (); ++t)
              if (encodingStep (grid_, axis_, slabs_, t) == s)
                points[t] = source.corePoints (t);
            const std::vector<int> ranks = tileRanks (points, group.size ());
            for (std::size_t t = 0; t < grid_.size (); ++t)
              if (ranks[t] >= 0)
              {
                rank_of_[t] = ranks[t];
                ++total_;
              }
          }
        }

        /// Encodes every tile; rank 0 gives them to \a tiles (the other ranks pass none). Returns false, on
        /// every rank, when a tile's patches list points beyond its neighbours (wavefrontMustRestart: a phase-0
        /// tile's phase-1 neighbours may have missed what it covers, and rank 0 measures each tile against its
        /// neighbours' patches only); throws, on every rank, the error of the lowest rank that failed.
        bool
        run (WavefrontMeasurement* tiles)
        {
          for (std::size_t step = 0; step < steps_; ++step)
          {
            std::vector<TileEncoding> mine;
            StepStatus status = StepStatus::encoded;
            std::string failure;
            const double seconds = encodeStep (step, mine, status, failure);
            std::vector<std::vector<std::uint8_t>> messages = compose (mine, status, seconds, failure);
            if (tiles)
            {
              received_ += mine.size ();
              for (TileEncoding& tile : mine)
                tiles->add (std::move (tile));
            }
            std::vector<TileEncoding> ().swap (mine);
            if (!receive (group_.exchange (std::move (messages)), tiles))
              return false;
            for (auto it = covered_.begin (); it != covered_.end ();)  // a phase-0 tile's phase-1 neighbours are done
              it = encodingStep (grid_, axis_, slabs_, it->first) + 3 <= step ? covered_.erase (it) : std::next (it);
            if (tiles)
            {
              tiles->measureReady ();
              if (!quiet_)
                std::fprintf (stderr, "\rtiles: %zu / %zu (%d ranks)%s", received_, total_, group_.size (),
                              step + 1 == steps_ ? "\n" : ""), std::fflush (stderr);
            }
          }
          return true;
        }

        /// Seconds taken: each step's slowest rank, summed.
        double seconds () const { return seconds_; }

      private:
        /// Encodes this rank's tiles of \a step (phase-1 tiles knowing what the phase-0 tiles around them
        /// cover); returns the seconds taken.
        double
        encodeStep (std::size_t step, std::vector<TileEncoding>& mine, StepStatus& status, std::string& failure) const
        {
          const auto start = std::chrono::steady_clock::now ();
          std::vector<std::size_t> these;
          for (std::size_t t = 0; t < grid_.size (); ++t)
            if (rank_of_[t] == group_.rank () && encodingStep (grid_, axis_, slabs_, t) == step)
              these.push_back (t);
          // A phase-0 tile's patches list points of its neighbours' cores only (else the run stops), so one list
          // of what those around this rank's phase-1 tiles cover serves them all.
          std::vector<std::size_t> known;
          for (const auto& entry : covered_)
            known.insert (known.end (), entry.second.begin (), entry.second.end ());
          std::sort (known.begin (), known.end ());
          known.erase (std::unique (known.begin (), known.end ()), known.end ());
          try
          {
            mine = encodeTiles (source_, these, options_, threads_, known, {}, keep_xy_);
            for (const TileEncoding& tile : mine)
              if (wavefrontMustRestart (grid_, tile, true))  // rank 0 measures every tile
                status = StepStatus::far_reaching;
          }
          catch (const std::exception& e)
          {
            status = StepStatus::failed;
            failure = e.what ();
          }
          return std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
        }

        /// The step's message to every rank: the status and seconds, then the error, or what \a mine's phase-0
        /// tiles cover (to the ranks with phase-1 tiles around them: tile, count, ascending points as
        /// differences) and, to rank 0 from the others, the tiles.
        std::vector<std::vector<std::uint8_t>>
        compose (const std::vector<TileEncoding>& mine, StepStatus status, double seconds, const std::string& failure) const
        {
          std::vector<std::vector<std::size_t>> cover (mine.size ());
          for (std::size_t i = 0; i < mine.size (); ++i)
            if (tilePhase (grid_, mine[i].tile) == 0)
              cover[i] = coveredPoints (std::vector<const TileEncoding*> {&mine[i]});
          std::vector<std::vector<std::uint8_t>> messages (static_cast<std::size_t> (group_.size ()));
          for (int d = 0; d < group_.size (); ++d)
          {
            ByteWriter out;
            out.putU8 (static_cast<std::uint8_t> (status));
            out.putF64 (seconds);
            if (status == StepStatus::failed)
              out.putBytes (reinterpret_cast<const std::uint8_t*> (failure.data ()), failure.size ());
            else
            {
              std::vector<std::size_t> sent;
              for (std::size_t i = 0; i < mine.size (); ++i)
                if (tilePhase (grid_, mine[i].tile) == 0 && aroundPhase1Of (mine[i].tile, d))
                  sent.push_back (i);
              out.putVarint (sent.size ());
              for (const std::size_t i : sent)
              {
                out.putVarint (mine[i].tile);
                out.putVarint (cover[i].size ());
                for (std::size_t k = 0; k < cover[i].size (); ++k)
                  out.putVarint (cover[i][k] - (k > 0 ? cover[i][k - 1] : 0));
              }
              if (d == 0 && group_.rank () != 0)
              {
                const std::vector<std::uint8_t> bytes = encodeTileEncodings (mine, source_.totalPoints ());
                out.putBytes (bytes.data (), bytes.size ());
              }
            }
            messages[d] = std::move (out.bytes ());
          }
          return messages;
        }

        /// Whether phase-0 tile \a u lies around a phase-1 tile of rank \a d.
        bool
        aroundPhase1Of (std::size_t u, int d) const
        {
          for (const std::size_t w : neighbourTiles (grid_, u))
            if (tilePhase (grid_, w) == 1 && rank_of_[w] == d)
              return true;
          return false;
        }

        /// Reads every rank's message of a step (freeing each once read): what phase 0 covers, and on rank 0 the
        /// tiles. Returns false if a rank's phase-0 tile reached too far; throws the lowest rank's error.
        bool
        receive (std::vector<std::vector<std::uint8_t>> messages, WavefrontMeasurement* tiles)
        {
          bool far = false;
          double slowest = 0.0;
          for (std::size_t r = 0; r < messages.size (); ++r)
          {
            const std::vector<std::uint8_t> m = std::move (messages[r]);
            const std::string name = "step message of rank " + std::to_string (r);
            ByteReader in (m.data (), m.size (), name);
            const auto status = static_cast<StepStatus> (in.getU8 ("status"));
            slowest = std::max (slowest, in.getF64 ("seconds"));
            if (status == StepStatus::failed)
              throw Error (std::string (reinterpret_cast<const char*> (m.data ()) + in.position (), in.remaining ()) +
                           (r > 0 ? " (rank " + std::to_string (r) + ")" : ""));
            far = far || status == StepStatus::far_reaching;
            const std::uint64_t count = in.getCount ("tiles covering", grid_.size ());
            for (std::uint64_t k = 0; k < count; ++k)
            {
              std::vector<std::size_t>& points = covered_[in.getCount ("tile", grid_.size () - 1)];
              points.resize (in.getCount ("points", source_.totalPoints ()));
              for (std::size_t i = 0; i < points.size (); ++i)
                points[i] = (i > 0 ? points[i - 1] : 0) + in.getVarint ("point");
            }
            if (tiles && r > 0)
            {
              std::vector<TileEncoding> theirs;
              decodeTileEncodings (m.data () + in.position (), in.remaining (), "tiles of rank " + std::to_string (r), theirs);
              received_ += theirs.size ();
              for (TileEncoding& tile : theirs)
                tiles->add (std::move (tile));
            }
          }
          seconds_ += slowest;
          return !far;
        }

        const ProcessGroup& group_;
        const TileSource& source_;
        const TileGrid& grid_;
        const int axis_;
        const SparseSurfaceEncoderOptions& options_;
        const int threads_;
        const bool keep_xy_, quiet_;
        int slabs_ = 1;  ///< slabs a step (slabsPerStep)
        std::size_t steps_ = 0, total_ = 0, received_ = 0;
        std::vector<int> rank_of_;                                 ///< rank encoding each tile (-1: no core points)
        std::map<std::size_t, std::vector<std::size_t>> covered_;  ///< what phase-0 tiles around this rank's phase-1 tiles cover
        double seconds_ = 0.0;
      };

      /// Encodes every tile phase by phase (what TiledSurfaceEncoder falls back to when a phase-0 tile's patches
      /// reach beyond its neighbours): every rank its share of phase 0, which all ranks receive (what it
      /// covers), then of phase 1, gathered on rank 0, which gives them all to \a tiles. Returns the seconds.
      double
      encodeByPhases (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                      int threads, bool keep_xy, bool quiet, WavefrontMeasurement* tiles)
      {
        const TileGrid& grid = source.grid ();
        std::vector<std::size_t> points (grid.size ());
        for (std::size_t t = 0; t < grid.size (); ++t)
          points[t] = tilePhase (grid, t) == 0 ? source.corePoints (t) : 0;
        std::vector<TileEncoding> phase0;
        double seconds = decodeShares (group.allGather (encodeShare (source, tilesOfRank (points, group.size (), group.rank ()),
                                                                     options, threads, {}, keep_xy, group, quiet)),
                                       phase0);
        const std::vector<std::size_t> covered = coveredPoints (phase0);
        if (!tiles)
          std::vector<TileEncoding> ().swap (phase0);  // only rank 0 measures them
        for (std::size_t t = 0; t < grid.size (); ++t)
          points[t] = tilePhase (grid, t) == 1 ? source.corePoints (t) : 0;
        std::vector<std::vector<std::uint8_t>> phase1 =
          group.gather (encodeShare (source, tilesOfRank (points, group.size (), group.rank ()), options, threads, covered,
                                     keep_xy, group, quiet));
        if (!tiles)
          return seconds;
        seconds += decodeShares (std::move (phase1), phase0);
        tiles->addAll (std::move (phase0));  // both phases now
        tiles->measureReady ();
        return seconds;
      }
    } // namespace

    namespace
    {
      /// encodeTilesAcross's work on several ranks with \a options as they are (no bound decided).
      TiledEncodingReport
      encodeAcrossRanks (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                         int threads, bool quiet, const TiledStatisticsOptions& statistics_options, TiledModel& tiled,
                         ModelStatistics& stats);
    } // namespace

    TiledEncodingReport
    encodeTilesAcross (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                       int threads, bool quiet, const TiledStatisticsOptions& statistics_options, TiledModel& tiled,
                       ModelStatistics& stats)
    {
      TiledEncodingReport seconds;
      if (group.size () == 1)
      {
        // One process: no messages, so the tiles' patches (and vertex lists) are held once, not copied, and
        // each tile is measured as soon as the tiles around it are encoded (a wavefront).
        TiledSurfaceEncoder encoder;
        encoder.setTileSource (std::shared_ptr<const TileSource> (&source, [] (const TileSource*) {}));
        encoder.setOptions (options);
        encoder.setNumberOfThreads (threads);
        encoder.setMeasurement (true, statistics_options);
        encoder.setProgressCallback (makeConsoleProgress (quiet));
        const auto start = std::chrono::steady_clock::now ();
        encoder.compute (tiled);
        stats = encoder.getStatistics ();
        seconds.coding = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
        seconds.statistics = encoder.getMeasurementSeconds ();
        seconds.held_tiles = encoder.getPeakHeldTiles ();
        seconds.held_listings = encoder.getPeakHeldVertices ();
        seconds.pending_tiles = encoder.getPeakPendingTiles ();
        return seconds;
      }
      // The compression bound for the whole model, as TiledSurfaceEncoder::compute does: unbounded first,
      // bounded tile by tile only if the whole exceeds it (rank 0 decides, every rank learns it).
      SparseSurfaceEncoderOptions unbounded = options;
      unbounded.max_compression_ratio = 0.0;
      seconds = encodeAcrossRanks (group, source, unbounded, threads, quiet, statistics_options, tiled, stats);
      const bool over = group.rank () == 0 && tiledEncodingOverTheBound (tiled, source.totalPoints (), options);
      if (group.allGather ({static_cast<std::uint8_t> (over ? 1 : 0)})[0][0] != 0)
      {
        tiled = TiledModel ();
        seconds = encodeAcrossRanks (group, source, options, threads, quiet, statistics_options, tiled, stats);
      }
      return seconds;
    }

    namespace
    {
      TiledEncodingReport
      encodeAcrossRanks (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                         int threads, bool quiet, const TiledStatisticsOptions& statistics_options, TiledModel& tiled,
                         ModelStatistics& stats)
      {
        TiledEncodingReport seconds;
        // Slab by slab (SlabRun); phase by phase when a tile's patches reach beyond its neighbours, as
        // TiledSurfaceEncoder does (wavefrontMustRestart).
        std::unique_ptr<WavefrontMeasurement> tiles;
        if (group.rank () == 0)
          tiles = std::make_unique<WavefrontMeasurement> (source, statistics_options.drop_vertices);
        // Vertex lists only for the statistics: without (x', y'), which the measurement recomputes.
        const bool keep_xy = !statistics_options.drop_vertices;
        SlabRun slabs (group, source, options, threads, keep_xy, quiet);
        if (slabs.run (tiles.get ()))
          seconds.coding = slabs.seconds ();
        else
        {
          if (tiles)
            tiles = std::make_unique<WavefrontMeasurement> (source, statistics_options.drop_vertices);
          seconds.coding = encodeByPhases (group, source, options, threads, keep_xy, quiet, tiles.get ());
        }
        if (!tiles)
          return seconds;
        tiled = tiles->takeModel ();
        stats = tiles->sums ().statistics (tiled.model, source.totalPoints ());
        seconds.statistics = tiles->seconds ();
        seconds.held_tiles = tiles->peakHeldTiles ();
        seconds.held_listings = tiles->peakHeldVertices ();
        seconds.pending_tiles = tiles->peakPendingTiles ();
        return seconds;
      }
    } // namespace
  } // namespace tools
} // namespace pcl_sparse
