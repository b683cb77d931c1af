#pragma once
/// \file frame_quantization.h
/// Patch frames R = (T1, T2, N) as quantised unit quaternions ("smallest three": the index of the
/// largest component, made positive, and the other three rounded to a step), plus the error budget
/// that ties the quantisation steps of the model file to a surface tolerance (docs/FORMAT.md).

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace pcl_sparse
{
  /// A frame as stored: R = rotation(q) * diag(1, reflected ? -1 : 1, 1).
  struct QuantisedFrame
  {
    int largest = 0;                    ///< index (w, x, y, z = 0..3) of the dropped largest component
    bool reflected = false;             ///< det R < 0: T2 flipped before the quaternion was taken
    std::array<std::int64_t, 3> q{};    ///< the other three components, in steps, in index order
  };

  /// Quantises an orthonormal frame as a "smallest three" quaternion.
  /// \param[in] frame  orthonormal, either handedness
  /// \param[in] step   quantisation step of the quaternion components (> 0)
  /// \return the stored form
  QuantisedFrame
  quantiseFrame (const Eigen::Matrix3d& frame, double step);

  /// The frame a quantised code stands for.
  /// \param[in]  code   the stored form
  /// \param[in]  step   the step it was quantised with
  /// \param[out] frame  the orthonormal frame
  /// \return false (\a frame unspecified) if the code is not a valid unit quaternion (sum of squares of
  ///         the three components > 1), which only a corrupt file has
  bool
  dequantiseFrame (const QuantisedFrame& code, double step, Eigen::Matrix3d& frame);

  /// Quaternion component step that keeps a frame's error within a displacement budget: the rotation
  /// angle error is <= 2 sqrt(3) step (to first order; a 10 % margin covers the rest), so
  /// step = budget / (1.1 * 2 sqrt(3) * radius * reach).
  /// \param[in] budget  largest displacement allowed, world units
  /// \param[in] radius  r_P, world units per local unit
  /// \param[in] reach   largest norm of a local point of the patch
  /// \return the step
  double
  frameStep (double budget, double radius, double reach);

  /// Coefficient step such that the rounding errors of a patch's coefficients (at most step / 2 each, on
  /// atoms bounded by 1 in magnitude) move its surface by at most a budget:
  /// radius * num_atoms * step / 2 <= budget.
  /// \param[in] budget     largest displacement allowed, world units
  /// \param[in] radius     r_P, world units per local unit
  /// \param[in] num_atoms  the patch's number of atoms
  /// \return the step
  double
  coefficientStep (double budget, double radius, std::size_t num_atoms);
} // namespace pcl_sparse
