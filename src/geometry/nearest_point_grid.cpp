#include <pcl_sparse/geometry/nearest_point_grid.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    /// As FLANN's L2_Simple<float> adds it up, so that the nearest point is the one its kd-tree finds.
    float
    squaredDistance (const Eigen::Vector3f& a, const Eigen::Vector3f& b)
    {
      const Eigen::Vector3f d = a - b;
      return (d.x () * d.x () + d.y () * d.y ()) + d.z () * d.z ();
    }

    /// The nearer of (\a squared, \a index) and the best so far (none: \a best < 0); the lower index among
    /// equal distances, infinite ones too (coordinates near the largest float).
    void
    keepNearer (float squared, int index, float& best_squared, int& best)
    {
      if (best < 0 || squared < best_squared || (squared == best_squared && index < best))
      {
        best_squared = squared;
        best = index;
      }
    }
  } // namespace

  NearestPointGrid::NearestPointGrid (const std::vector<Eigen::Vector3f>& points) : points_ (points)
  {
    if (points_.empty ())
      return;
    Eigen::Vector3f high = points_[0];
    low_ = points_[0];
    for (const Eigen::Vector3f& p : points_)
    {
      if (!p.allFinite ())
        throw Error ("NearestPointGrid: a point is not finite");
      low_ = low_.cwiseMin (p);
      high = high.cwiseMax (p);
    }
    // Cubes filling the box about once per point; a flat axis counts as the side of a cube per point along
    // the longest one, so that a plane's points fill cells of a few points each.
    // In double: the extent of floats near their largest value overflows a float.
    const Eigen::Vector3d extent = high.cast<double> () - low_.cast<double> ();
    const double n = static_cast<double> (points_.size ());
    const double floor_extent = extent.maxCoeff () / std::cbrt (n);
    const double side = std::cbrt (extent.cwiseMax (floor_extent).prod () / n);
    cell_ = side > 0.0 && std::isfinite (side) ? side : 1.0;
    for (int a = 0; a < 3; ++a)
      cells_[a] = static_cast<int> (std::min (extent[a] / cell_, n)) + 1;

    // Counting sort by cell: each cell's points in ascending index.
    const std::size_t num_cells = static_cast<std::size_t> (cells_.cast<std::int64_t> ().prod ());
    std::vector<std::uint32_t> cell_of (points_.size ());
    cell_begin_.assign (num_cells + 1, 0);
    for (std::size_t i = 0; i < points_.size (); ++i)
    {
      const Eigen::Vector3i c = cellOf (points_[i]);
      cell_of[i] = static_cast<std::uint32_t> ((static_cast<std::size_t> (c.z ()) * cells_.y () + c.y ()) * cells_.x () + c.x ());
      ++cell_begin_[cell_of[i] + 1];
    }
    std::partial_sum (cell_begin_.begin (), cell_begin_.end (), cell_begin_.begin ());
    order_.resize (points_.size ());
    std::vector<int> cursor (cell_begin_.begin (), cell_begin_.end () - 1);
    for (std::size_t i = 0; i < points_.size (); ++i)
      order_[cursor[cell_of[i]]++] = static_cast<int> (i);
  }

  Eigen::Vector3i
  NearestPointGrid::cellOf (const Eigen::Vector3f& p) const
  {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a)
    {
      const double x = std::floor ((static_cast<double> (p[a]) - low_[a]) / cell_);
      c[a] = x < 0.0 ? 0 : x >= cells_[a] - 1 ? cells_[a] - 1 : static_cast<int> (x);
    }
    return c;
  }

  int
  NearestPointGrid::nearest (const Eigen::Vector3f& query) const
  {
    int best = -1;
    float best_squared = std::numeric_limits<float>::infinity ();
    if (points_.empty ())
      return best;
    const Eigen::Vector3i c = cellOf (query);
    const int max_ring = cells_.maxCoeff ();
    std::size_t cells_visited = 0;
    for (int r = 0; r <= max_ring; ++r)
    {
      // The cells r rings out: (i, j) on the square's rim take the whole column of k, the others its two ends.
      const Eigen::Vector3i lo = (c.array () - r).max (0), hi = (c.array () + r).min (cells_.array () - 1);
      const auto visit = [&] (int i, int j, int k) {
        const std::size_t cell = (static_cast<std::size_t> (k) * cells_.y () + j) * cells_.x () + i;
        for (int e = cell_begin_[cell]; e < cell_begin_[cell + 1]; ++e)
          keepNearer (squaredDistance (query, points_[order_[e]]), order_[e], best_squared, best);
        ++cells_visited;
      };
      for (int j = lo.y (); j <= hi.y (); ++j)
        for (int i = lo.x (); i <= hi.x (); ++i)
          if (std::abs (i - c.x ()) == r || std::abs (j - c.y ()) == r)
            for (int k = lo.z (); k <= hi.z (); ++k)
              visit (i, j, k);
          else
            for (int k : {c.z () - r, c.z () + r})
              if (k >= 0 && k < cells_.z ())
                visit (i, j, k);
      // Every cell further out lies r full cells beyond the query's (half a cell off for rounding): no point
      // there is nearer. Far from every point the rings grow large; then one pass over all points is cheaper.
      const double reach = (r - 0.5) * cell_;
      if (best >= 0 && r >= 1 && static_cast<double> (best_squared) < reach * reach)
        break;
      if (cells_visited > points_.size ())
      {
        for (std::size_t i = 0; i < points_.size (); ++i)
          keepNearer (squaredDistance (query, points_[i]), static_cast<int> (i), best_squared, best);
        break;
      }
    }
    return best;
  }
} // namespace pcl_sparse
