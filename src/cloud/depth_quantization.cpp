#include <pcl_sparse/cloud/depth_quantization.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// The rule of steps: a coordinate that \a points take at least 2 and fewer than points / 100 distinct
    /// values of (findDepthQuantization on one scan, SteppedAxes on a whole input).
    bool
    fewEnoughValues (std::size_t distinct, std::size_t points)
    {
      return distinct >= 2 && distinct < points / 100;
    }
  } // namespace

  double
  DepthQuantization::effectiveLength (const std::vector<Eigen::Vector3d>& positions, int a, int b) const
  {
    const Eigen::Vector3d d = positions[b] - positions[a];
    if (axis < 0)
      return d.norm ();
    const double step = stepAbove (std::min (level[a], level[b]));
    const double along = std::abs (d[axis]), reduced = std::max (0.0, along - step);
    return std::sqrt (std::max (0.0, d.squaredNorm () - along * along) + reduced * reduced);
  }

  DepthQuantization
  findDepthQuantization (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& used,
                         const Eigen::Vector3d& viewpoint, std::optional<std::uint8_t> stepped_axes)
  {
    DepthQuantization q;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero ();
    std::size_t count = 0;
    for (std::size_t i = 0; i < positions.size (); ++i)
      if (used[i] && positions[i] != viewpoint)
      {
        mean += (positions[i] - viewpoint).normalized ();
        ++count;
      }
    if (count < 100)
      return q;
    mean /= static_cast<double> (count);
    int axis;
    if (!(mean.cwiseAbs ().maxCoeff (&axis) >= 0.7) || (stepped_axes && !(*stepped_axes >> axis & 1)))
      return q;
    std::vector<double> values;
    values.reserve (count);
    for (std::size_t i = 0; i < positions.size (); ++i)
      if (used[i])
        values.push_back (positions[i][axis]);
    std::sort (values.begin (), values.end ());
    values.erase (std::unique (values.begin (), values.end ()), values.end ());
    if (values.size () < 2 || (!stepped_axes && !fewEnoughValues (values.size (), count)))
      return q;
    q.axis = axis;
    q.levels = values;
    q.level.assign (positions.size (), -1);
    for (std::size_t i = 0; i < positions.size (); ++i)
      if (used[i])
        q.level[i] = static_cast<int> (std::lower_bound (values.begin (), values.end (), positions[i][axis]) - values.begin ());
    return q;
  }

  void
  SteppedAxes::add (const Eigen::Vector3d& p)
  {
    for (int a = 0; a < 3; ++a)
      if (!continuous_[a] && values_[a].insert (p[a]).second && values_[a].size () > cap_)
      {
        continuous_[a] = true;
        values_[a] = std::unordered_set<double> ();
      }
  }

  std::uint8_t
  SteppedAxes::judge (std::size_t points) const
  {
    std::uint8_t bits = 0;
    for (int a = 0; a < 3; ++a)
      if (!continuous_[a] && fewEnoughValues (values_[a].size (), points))
        bits |= static_cast<std::uint8_t> (1u << a);
    return bits;
  }
} // namespace pcl_sparse
