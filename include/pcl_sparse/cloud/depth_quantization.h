#pragma once
/// \file depth_quantization.h
/// Depth stored in steps. A Kinect-class camera measures disparity in 1/8 pixel, so depth comes in steps
/// of about 0.003 z^2 (office1.pcd: 125 distinct depths, 1 cm apart at 1.8 m, 7.5 cm at 5.1 m, for a
/// 1 cm pixel): every surface not facing the sensor becomes a staircase whose risers are several
/// spacings long, and the gap rule would cut it into strips one terrace wide. Measured over the steps
/// (one step of depth difference counted as none), the staircase is the surface it samples again.

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// The depth steps of a scan, if its depth coordinate is stored in steps.
  struct DepthQuantization
  {
    int axis = -1;               ///< the coordinate stored in steps (0, 1, 2), or -1: not quantized
    std::vector<double> levels;  ///< its distinct values, ascending
    std::vector<int> level;      ///< #P index of each point's value in levels (-1 for points not used)

    bool active () const { return axis >= 0; }

    /// The step from level \a l to the next one up, 0 for the top level or l < 0.
    double
    stepAbove (int l) const
    {
      return l >= 0 && l + 1 < static_cast<int> (levels.size ()) ? levels[l + 1] - levels[l] : 0.0;
    }

    /// |p_b - p_a|, with the difference along the axis reduced by one step (the step above the lower of
    /// the two levels): adjacent terraces are neighbours, a jump of several steps stays a jump.
    double
    effectiveLength (const std::vector<Eigen::Vector3d>& positions, int a, int b) const;
  };

  /// Finds depth steps seen from \a viewpoint: the axis is the coordinate most aligned with the mean
  /// direction from the viewpoint to the points (|component| >= 0.7, so a camera looking along it), and it
  /// counts as stepped when the used points take fewer distinct values along it than 1 % of their number.
  DepthQuantization
  findDepthQuantization (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& used,
                         const Eigen::Vector3d& viewpoint);
} // namespace pcl_sparse
