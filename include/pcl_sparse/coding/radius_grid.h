#pragma once
/// \file radius_grid.h
/// Patch radii on a logarithmic grid, r = 2^(k / kRadiusStepsPerOctave), so that a quantised model file
/// stores a radius as the small integer k, exactly.
///
/// The radius only scales a patch's local coordinates into the basis square; rounding it up by at most
/// 2^(1/32) (2.2 %) leaves the patch a little inside the square and its code fitted to the same points.
/// On the 25 shared meshes the default file's RADI section falls from about 16 bits a patch (a fine step
/// from the file tolerance, near-random low bits) to about 6 (spot 1384 -> 526 bytes).

#include <cmath>
#include <cstdint>

namespace pcl_sparse
{
  /// Grid steps per doubling of the radius.
  constexpr int kRadiusStepsPerOctave = 32;

  /// The smallest grid radius at least \a radius (a radius already on the grid is kept); \a radius
  /// itself when not positive and finite.
  inline double
  radiusOnGrid (double radius)
  {
    if (!(radius > 0.0) || !std::isfinite (radius))
      return radius;
    // The margin keeps a radius on the grid (up to round-off in log2) on its own step.
    const double steps = std::ceil (kRadiusStepsPerOctave * std::log2 (radius) - 1e-9);
    const double grid = std::exp2 (steps / kRadiusStepsPerOctave);
    return grid >= radius ? grid : std::exp2 ((steps + 1.0) / kRadiusStepsPerOctave);
  }

  /// Whether \a radius lies on the grid (within round-off, as exp2 and exp of the step give it back); if so
  /// \a step receives its k.
  inline bool
  radiusGridStep (double radius, std::int64_t& step)
  {
    if (!(radius > 0.0) || !std::isfinite (radius))
      return false;
    const double steps = kRadiusStepsPerOctave * std::log2 (radius);
    const double nearest = std::round (steps);
    if (!(std::abs (steps - nearest) <= 1e-6))
      return false;
    step = static_cast<std::int64_t> (nearest);
    return true;
  }
} // namespace pcl_sparse
