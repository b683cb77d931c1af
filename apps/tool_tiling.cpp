#include "tool_tiling.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/format/tile_encoding_bytes.h>
#include <pcl_sparse/io/mesh_stream.h>
#include <pcl_sparse/io/scan_stream.h>
#include <pcl_sparse/tiles/tile_encoding.h>

#include <pcl/console/print.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace pcl_sparse
{
  namespace tools
  {
    std::uint64_t
    parseByteSize (const std::string& option, const std::string& text)
    {
      char* end = nullptr;
      const double value = std::strtod (text.c_str (), &end);
      double scale = 1.0;
      const std::string suffix = end ? std::string (end) : std::string ();
      if (suffix == "K" || suffix == "k")
        scale = 1024.0;
      else if (suffix == "M" || suffix == "m")
        scale = 1024.0 * 1024.0;
      else if (suffix == "G" || suffix == "g")
        scale = 1024.0 * 1024.0 * 1024.0;
      else if (suffix == "T" || suffix == "t")
        scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
      else if (!suffix.empty ())
        throw Error ("option " + option + ": '" + text + "' is not a size (a number with K, M, G or T)");
      const double bytes = value * scale;
      if (end == text.c_str () || !std::isfinite (bytes) || bytes < 1024.0 * 1024.0 || bytes > 1e18)
        throw Error ("option " + option + ": '" + text + "' is not a size of at least 1M");
      return static_cast<std::uint64_t> (bytes);
    }

    std::uint64_t
    memoryBudget (const CommandLine& args)
    {
      return parseByteSize ("-memory", args.value ("-memory", "2G"));
    }

    bool
    spillsInput (const CommandLine& args, const std::string& path, bool& mesh, std::size_t& points)
    {
      mesh = false;
      points = 0;
      const bool ply = hasExtension (path, ".ply");
      if (!ply && !hasExtension (path, ".pcd"))
        return false;
      const double budget = static_cast<double> (memoryBudget (args));
      std::error_code error;
      const std::uintmax_t bytes = std::filesystem::file_size (path, error);
      if (error || static_cast<double> (bytes) / 12.0 * kEncoderBytesPerPoint <= budget)
        return false;  // missing (loading says so) or too small to exceed the budget
      if (ply)
      {
        try
        {
          const MeshStreamReader reader (path);
          mesh = true;
          points = reader.numVertices ();
          return reader.isStreamed () && static_cast<double> (points) * kEncoderBytesPerPoint > budget;
        }
        catch (const Error&)
        {
          // No faces (a .ply of points, read as a scan) or a bad file (loading says what is wrong).
        }
      }
      mesh = false;
      try
      {
        const ScanStreamReader reader (path);
        points = reader.size ();
        return reader.isStreamed () && static_cast<double> (points) * kEncoderBytesPerPoint > budget;
      }
      catch (const Error&)
      {
        return false;  // loading gives the error
      }
    }

    bool
    chooseTiling (const CommandLine& args, std::size_t points, TileGridOptions& options)
    {
      options = TileGridOptions ();
      if (args.integer ("-tiles", options.tiles_along_longest, Range::closed (1, 4096)))
        return true;
      const std::uint64_t budget = memoryBudget (args);
      if (static_cast<double> (points) * kEncoderBytesPerPoint <= static_cast<double> (budget))
        return false;
      // A tile's input is its core and margins (up to (1 + 2 x 0.1)^2 = 1.44 times its points on a surface),
      // and kBudgetTilesAtOnce tiles are encoded side by side in half the budget: the other half is for the
      // patches encoded so far (their vertex lists hold a few tens of bytes per input point until measured).
      options.points_per_tile = std::max<std::size_t> (
        1000, static_cast<std::size_t> (0.5 * static_cast<double> (budget) / kEncoderBytesPerPoint / 1.5 / kBudgetTilesAtOnce));
      return true;
    }

    namespace
    {
      /// Encodes \a tiles (a rank's share of one phase) into a message: a flag (0 tiles, 1 an error), the
      /// seconds taken, then the tiles' bytes or the error text.
      std::vector<std::uint8_t>
      encodeShare (const TileSource& source, const std::vector<std::size_t>& tiles, const SparseSurfaceEncoderOptions& options,
                   int threads, const std::vector<std::size_t>& covered, const ProcessGroup& group, bool quiet)
      {
        const auto start = std::chrono::steady_clock::now ();
        std::vector<TileEncoding> encodings;
        std::string failure;
        try
        {
          const bool report = !quiet && group.rank () == 0;
          encodings = encodeTiles (source, tiles, options, threads, covered, [&] (std::size_t done) {
            if (report)
              pcl::console::print_info ("\rtiles: %zu / %zu of rank 0 (%d ranks)", done, tiles.size (), group.size ());
          });
          if (report && !tiles.empty ())
            pcl::console::print_info ("\n");
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
    } // namespace

    TiledEncodingReport
    encodeTilesAcross (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                       int threads, bool quiet, const TiledStatisticsOptions& statistics_options, TiledModel& tiled,
                       ModelStatistics& stats)
    {
      const TileGrid& grid = source.grid ();
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
        seconds.pending_errors = encoder.getPeakPendingErrors ();
        return seconds;
      }
      // Phase 0 (tilePhase), shared with every rank: phase-1 tiles need to know what its patches cover.
      std::vector<std::size_t> points (grid.size ());
      for (std::size_t t = 0; t < grid.size (); ++t)
        points[t] = tilePhase (grid, t) == 0 ? source.corePoints (t) : 0;
      std::vector<TileEncoding> tiles;
      seconds.coding = decodeShares (group.allGather (encodeShare (source, tilesOfRank (points, group.size (), group.rank ()),
                                                                   options, threads, {}, group, quiet)),
                                     tiles);
      const std::vector<std::size_t> covered = coveredPoints (tiles);
      if (group.rank () != 0)
        std::vector<TileEncoding> ().swap (tiles);  // only rank 0 merges them
      for (std::size_t t = 0; t < grid.size (); ++t)
        points[t] = tilePhase (grid, t) == 1 ? source.corePoints (t) : 0;
      std::vector<std::vector<std::uint8_t>> phase1 =
        group.gather (encodeShare (source, tilesOfRank (points, group.size (), group.rank ()), options, threads, covered,
                                   group, quiet));
      if (group.rank () != 0)
        return seconds;
      seconds.coding += decodeShares (std::move (phase1), tiles);
      tiled = mergeTileEncodings (grid, source.totalPoints (), std::move (tiles));
      // Rank 0 holds every tile's vertex lists until measured.
      for (const TileRange& range : tiled.tiles)
      {
        std::size_t listings = 0;
        for (std::size_t p = range.first_patch; p < range.first_patch + range.num_patches; ++p)
          listings += tiled.model.patches[p].vertices.size ();
        seconds.held_tiles += listings > 0;
        seconds.held_listings += listings;
      }
      const auto start = std::chrono::steady_clock::now ();
      stats = tiledModelStatistics (source, tiled, statistics_options);
      seconds.statistics = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      return seconds;
    }
  } // namespace tools
} // namespace pcl_sparse
