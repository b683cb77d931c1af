#include <pcl_sparse/cloud/grid_neighborhoods.h>
#include <pcl_sparse/common/thread_count.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    const long kMaxColumnStride = 8;  // window columns at most 8 azimuth steps apart (rings 16 steps apart)

    /// Lengths of the horizontal (dx = 1) or vertical (dy = 1) edges, -1 where missing.
    std::vector<float>
    edgeLengths (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, int dx, int dy, int threads,
                 const DepthQuantization* steps)
    {
      std::vector<float> lengths (grid.cells.size (), -1.0f);
#pragma omp parallel for num_threads(threads) schedule(static)
      for (int y = 0; y < grid.height - dy; ++y)
        for (int x = 0; x < grid.width - dx; ++x)
        {
          const int a = grid.at (x, y), b = grid.at (x + dx, y + dy);
          if (a >= 0 && b >= 0)
            lengths[static_cast<std::size_t> (y) * grid.width + x] =
              static_cast<float> (steps ? steps->effectiveLength (positions, a, b) : (positions[a] - positions[b]).norm ());
        }
      return lengths;
    }

    /// Median of the existing values among \a count (at most 5), or -1 if none exists.
    float
    medianOfExisting (const float* values, int count)
    {
      float v[5];
      int m = 0;
      for (int q = 0; q < std::min (count, 5); ++q)
        if (values[q] >= 0.0f)
          v[m++] = values[q];
      if (m == 0)
        return -1.0f;
      // Insertion sort of at most 5 values (std::sort's bounds are past GCC 12's -Warray-bounds analysis).
      for (int i = 1; i < m; ++i)
        for (int j = i; j > 0 && v[j] < v[j - 1]; --j)
          std::swap (v[j], v[j - 1]);
      return v[m / 2];
    }

    /// States and spacings of the edges of one direction. The spacing of an edge is the median of three
    /// medians: of the 5 edges along its line centred on it, and of the same on the two parallel lines
    /// beside it (a separable stand-in for the median of the 5 x 3 window, 5 times cheaper, as robust to
    /// a line of long edges).
    void
    classifyDirection (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, int dx, int dy,
                       double gap_factor, const ShadowRule& shadow, int threads, const DepthQuantization* steps,
                       std::vector<GridEdgeState>& state, std::vector<float>& spacing)
    {
      const std::vector<float> lengths = edgeLengths (grid, positions, dx, dy, threads, steps);
      const int W = grid.width, x_end = grid.width - dx, y_end = grid.height - dy;
      const std::ptrdiff_t step = dx == 1 ? 1 : W;  // along the edges' line
      std::vector<float> along (grid.cells.size (), -1.0f);
#pragma omp parallel for num_threads(threads) schedule(static)
      for (int y = 0; y < y_end; ++y)
        for (int x = 0; x < x_end; ++x)
        {
          const std::ptrdiff_t e = static_cast<std::ptrdiff_t> (y) * W + x;
          const int position = dx == 1 ? x : y, end = dx == 1 ? x_end : y_end;
          const int first = std::max (0, position - 2), last = std::min (end - 1, position + 2);
          float window[5];
          for (int q = first; q <= last; ++q)
            window[q - first] = lengths[e + (q - position) * step];
          along[e] = medianOfExisting (window, last - first + 1);
        }
      state.assign (grid.cells.size (), GridEdgeState::Missing);
      spacing.assign (grid.cells.size (), 0.0f);
      const std::ptrdiff_t across = dx == 1 ? W : 1;
#pragma omp parallel for num_threads(threads) schedule(static)
      for (int y = 0; y < y_end; ++y)
        for (int x = 0; x < x_end; ++x)
        {
          const std::ptrdiff_t e = static_cast<std::ptrdiff_t> (y) * W + x;
          if (lengths[e] < 0.0f)
            continue;
          const bool has_before = dx == 1 ? y > 0 : x > 0, has_after = dx == 1 ? y + 1 < y_end : x + 1 < x_end;
          const float window[3] = {has_before ? along[e - across] : -1.0f, along[e], has_after ? along[e + across] : -1.0f};
          spacing[e] = medianOfExisting (window, 3);
          const int a = grid.at (x, y), b = grid.at (x + dx, y + dy);
          if (lengths[e] > gap_factor * spacing[e])
            state[e] = GridEdgeState::Gap;
          else if (shadow.shadowed (a, positions[a], positions[b]))
            state[e] = GridEdgeState::Shadow;
          else
            state[e] = GridEdgeState::Accepted;
        }
    }

    /// Mean spacing of the existing edges (e0, e1 may be out of the grid: pass -1).
    double
    meanSpacing (const std::vector<GridEdgeState>& state, const std::vector<float>& spacing, std::ptrdiff_t e0,
                 std::ptrdiff_t e1)
    {
      double sum = 0.0;
      int count = 0;
      for (const std::ptrdiff_t e : {e0, e1})
        if (e >= 0 && state[e] != GridEdgeState::Missing)
        {
          sum += spacing[e];
          ++count;
        }
      return count > 0 ? sum / count : 0.0;
    }
  } // namespace

  GridEdges
  classifyGridEdges (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, double gap_factor,
                     const ShadowRule& shadow, int num_threads, const DepthQuantization* steps)
  {
    GridEdges edges;
    const int threads = resolveThreadCount (num_threads);
    if (steps && !steps->active ())
      steps = nullptr;
    classifyDirection (grid, positions, 1, 0, gap_factor, shadow, threads, steps, edges.horizontal_state,
                       edges.horizontal_spacing);
    classifyDirection (grid, positions, 0, 1, gap_factor, shadow, threads, steps, edges.vertical_state,
                       edges.vertical_spacing);
    return edges;
  }

  void
  countGridEdges (const GridEdges& edges, std::size_t& candidates, std::size_t& refused, std::size_t& shadowed)
  {
    candidates = refused = shadowed = 0;
    for (const auto* states : {&edges.horizontal_state, &edges.vertical_state})
      for (const GridEdgeState s : *states)
      {
        candidates += s != GridEdgeState::Missing ? 1 : 0;
        refused += (s == GridEdgeState::Gap || s == GridEdgeState::Shadow) ? 1 : 0;
        shadowed += s == GridEdgeState::Shadow ? 1 : 0;
      }
  }

  PointNeighborhoods
  gridNeighborhoods (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, const GridEdges& edges,
                     int window_radius, double gap_factor, int num_threads, const DepthQuantization* steps,
                     double steps_reached)
  {
    if (steps && !steps->active ())
      steps = nullptr;
    const std::size_t n = positions.size ();
    const int r = window_radius;
    // Lidar rings: besides its 2 r + 1 adjacent columns the window takes the columns c s apart (c = 1 .. r),
    // s half a ring step in azimuth steps (4 on the HDL-32E frames), so that it reaches half as far along the
    // ring as across rings. With the adjacent columns alone it saw a strip 8 times higher than wide, whose
    // normal the noise across the strip turned (on walls facing the sensor, along the line of sight); a
    // whole ring step blurred corners (bench/results/scans-notes.md).
    const int column_stride = static_cast<int> (std::clamp (std::lround (0.5 * grid.row_to_column_angle), 1l, kMaxColumnStride));
    std::vector<int> columns;  // window columns in units of k (below)
    for (int c = -r; c <= r; ++c)
      columns.push_back (c);
    for (int c = 1; c <= r; ++c)
      if (c * column_stride > r)  // not one of the adjacent columns
        columns.push_back (-c * column_stride), columns.push_back (c * column_stride);
    const int stride = (2 * r + 1) * static_cast<int> (columns.size ()) - 1;
    PointNeighborhoods hoods;
    hoods.spacing.assign (n, 0.0);
    const std::unique_ptr<int[]> found = uninitialisedNeighborSlots (n, static_cast<std::size_t> (stride));
    std::vector<int> counts (n, 0);
    const int threads = resolveThreadCount (num_threads);
    const double gap2 = gap_factor * gap_factor;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int y = 0; y < grid.height; ++y)
      for (int x = 0; x < grid.width; ++x)
      {
        const int i = grid.at (x, y);
        if (i < 0 || x == grid.wrap_column)  // a repeated point has its own cell
          continue;
        const std::ptrdiff_t e = static_cast<std::ptrdiff_t> (y) * grid.width + x;
        double sx = meanSpacing (edges.horizontal_state, edges.horizontal_spacing, x > 0 ? e - 1 : -1, e);
        double sy = meanSpacing (edges.vertical_state, edges.vertical_spacing, y > 0 ? e - grid.width : -1, e);
        sx = sx > 0.0 ? sx : sy;
        sy = sy > 0.0 ? sy : sx;
        hoods.spacing[i] = std::sqrt (sx * sy);
        int* out = found.get () + static_cast<std::size_t> (i) * stride;
        int k = 1;  // pixels between window pixels
        const double step = steps ? steps->stepAbove (steps->level[i]) : 0.0;
        if (steps_reached > 0.0 && step > 0.0 && hoods.spacing[i] > 0.0)
          k = std::max (1, std::min (12, static_cast<int> (std::ceil (steps_reached * step / hoods.spacing[i] / r))));
        for (int ddy = -r; ddy <= r; ++ddy)
          for (const int ddx : columns)
          {
            const int dx = ddx * k, dy = ddy * k;
            const int u = x + dx, v = y + dy;
            if ((dx == 0 && dy == 0) || u < 0 || v < 0 || u >= grid.width || v >= grid.height)
              continue;
            const int j = grid.at (u, v);
            const double reach2 = gap2 * (dx * dx * sx * sx + dy * dy * sy * sy);
            if (j < 0)
              continue;
            const double d = steps ? steps->effectiveLength (positions, i, j) : (positions[j] - positions[i]).norm ();
            if (d * d <= reach2)
              out[counts[i]++] = j;
          }
      }
    packNeighborSlots (found.get (), static_cast<std::size_t> (stride), counts, hoods, threads);
    return hoods;
  }
} // namespace pcl_sparse
