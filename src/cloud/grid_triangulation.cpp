#include <pcl_sparse/cloud/grid_triangulation.h>
#include <pcl_sparse/common/thread_count.h>

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
    diagonal (const std::vector<Eigen::Vector3d>& positions, int p, int q, double limit, const ShadowRule& shadow,
              const DepthQuantization* steps)
    {
      if (p < 0 || q < 0)
        return -1.0;
      const double length = steps ? steps->effectiveLength (positions, p, q) : (positions[p] - positions[q]).norm ();
      return (length <= limit && !shadow.shadowed (p, positions[p], positions[q])) ? length : -1.0;
    }

    /// > 0 when the triangle (image winding) faces the side \a facing of its corners' normals; 1 without normals.
    double
    facingOf (const Eigen::Vector3i& t, const std::vector<Eigen::Vector3d>& positions,
              const std::vector<Eigen::Vector3d>* normals, double facing)
    {
      if (!normals)
        return 1.0;
      const Eigen::Vector3d& a = positions[t[0]];
      const Eigen::Vector3d area = (positions[t[1]] - a).cross (positions[t[2]] - a);
      return facing * area.dot ((*normals)[t[0]] + (*normals)[t[1]] + (*normals)[t[2]]);
    }

    /// The cell's triangles across a-d (\a ad) or b-c, where their grid edges are accepted.
    int
    splitCell (const Cell& k, bool ad, Eigen::Vector3i out[2])
    {
      int count = 0;
      if (ad)
      {
        if (k.c >= 0 && k.ac && k.cd)
          out[count++] = Eigen::Vector3i (k.a, k.c, k.d);
        if (k.b >= 0 && k.ab && k.bd)
          out[count++] = Eigen::Vector3i (k.a, k.d, k.b);
      }
      else
      {
        if (k.a >= 0 && k.ac && k.ab)
          out[count++] = Eigen::Vector3i (k.a, k.c, k.b);
        if (k.d >= 0 && k.cd && k.bd)
          out[count++] = Eigen::Vector3i (k.b, k.c, k.d);
      }
      return count;
    }

    void
    triangulateCell (const Cell& k, const std::vector<Eigen::Vector3d>& positions, double gap_factor,
                     const ShadowRule& shadow, const std::vector<Eigen::Vector3d>* normals, double facing,
                     const DepthQuantization* steps, std::vector<Eigen::Vector3i>& out)
    {
      const double limit = gap_factor * std::hypot (k.sx, k.sy);
      const double ad = diagonal (positions, k.a, k.d, limit, shadow, steps);
      const double bc = diagonal (positions, k.b, k.c, limit, shadow, steps);
      const bool all = k.a >= 0 && k.b >= 0 && k.c >= 0 && k.d >= 0;
      const bool can_ad = ad >= 0.0 && (all || k.b < 0 || k.c < 0), can_bc = bc >= 0.0 && (all || k.a < 0 || k.d < 0);
      Eigen::Vector3i with_ad[2], with_bc[2];
      const int n_ad = can_ad ? splitCell (k, true, with_ad) : 0, n_bc = can_bc ? splitCell (k, false, with_bc) : 0;
      // The split with more triangles facing like their corners' normals, then the shorter diagonal.
      int good_ad = 0, good_bc = 0;
      for (int t = 0; t < n_ad; ++t)
        good_ad += facingOf (with_ad[t], positions, normals, facing) > 0.0 ? 1 : 0;
      for (int t = 0; t < n_bc; ++t)
        good_bc += facingOf (with_bc[t], positions, normals, facing) > 0.0 ? 1 : 0;
      const bool use_ad = can_ad && (!can_bc || good_ad > good_bc || (good_ad == good_bc && ad <= bc));
      const int count = use_ad ? n_ad : can_bc ? n_bc : 0;
      for (int t = 0; t < count; ++t)
        out.push_back (use_ad ? with_ad[t] : with_bc[t]);
    }
  } // namespace

  std::vector<Eigen::Vector3i>
  triangulateImageGrid (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, const GridEdges& edges,
                        const std::vector<std::uint8_t>& usable, double gap_factor, const ShadowRule& shadow,
                        int num_threads, const std::vector<Eigen::Vector3d>* normals, double facing,
                        const DepthQuantization* steps)
  {
    if (steps && !steps->active ())
      steps = nullptr;
    const int rows = grid.height - 1;
    if (rows <= 0 || grid.width < 2)
      return {};
    std::vector<std::vector<Eigen::Vector3i>> per_row (rows);
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 8)
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x + 1 < grid.width; ++x)
        triangulateCell (cellAt (grid, edges, usable, x, y), positions, gap_factor, shadow, normals, facing, steps,
                         per_row[y]);
    std::vector<Eigen::Vector3i> triangles;
    for (const auto& row : per_row)
      triangles.insert (triangles.end (), row.begin (), row.end ());
    return triangles;
  }
} // namespace pcl_sparse
