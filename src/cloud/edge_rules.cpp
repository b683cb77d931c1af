#include <pcl_sparse/cloud/edge_rules.h>

#include <cmath>

namespace pcl_sparse
{
  ShadowRule::ShadowRule (const Viewpoints* viewpoints, double angle_degrees) : viewpoints_ (viewpoints)
  {
    cos_limit_ = angle_degrees > 0.0 ? std::cos (angle_degrees * M_PI / 180.0) : 2.0;
  }

  bool
  ShadowRule::shadowed (std::size_t i, const Eigen::Vector3d& a, const Eigen::Vector3d& b) const
  {
    if (!active ())
      return false;
    const Eigen::Vector3d edge = b - a;
    const Eigen::Vector3d sight = 0.5 * (a + b) - viewpoints_->of (i);
    const double norms = edge.norm () * sight.norm ();
    if (!(norms > 0.0))
      return false;
    return std::abs (edge.dot (sight)) > cos_limit_ * norms;
  }
} // namespace pcl_sparse
