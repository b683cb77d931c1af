#pragma once
/// \file depth_quantization.h
/// Depth stored in steps. A Kinect-class camera measures disparity in 1/8 pixel, so depth comes in steps
/// of about 0.003 z^2 (office1.pcd: 125 distinct depths, 1 cm apart at 1.8 m, 7.5 cm at 5.1 m, for a
/// 1 cm pixel): every surface not facing the sensor becomes a staircase whose risers are several
/// spacings long, and the gap rule would cut it into strips one terrace wide. Measured over the steps
/// (one step of depth difference counted as none), the staircase is the surface it samples again.

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_set>
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
  /// counts as stepped when the used points take fewer distinct values along it than 1 % of their number,
  /// or, given \a stepped_axes (SteppedAxes::judge on a whole input of which \a positions are a part), when
  /// its bit is set there: a tile of a frame may hold a few hundred points over 20 steps.
  DepthQuantization
  findDepthQuantization (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& used,
                         const Eigen::Vector3d& viewpoint, std::optional<std::uint8_t> stepped_axes = std::nullopt);

  /// Judges which coordinates of a whole input are stored in steps, as findDepthQuantization does on one
  /// scan, from points given one at a time (a file streamed in chunks as well as a scan in memory): bit a
  /// of the result is set when coordinate a takes at least 2 and fewer than points / 100 distinct values.
  class SteppedAxes
  {
  public:
    /// \a max_points: at least the number of points that will be added; an axis with more than
    /// max_points / 100 or 65536 distinct values is continuous and stops being counted, so memory stays
    /// at most 65536 values per axis however large the input (a camera's depth takes a few hundred levels:
    /// office1.pcd 125, milk_cartoon_all_small_clorox.pcd 508).
    explicit SteppedAxes (std::size_t max_points) : cap_ (std::min<std::size_t> (max_points / 100, 65536)) {}

    void add (const Eigen::Vector3d& p);

    /// The stepped coordinates' bits, for an input of \a points points (those added, duplicates merged).
    std::uint8_t judge (std::size_t points) const;

  private:
    std::size_t cap_;
    std::unordered_set<double> values_[3];
    bool continuous_[3] = {false, false, false};
  };
} // namespace pcl_sparse
