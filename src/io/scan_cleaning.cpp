#include <pcl_sparse/io/scan_cleaning.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
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
    {
      // Sort the remaining points by position, ties by file order, so the first of each run of equal
      // positions is the earliest in the file.
      std::vector<std::size_t> order;
      order.reserve (n);
      for (std::size_t i = 0; i < n; ++i)
        if (keep[i])
          order.push_back (i);
      const auto less = [&] (std::size_t a, std::size_t b) {
        const Eigen::Vector3d& p = scan.positions[a];
        const Eigen::Vector3d& q = scan.positions[b];
        if (p.x () != q.x ())
          return p.x () < q.x ();
        if (p.y () != q.y ())
          return p.y () < q.y ();
        if (p.z () != q.z ())
          return p.z () < q.z ();
        return a < b;
      };
      std::sort (order.begin (), order.end (), less);
      for (std::size_t k = 1; k < order.size (); ++k)
        if (scan.positions[order[k]] == scan.positions[order[k - 1]])
        {
          keep[order[k]] = 0;
          ++report.duplicates_merged;
        }
    }

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
