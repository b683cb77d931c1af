#include <pcl_sparse/geometry/morton_order.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace pcl_sparse
{
  namespace
  {
    /// Spreads the low 21 bits of \a x to every third bit.
    std::uint64_t
    spreadBits (std::uint64_t x)
    {
      x &= 0x1fffffu;
      x = (x | x << 32) & 0x1f00000000ffffULL;
      x = (x | x << 16) & 0x1f0000ff0000ffULL;
      x = (x | x << 8) & 0x100f00f00f00f00fULL;
      x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
      x = (x | x << 2) & 0x1249249249249249ULL;
      return x;
    }
  } // namespace

  std::vector<int>
  mortonOrder (const std::vector<Eigen::Vector3d>& points, std::vector<int> indices)
  {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant (std::numeric_limits<double>::infinity ()), hi = -lo;
    for (int i : indices)
      if (points[i].allFinite ())
      {
        lo = lo.cwiseMin (points[i]);
        hi = hi.cwiseMax (points[i]);
      }
    const double extent = (hi - lo).maxCoeff ();
    // A single point (or no finite one) has no extent: every code is 0 and the order is by index.
    const double scale = extent > 0.0 && std::isfinite (extent) ? static_cast<double> ((1u << 21) - 1u) / extent : 0.0;
    std::vector<std::pair<std::uint64_t, int>> keyed;
    keyed.reserve (indices.size ());
    for (int i : indices)
    {
      std::uint64_t code = 0;
      if (points[i].allFinite ())
      {
        const Eigen::Vector3d q = (points[i] - lo) * scale;
        code = spreadBits (static_cast<std::uint64_t> (q.x ())) | spreadBits (static_cast<std::uint64_t> (q.y ())) << 1 |
               spreadBits (static_cast<std::uint64_t> (q.z ())) << 2;
      }
      keyed.emplace_back (code, i);
    }
    std::sort (keyed.begin (), keyed.end ());
    keyed.erase (std::unique (keyed.begin (), keyed.end ()), keyed.end ());
    indices.resize (keyed.size ());
    for (std::size_t k = 0; k < keyed.size (); ++k)
      indices[k] = keyed[k].second;
    return indices;
  }

  std::vector<int>
  mortonOrder (const std::vector<Eigen::Vector3d>& points)
  {
    std::vector<int> indices (points.size ());
    std::iota (indices.begin (), indices.end (), 0);
    return mortonOrder (points, std::move (indices));
  }
} // namespace pcl_sparse
