#include <pcl_sparse/cloud/lidar_rings.h>
#include <pcl_sparse/common/upper_median.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    const double kRingSplit = 0.05 * M_PI / 180.0;  // elevations further apart start a new ring
    const std::size_t kMinRingPoints = 32;

    struct Ring
    {
      std::size_t first, last;  // range in the elevation-sorted order
      double low, high;         // elevation range
    };

    /// Splits the elevation-sorted points into rings; returns false when they are not a lidar's rings.
    bool
    findRings (const std::vector<double>& elevation, const std::vector<int>& by_elevation, std::vector<Ring>& rings)
    {
      std::vector<Ring> all;
      for (std::size_t s = 0; s < by_elevation.size (); ++s)
      {
        const double e = elevation[by_elevation[s]];
        if (all.empty () || e - all.back ().high > kRingSplit)
          all.push_back ({s, s + 1, e, e});
        else
        {
          all.back ().last = s + 1;
          all.back ().high = e;
        }
      }
      std::size_t on_rings = 0;
      for (const auto& ring : all)
        if (ring.last - ring.first >= kMinRingPoints)
        {
          rings.push_back (ring);
          on_rings += ring.last - ring.first;
        }
      if (rings.size () < 2 || rings.size () > 256 || on_rings < 0.95 * by_elevation.size ())
        return false;
      double widest = 0.0, smallest_step = M_PI;
      for (std::size_t r = 0; r < rings.size (); ++r)
      {
        widest = std::max (widest, rings[r].high - rings[r].low);
        if (r > 0)
          smallest_step = std::min (smallest_step, 0.5 * (rings[r].low + rings[r].high - rings[r - 1].low - rings[r - 1].high));
      }
      return widest <= 0.25 * smallest_step;
    }

    /// Median azimuth step between consecutive points of a ring; 0 if none. Steps under a twentieth of the
    /// mean step are left out: repeated points, and the two returns of one pulse in a dual-return frame,
    /// whose azimuths differ by float rounding (a median of those made a grid of billions of columns).
    double
    azimuthStep (const std::vector<double>& azimuth, const std::vector<int>& by_elevation, const std::vector<Ring>& rings)
    {
      const double mean_step = 2.0 * M_PI * static_cast<double> (rings.size ()) / static_cast<double> (by_elevation.size ());
      std::vector<double> steps, ring_azimuths;
      for (const auto& ring : rings)
      {
        ring_azimuths.clear ();
        for (std::size_t s = ring.first; s < ring.last; ++s)
          ring_azimuths.push_back (azimuth[by_elevation[s]]);
        std::sort (ring_azimuths.begin (), ring_azimuths.end ());
        for (std::size_t a = 1; a < ring_azimuths.size (); ++a)
          if (ring_azimuths[a] - ring_azimuths[a - 1] > 0.05 * mean_step)
            steps.push_back (ring_azimuths[a] - ring_azimuths[a - 1]);
      }
      return upperMedian (steps);
    }

    /// Median elevation step between consecutive rings (their centres).
    double
    medianRingStep (const std::vector<Ring>& rings)
    {
      std::vector<double> steps;
      for (std::size_t r = 1; r < rings.size (); ++r)
        steps.push_back (0.5 * (rings[r].low + rings[r].high - rings[r - 1].low - rings[r - 1].high));
      return upperMedian (steps);
    }

    /// A full turn ends one column before it starts again: the first used column, repeated after the last
    /// used one, closes the grid behind the sensor, where a crack of one column was never triangulated
    /// (found by a review). Only when the two are exactly a turn apart: a sweep short of a full turn stays
    /// open, and so does one whose first and last columns hold the same azimuth (repeating the second
    /// column there would give its vertical edges three triangles).
    void
    closeTheTurn (ScanGrid& grid, double step)
    {
      int first = grid.width, last = -1;
      for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x < grid.width; ++x)
          if (grid.at (x, y) >= 0)
            first = std::min (first, x), last = std::max (last, x);
      const long source = last + 1 - std::lround (2.0 * M_PI / step);
      if (last < 0 || source != first || last + 1 >= grid.width)
        return;
      for (int y = 0; y < grid.height; ++y)
        grid.cells[static_cast<std::size_t> (y) * grid.width + last + 1] = grid.at (static_cast<int> (source), y);
      grid.wrap_column = last + 1;
    }
  } // namespace

  bool
  arrangeLidarRings (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& used,
                     const Eigen::Vector3d& sensor, const Eigen::Quaterniond& orientation, ScanGrid& grid,
                     std::size_t& unplaced)
  {
    const std::size_t n = positions.size ();
    const Eigen::Matrix3d to_sensor = orientation.normalized ().toRotationMatrix ().transpose ();
    std::vector<double> elevation (n, 0.0), azimuth (n, 0.0);
    std::vector<int> by_elevation;
    std::size_t candidates = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!used[i])
        continue;
      ++candidates;
      const Eigen::Vector3d d = to_sensor * (positions[i] - sensor);
      const double horizontal = std::hypot (d.x (), d.y ());
      if (!(horizontal > 0.0))
        continue;
      elevation[i] = std::atan2 (d.z (), horizontal);
      azimuth[i] = std::atan2 (d.y (), d.x ());
      by_elevation.push_back (static_cast<int> (i));
    }
    if (by_elevation.size () < 2 * kMinRingPoints)
      return false;
    std::stable_sort (by_elevation.begin (), by_elevation.end (),
                      [&] (int a, int b) { return elevation[a] < elevation[b]; });
    std::vector<Ring> rings;
    if (!findRings (elevation, by_elevation, rings))
      return false;
    const double step = azimuthStep (azimuth, by_elevation, rings);
    if (!(step > 0.0))
      return false;

    // Columns: azimuth steps from -pi, shifted by the mean phase of the points within a step (a regular
    // firing pattern puts them all at one phase, so rounding never splits a column); +1 so that all are >= 0.
    double c = 0.0, s = 0.0;
    for (const int i : by_elevation)
    {
      const double phase = 2.0 * M_PI * ((azimuth[i] + M_PI) / step);
      c += std::cos (phase), s += std::sin (phase);
    }
    const double shift = std::atan2 (s, c) / (2.0 * M_PI);
    // A ring grid far larger than the points (a frame covering a narrow wedge with a fine step) is no
    // range image to build a surface on; nor may its size overflow.
    const double columns = std::ceil (2.0 * M_PI / step) + 3.0;
    if (!(columns * static_cast<double> (rings.size ()) <= 8.0 * static_cast<double> (n) + 4096.0))
      return false;
    ScanGrid result;
    result.width = static_cast<int> (columns);
    result.height = static_cast<int> (rings.size ());
    result.cells.assign (static_cast<std::size_t> (result.width) * result.height, -1);
    // Rows from the highest ring down, like an image. Along a ring, by azimuth, each point takes its column
    // or, when that is taken, the next one (a sensor's step varies a little); further is unplaced.
    std::size_t placed = 0;
    std::vector<int> order;
    for (std::size_t r = 0; r < rings.size (); ++r)
    {
      order.assign (by_elevation.begin () + rings[r].first, by_elevation.begin () + rings[r].last);
      std::sort (order.begin (), order.end (), [&] (int a, int b) {
        return azimuth[a] < azimuth[b] || (azimuth[a] == azimuth[b] && a < b);
      });
      const int row = static_cast<int> (rings.size () - 1 - r);
      int previous = -1;
      for (const int i : order)
      {
        const int ideal = static_cast<int> (std::lround ((azimuth[i] + M_PI) / step - shift)) + 1;
        const int column = std::max (ideal, previous + 1);
        if (column > ideal + 1 || column >= result.width)
          continue;
        result.cells[static_cast<std::size_t> (row) * result.width + column] = i;
        previous = column;
        ++placed;
      }
    }
    if (placed < 0.9 * candidates)
      return false;
    result.row_to_column_angle = medianRingStep (rings) / step;
    closeTheTurn (result, step);
    unplaced = candidates - placed;
    grid = std::move (result);
    return true;
  }
} // namespace pcl_sparse
