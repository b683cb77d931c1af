#include "tool_tiling.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/tile_encoding_bytes.h>
#include <pcl_sparse/tiles/tile_encoding.h>

#include <pcl/console/print.h>

#include <chrono>
#include <cmath>
#include <cstdlib>

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

    bool
    chooseTiling (const CommandLine& args, std::size_t points, TileGridOptions& options)
    {
      options = TileGridOptions ();
      if (args.integer ("-tiles", options.tiles_along_longest, Range::closed (1, 4096)))
        return true;
      const std::uint64_t budget = parseByteSize ("-memory", args.value ("-memory", "2G"));
      if (static_cast<double> (points) * kEncoderBytesPerPoint <= static_cast<double> (budget))
        return false;
      // A tile's input is its core and margins (up to (1 + 2 x 0.1)^2 = 1.44 times its points on a surface).
      options.points_per_tile =
        std::max<std::size_t> (1000, static_cast<std::size_t> (static_cast<double> (budget) / kEncoderBytesPerPoint / 1.5));
      return true;
    }

    double
    encodeTilesAcross (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                       int threads, bool quiet, TiledModel& tiled)
    {
      const TileGrid& grid = source.grid ();
      std::vector<std::size_t> points (grid.size ());
      for (std::size_t t = 0; t < grid.size (); ++t)
        points[t] = source.corePoints (t);
      const std::vector<std::size_t> mine = tilesOfRank (points, group.size (), group.rank ());
      const auto start = std::chrono::steady_clock::now ();
      std::vector<TileEncoding> encodings;
      std::string failure;
      try
      {
        for (std::size_t i = 0; i < mine.size (); ++i)
        {
          encodings.push_back (encodeTile (source, mine[i], options, threads));
          if (!quiet && group.rank () == 0)
            pcl::console::print_info ("\rtiles: %zu / %zu of rank 0 (%d ranks)", i + 1, mine.size (), group.size ());
        }
        if (!quiet && group.rank () == 0 && !mine.empty ())
          pcl::console::print_info ("\n");
      }
      catch (const std::exception& e)
      {
        failure = e.what ();
      }
      const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      // Each rank sends a flag (0 tiles, 1 an error), its seconds and its tiles' bytes.
      std::vector<std::uint8_t> message;
      message.push_back (failure.empty () ? 0 : 1);
      const std::vector<std::uint8_t> body =
        failure.empty () ? encodeTileEncodings (encodings, source.totalPoints ())
                         : std::vector<std::uint8_t> (failure.begin (), failure.end ());
      const unsigned char* s = reinterpret_cast<const unsigned char*> (&seconds);
      message.insert (message.end (), s, s + sizeof seconds);
      message.insert (message.end (), body.begin (), body.end ());
      const std::vector<std::vector<std::uint8_t>> all = group.gather (message);
      if (group.rank () != 0)
      {
        if (!failure.empty ())
          throw Error (failure);
        return seconds;
      }
      std::vector<TileEncoding> tiles;
      double slowest = 0.0;
      for (std::size_t r = 0; r < all.size (); ++r)
      {
        const std::vector<std::uint8_t>& m = all[r];
        if (m.size () < 1 + sizeof (double))
          throw Error ("rank " + std::to_string (r) + " sent no tiles");
        double rank_seconds = 0.0;
        std::copy (m.begin () + 1, m.begin () + 1 + sizeof (double), reinterpret_cast<unsigned char*> (&rank_seconds));
        slowest = std::max (slowest, rank_seconds);
        const std::uint8_t* data = m.data () + 1 + sizeof (double);
        const std::size_t size = m.size () - 1 - sizeof (double);
        if (m[0] != 0)
          throw Error (std::string (reinterpret_cast<const char*> (data), size) + (r > 0 ? " (rank " + std::to_string (r) + ")" : ""));
        decodeTileEncodings (data, size, "tiles of rank " + std::to_string (r), tiles);
      }
      tiled = mergeTileEncodings (grid, source.totalPoints (), std::move (tiles));
      return slowest;
    }
  } // namespace tools
} // namespace pcl_sparse
