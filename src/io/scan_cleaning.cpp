#include <pcl_sparse/io/scan_cleaning.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    template <typename T>
    void
    requireSize (const std::vector<T>& values, std::size_t n, const char* name)
    {
      if (!values.empty () && values.size () != n)
        throw Error (std::string ("ScanCloud: ") + name + " has " + std::to_string (values.size ()) +
                     " entries for " + std::to_string (n) + " points");
    }

    /// Keeps the entries of \a values whose flag is set (a no-op on an empty vector).
    template <typename T>
    void
    keepFlagged (std::vector<T>& values, const std::vector<char>& keep)
    {
      if (values.empty ())
        return;
      std::size_t out = 0;
      for (std::size_t i = 0; i < keep.size (); ++i)
        if (keep[i])
          values[out++] = values[i];
      values.resize (out);
    }

    /// The bits of \a v, -0 as 0 (they compare equal, so they must hash alike).
    std::uint64_t
    bitsOf (double v)
    {
      v += 0.0;
      std::uint64_t bits;
      std::memcpy (&bits, &v, sizeof bits);
      return bits;
    }

    /// splitmix64's finaliser: every input bit moves about half the output bits.
    std::uint64_t
    mixBits (std::uint64_t h)
    {
      h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
      h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
      return h ^ (h >> 31);
    }

    /// Unflags, in file order, each flagged point whose position (exactly, -0 and 0 alike) an earlier flagged
    /// point has: the earliest of equal positions stays. An open-addressing table of point indices, at most
    /// half full: O(n), where sorting the points by position was O(n log n) (loading office1.pcd 0.105 ->
    /// 0.091 s). Returns how many it unflagged.
    std::size_t
    dropRepeatedPositions (const std::vector<Eigen::Vector3d>& positions, std::vector<char>& keep)
    {
      const std::size_t flagged = static_cast<std::size_t> (std::count (keep.begin (), keep.end (), 1));
      std::size_t capacity = 16;
      while (capacity < 2 * flagged)
        capacity *= 2;
      constexpr std::size_t kEmpty = std::numeric_limits<std::size_t>::max ();
      std::vector<std::size_t> table (capacity, kEmpty);
      std::size_t dropped = 0;
      for (std::size_t i = 0; i < positions.size (); ++i)
      {
        if (!keep[i])
          continue;
        const Eigen::Vector3d& p = positions[i];
        const std::uint64_t hash = mixBits (bitsOf (p.x ()) ^ mixBits (bitsOf (p.y ()) ^ mixBits (bitsOf (p.z ()))));
        std::size_t slot = hash & (capacity - 1);
        while (table[slot] != kEmpty && positions[table[slot]] != p)
          slot = (slot + 1) & (capacity - 1);
        if (table[slot] == kEmpty)
          table[slot] = i;
        else
        {
          keep[i] = 0;
          ++dropped;
        }
      }
      return dropped;
    }
  } // namespace

  ScanCleaningReport
  cleanScan (ScanCloud& scan, const ScanCleaningOptions& options)
  {
    const std::size_t n = scan.positions.size ();
    requireSize (scan.normals, n, "normals");
    requireSize (scan.viewpoints, n, "viewpoints");
    requireSize (scan.colors, n, "colors");
    requireSize (scan.intensities, n, "intensities");
    requireSize (scan.indices, n, "indices");
    if (scan.indices.empty ())
    {
      scan.indices.resize (n);
      std::iota (scan.indices.begin (), scan.indices.end (), std::size_t (0));
    }

    ScanCleaningReport report;
    report.input_points = n;
    std::vector<char> keep (n, 1);
    const Eigen::Vector3d sensor = scan.sensor_origin - scan.origin;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Eigen::Vector3d& p = scan.positions[i];
      if (!p.allFinite ())
      {
        keep[i] = 0;
        ++report.non_finite;
      }
      else if (options.drop_at_sensor_origin && p == sensor)
      {
        keep[i] = 0;
        ++report.at_sensor_origin;
      }
    }

    if (options.merge_duplicates)
      report.duplicates_merged = dropRepeatedPositions (scan.positions, keep);

    keepFlagged (scan.positions, keep);
    keepFlagged (scan.normals, keep);
    keepFlagged (scan.viewpoints, keep);
    keepFlagged (scan.colors, keep);
    keepFlagged (scan.intensities, keep);
    keepFlagged (scan.indices, keep);
    report.kept = scan.positions.size ();
    report.non_finite_intensities = static_cast<std::size_t> (
      std::count_if (scan.intensities.begin (), scan.intensities.end (), [] (float v) { return !std::isfinite (v); }));
    scan.report = report;
    return report;
  }
} // namespace pcl_sparse
