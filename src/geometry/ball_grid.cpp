#include <pcl_sparse/geometry/ball_grid.h>

#include <pcl_sparse/common/error.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    // Three cell coordinates of 21 bits each make a 64-bit key.
    constexpr double kMaxCellsPerAxis = 2097152.0;
    // Filings per ball on average before the cell doubles (a few huge balls would fill millions of cells).
    constexpr double kMaxFilingsPerBall = 64.0;

    std::uint64_t
    cellKey (std::int64_t x, std::int64_t y, std::int64_t z)
    {
      return (static_cast<std::uint64_t> (x) << 42) | (static_cast<std::uint64_t> (y) << 21) | static_cast<std::uint64_t> (z);
    }

    /// A ball's box, a little wider than the ball for the rounding of a point's cell (its side in ulps).
    Eigen::AlignedBox3d
    paddedBox (const Eigen::Vector3d& centre, double radius)
    {
      const double pad = 1e-9 * (radius + centre.cwiseAbs ().maxCoeff ()) + 1e-300;
      return Eigen::AlignedBox3d (centre.array () - (radius + pad), centre.array () + (radius + pad));
    }
  } // namespace

  BallGrid::BallGrid (const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& radii, double cell)
  {
    if (centres.size () != radii.size ())
      throw Error ("BallGrid: " + std::to_string (centres.size ()) + " centres for " + std::to_string (radii.size ()) +
                   " radii");
    if (!(cell > 0.0) || !std::isfinite (cell))
      throw Error ("BallGrid: the cell must be positive and finite, got " + std::to_string (cell));
    Eigen::AlignedBox3d all;  // empty
    std::vector<Eigen::AlignedBox3d> boxes;
    boxes.reserve (centres.size ());
    for (std::size_t i = 0; i < centres.size (); ++i)
    {
      if (!centres[i].allFinite () || !std::isfinite (radii[i]) || !(radii[i] >= 0.0))
        throw Error ("BallGrid: ball " + std::to_string (i) + " has a non-finite centre or a negative or non-finite radius");
      boxes.push_back (paddedBox (centres[i], radii[i]));
      all.extend (boxes.back ());
    }
    if (boxes.empty ())
      return;
    if (!all.sizes ().allFinite ())  // centres and radii finite, their sum not: no grid can count its cells
      throw Error ("BallGrid: the balls span more than a double holds");
    low_ = all.min ();
    cell_ = cell;
    auto span = [this] (const Eigen::AlignedBox3d& b, int a) {  // cells the box meets along axis a
      return std::floor ((b.max ()[a] - low_[a]) / cell_) - std::floor ((b.min ()[a] - low_[a]) / cell_) + 1.0;
    };
    for (;;)
    {
      if (!(all.sizes ().maxCoeff () / cell_ < kMaxCellsPerAxis - 2.0))
      {
        cell_ *= 2.0;
        continue;
      }
      double filings = 0.0;
      for (const Eigen::AlignedBox3d& b : boxes)
        filings += span (b, 0) * span (b, 1) * span (b, 2);
      if (filings <= kMaxFilingsPerBall * static_cast<double> (boxes.size ()))
        break;
      cell_ *= 2.0;
    }
    for (int a = 0; a < 3; ++a)
      cells_[a] = static_cast<int> (std::floor (all.sizes ()[a] / cell_)) + 1;

    std::vector<std::pair<std::uint64_t, int>> filed;
    for (std::size_t i = 0; i < boxes.size (); ++i)
    {
      Eigen::Vector3i lo, hi;
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::clamp (static_cast<int> (std::floor ((boxes[i].min ()[a] - low_[a]) / cell_)), 0, cells_[a] - 1);
        hi[a] = std::clamp (static_cast<int> (std::floor ((boxes[i].max ()[a] - low_[a]) / cell_)), 0, cells_[a] - 1);
      }
      for (int x = lo.x (); x <= hi.x (); ++x)
        for (int y = lo.y (); y <= hi.y (); ++y)
          for (int z = lo.z (); z <= hi.z (); ++z)
            filed.emplace_back (cellKey (x, y, z), static_cast<int> (i));
    }
    std::sort (filed.begin (), filed.end ());  // by cell, then ball index
    std::size_t occupied = 0;
    for (std::size_t k = 0; k < filed.size (); ++k)
      occupied += k == 0 || filed[k].first != filed[k - 1].first;
    balls_.reserve (filed.size ());
    ranges_.reserve (occupied);
    for (std::size_t k = 0; k < filed.size ();)
    {
      const std::uint64_t key = filed[k].first;
      const auto begin = static_cast<std::uint32_t> (balls_.size ());
      for (; k < filed.size () && filed[k].first == key; ++k)
        balls_.push_back (filed[k].second);
      ranges_.emplace (key, std::make_pair (begin, static_cast<std::uint32_t> (balls_.size ())));
    }
  }

  bool
  BallGrid::cellOf (const Eigen::Vector3d& p, std::uint64_t& key) const
  {
    if (balls_.empty ())
      return false;
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a)
    {
      const double t = std::floor ((p[a] - low_[a]) / cell_);
      if (!(t >= 0.0 && t < static_cast<double> (cells_[a])))  // outside every box, or not a number
        return false;
      c[a] = static_cast<std::int64_t> (t);
    }
    key = cellKey (c[0], c[1], c[2]);
    return true;
  }

  std::pair<const int*, const int*>
  BallGrid::candidates (const Eigen::Vector3d& p) const
  {
    std::uint64_t key;
    if (!cellOf (p, key))
      return {nullptr, nullptr};
    const auto it = ranges_.find (key);
    if (it == ranges_.end ())
      return {nullptr, nullptr};
    return {balls_.data () + it->second.first, balls_.data () + it->second.second};
  }
} // namespace pcl_sparse
