#include "tool_tiling.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_stream.h>
#include <pcl_sparse/io/scan_stream.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
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
      std::string suffix = end ? std::string (end) : std::string ();
      // "2GB" and "2GiB" mean what "2G" does (powers of 1024, as free -h and ulimit count)
      for (const char* tail : {"iB", "ib", "B", "b"})
        if (suffix.size () == 1 + std::char_traits<char>::length (tail) && suffix.compare (1, std::string::npos, tail) == 0)
          suffix.resize (1);
      if (suffix == "K" || suffix == "k")
        scale = 1024.0;
      else if (suffix == "M" || suffix == "m")
        scale = 1024.0 * 1024.0;
      else if (suffix == "G" || suffix == "g")
        scale = 1024.0 * 1024.0 * 1024.0;
      else if (suffix == "T" || suffix == "t")
        scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
      else if (!suffix.empty ())
        throw Error ("option " + option + ": '" + text + "' is not a size (a number with K, M, G or T, as 2G or 2GB)");
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

    namespace
    {
      /// A file over the budget that cannot be read piece by piece (a binary_compressed PCD, for one)
      /// was loaded whole without a word, whatever -memory said (found by a review). A note: off with -q and
      /// --json, as the tool's other notes.
      void
      warnIfLoadedWholeOverBudget (const std::string& path, bool loaded_whole, std::size_t points, double budget)
      {
        if (loaded_whole)
          printNote (format ("%s: %zu points need about %.0f MB, more than -memory's %.0f MB, but its format (a "
                             "binary_compressed PCD, for one) is not read piece by piece: loaded whole. A binary or "
                             "ascii PCD, or a binary PLY, would be spilled into tiles", path.c_str (), points,
                             static_cast<double> (points) * kEncoderBytesPerPoint / 1e6, budget / 1e6));
      }
    } // namespace

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
      // A point takes at least 6 bytes (an ascii "0 0 0\n"; 12 bytes, a binary point's, let an ascii file of
      // short numbers over the budget be loaded whole).
      if (error || static_cast<double> (bytes) / 6.0 * kEncoderBytesPerPoint <= budget)
        return false;  // missing (loading says so) or too small to exceed the budget
      if (ply)
      {
        try
        {
          const MeshStreamReader reader (path);
          mesh = true;
          points = reader.numVertices ();
          const bool over = static_cast<double> (points) * kEncoderBytesPerPoint > budget;
          warnIfLoadedWholeOverBudget (path, over && !reader.isStreamed (), points, budget);
          return reader.isStreamed () && over;
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
        const bool over = static_cast<double> (points) * kEncoderBytesPerPoint > budget;
        warnIfLoadedWholeOverBudget (path, over && !reader.isStreamed (), points, budget);
        return reader.isStreamed () && over;
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
      const std::uint64_t budget = memoryBudget (args);  // checked with -tiles too (-memory abc passed there)
      if (args.integer ("-tiles", options.tiles_along_longest, Range::closed (1, 4096)))
        return true;
      if (static_cast<double> (points) * kEncoderBytesPerPoint <= static_cast<double> (budget))
        return false;
      // A tile's input is its core and margins (up to (1 + 2 x 0.1)^2 = 1.44 times its points on a surface),
      // and kBudgetTilesAtOnce tiles are encoded side by side in half the budget: the other half is for the
      // patches encoded so far (their vertex lists hold about 10 bytes per input point until measured: some
      // 2.5 listings of a 4-byte number).
      options.points_per_tile = std::max<std::size_t> (
        1000, static_cast<std::size_t> (0.5 * static_cast<double> (budget) / kEncoderBytesPerPoint / 1.5 / kBudgetTilesAtOnce));
      options.min_tiles = kRegionTiles;
      return true;
    }
  } // namespace tools
} // namespace pcl_sparse
