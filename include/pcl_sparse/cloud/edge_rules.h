#pragma once
/// \file edge_rules.h
/// The viewpoints a scan was seen from and the shadow rule: an edge nearly along the line of sight joins
/// a foreground surface to the background behind it (or crosses the shadow between them), however short
/// the gap. The gap rule itself depends on how the spacing is known (kNN or image grid) and lives there.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// None, one, or one viewpoint per point, in the scan's local frame.
  struct Viewpoints
  {
    std::vector<Eigen::Vector3d> points;  ///< empty, 1, or #P entries

    bool empty () const { return points.empty (); }
    const Eigen::Vector3d& of (std::size_t i) const { return points.size () == 1 ? points[0] : points[i]; }
  };

  /// The shadow rule: refuses an edge within \a angle_degrees of the line of sight at its midpoint.
  class ShadowRule
  {
  public:
    ShadowRule () = default;
    /// \a viewpoints may be empty (then nothing is shadowed); angle 0 turns the rule off.
    ShadowRule (const Viewpoints* viewpoints, double angle_degrees);

    bool active () const { return viewpoints_ != nullptr && !viewpoints_->empty () && cos_limit_ < 1.0; }

    /// True when the edge (a, b), seen from the viewpoint of point \a i, is shadowed.
    bool shadowed (std::size_t i, const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;

  private:
    const Viewpoints* viewpoints_ = nullptr;
    double cos_limit_ = 2.0;  ///< cosine of the angle; > 1: off
  };
} // namespace pcl_sparse
