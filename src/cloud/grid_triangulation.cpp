#include <pcl_sparse/cloud/grid_triangulation.h>

#include <omp.h>

#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    struct Cell
    {
      int a, b, c, d;               // point indices, -1 where missing or unusable
      bool ab, cd, ac, bd;          // grid edges accepted
      double sx, sy;                // mean spacings of the horizontal and vertical edges
    };

    double
    meanOfExisting (GridEdgeState s0, float v0, GridEdgeState s1, float v1)
    {
      const int count = (s0 != GridEdgeState::Missing ? 1 : 0) + (s1 != GridEdgeState::Missing ? 1 : 0);
      const double sum = (s0 != GridEdgeState::Missing ? v0 : 0.0) + (s1 != GridEdgeState::Missing ? v1 : 0.0);
      return count > 0 ? sum / count : 0.0;
    }

    Cell
    cellAt (const ScanGrid& grid, const GridEdges& edges, const std::vector<std::uint8_t>& usable, int x, int y)
    {
      auto point = [&] (int u, int v) {
        const int i = grid.at (u, v);
        return (i >= 0 && usable[i]) ? i : -1;
      };
      const std::size_t top = static_cast<std::size_t> (y) * grid.width + x, bottom = top + grid.width;
      Cell cell;
      cell.a = point (x, y), cell.b = point (x + 1, y), cell.c = point (x, y + 1), cell.d = point (x + 1, y + 1);
      cell.ab = edges.horizontal_state[top] == GridEdgeState::Accepted;
      cell.cd = edges.horizontal_state[bottom] == GridEdgeState::Accepted;
      cell.ac = edges.vertical_state[top] == GridEdgeState::Accepted;
      cell.bd = edges.vertical_state[top + 1] == GridEdgeState::Accepted;
      cell.sx = meanOfExisting (edges.horizontal_state[top], edges.horizontal_spacing[top], edges.horizontal_state[bottom],
                                edges.horizontal_spacing[bottom]);
      cell.sy = meanOfExisting (edges.vertical_state[top], edges.vertical_spacing[top], edges.vertical_state[top + 1],
                                edges.vertical_spacing[top + 1]);
      cell.sx = cell.sx > 0.0 ? cell.sx : cell.sy;
      cell.sy = cell.sy > 0.0 ? cell.sy : cell.sx;
      return cell;
    }

    /// Length of the diagonal (p, q) if it passes the rules, else -1.
    double
    diagonal (const std::vector<Eigen::Vector3d>& positions, int p, int q, double limit, const ShadowRule& shadow)
    {
      if (p < 0 || q < 0)
        return -1.0;
      const double length = (positions[p] - positions[q]).norm ();
      return (length <= limit && !shadow.shadowed (p, positions[p], positions[q])) ? length : -1.0;
    }

    void
    triangulateCell (const Cell& k, const std::vector<Eigen::Vector3d>& positions, double gap_factor,
                     const ShadowRule& shadow, std::vector<Eigen::Vector3i>& out)
    {
      const double limit = gap_factor * std::hypot (k.sx, k.sy);
      const double ad = diagonal (positions, k.a, k.d, limit, shadow);
      const double bc = diagonal (positions, k.b, k.c, limit, shadow);
      const bool all = k.a >= 0 && k.b >= 0 && k.c >= 0 && k.d >= 0;
      // Across a-d when it is the only diagonal, or the shorter one, or a 3-corner cell without b or c.
      const bool use_ad = ad >= 0.0 && (bc < 0.0 || ad <= bc) && (all || k.b < 0 || k.c < 0);
      const bool use_bc = !use_ad && bc >= 0.0 && (all || k.a < 0 || k.d < 0);
      if (use_ad)
      {
        if (k.c >= 0 && k.ac && k.cd)
          out.emplace_back (k.a, k.c, k.d);
        if (k.b >= 0 && k.ab && k.bd)
          out.emplace_back (k.a, k.d, k.b);
      }
      else if (use_bc)
      {
        if (k.a >= 0 && k.ac && k.ab)
          out.emplace_back (k.a, k.c, k.b);
        if (k.d >= 0 && k.cd && k.bd)
          out.emplace_back (k.b, k.c, k.d);
      }
    }
  } // namespace

  std::vector<Eigen::Vector3i>
  triangulateImageGrid (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, const GridEdges& edges,
                        const std::vector<std::uint8_t>& usable, double gap_factor, const ShadowRule& shadow,
                        int num_threads)
  {
    const int rows = grid.height - 1;
    if (rows <= 0 || grid.width < 2)
      return {};
    std::vector<std::vector<Eigen::Vector3i>> per_row (rows);
    const int threads = num_threads > 0 ? num_threads : omp_get_max_threads ();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 8)
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x + 1 < grid.width; ++x)
        triangulateCell (cellAt (grid, edges, usable, x, y), positions, gap_factor, shadow, per_row[y]);
    std::vector<Eigen::Vector3i> triangles;
    for (const auto& row : per_row)
      triangles.insert (triangles.end (), row.begin (), row.end ());
    return triangles;
  }
} // namespace pcl_sparse
