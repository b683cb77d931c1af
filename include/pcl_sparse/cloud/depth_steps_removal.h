#pragma once
/// \file depth_steps_removal.h
/// Depth stored in steps (depth_quantization.h) taken out of a scan before its surface is built.
/// A Kinect-class camera stores depth in steps of about 0.003 z^2 (office1.pcd: 1 cm at 1.8 m, 7.5 cm at
/// 5.1 m), so a slanted wall comes as a staircase of terraces several pixels wide: normals from a small
/// image window follow the terraces and risers, not the wall, and patches grown over them stay small and
/// tilted (office1: 29512 patches, 5516 resampled normals more than 10 degrees past perpendicular to the line
/// of sight). The measured depth only says the true depth lies in its step's bin, so each point is moved along
/// its line of sight onto the plane of the points around it, as far as that bin allows: the staircase
/// becomes the surface it samples, and no point leaves what it measured.

#include <pcl_sparse/cloud/depth_quantization.h>
#include <pcl_sparse/cloud/edge_rules.h>
#include <pcl_sparse/cloud/scan_grid.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// \brief An organized scan's positions with its depth steps taken out at the depth levels whose steps are
  /// wider than the sampling (per level, the median step over the distance between horizontally adjacent
  /// pixels at least 2: finer steps make no terraces, and the points of such levels stay where they are).
  /// \param[in] positions  the points (local frame)
  /// \param[in] finite     #P flags: the points that may move (the others stay)
  /// \param[in] grid       the scan's image grid
  /// \param[in] steps      the depth steps
  /// \param[in] viewpoint  the sensor (local frame): points move along their lines of sight from it
  /// \param[in] shadow     the shadow rule the grid edges take
  /// \param[in] gap_factor the gap rule's factor (CloudSurfaceOptions::gap_factor)
  /// \param[in] num_threads OpenMP threads (0 = default); the result does not depend on it
  /// \param[out] moved     #P positions when it returns true: point i's plane is fitted (PCA) to the points of
  ///                       a 7 x 7 lattice of pixels around it, spread so that it reaches about one depth step of
  ///                       i's level sideways (pitch up to 12 pixels) and kept by the gap rule over the steps
  ///                       (gridNeighborhoods); i moves to where its line of sight meets that plane, clamped to
  ///                       its bin (halfway to the levels below and above). A point with fewer than 8 such
  ///                       neighbours, or whose line of sight meets its plane within 6 degrees of grazing, stays.
  /// \return whether the steps were taken out at some level (\a moved is untouched otherwise)
  bool
  removeDepthSteps (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& finite,
                    const ScanGrid& grid, const DepthQuantization& steps, const Eigen::Vector3d& viewpoint,
                    const ShadowRule& shadow, double gap_factor, int num_threads, std::vector<Eigen::Vector3d>& moved);

  /// \brief The same for an unorganized scan (a frame whose NaNs were dropped, a filtered cloud): the gate
  /// compares each level's median step with the distance of its points to their nearest across the depth
  /// axis (over every 16th point first: no level passing there, the scan is left as it is), and point i's
  /// plane is fitted to the points within two steps of it (at least 3 spacings, the mean distance to the 6
  /// nearest; kd-tree radius search: a ball of one step does not reach the next terrace, a step deeper).
  /// \return whether the steps were taken out at some level (\a moved is untouched otherwise)
  bool
  removeDepthSteps (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& finite,
                    const DepthQuantization& steps, const Eigen::Vector3d& viewpoint, int num_threads,
                    std::vector<Eigen::Vector3d>& moved);
} // namespace pcl_sparse
