#pragma once
/// \file lidar_rings.h
/// A spinning lidar frame (Velodyne and the like) as a range image: rows are the lasers' rings, columns
/// the azimuth. Its points lie on a few exact elevation angles seen from the sensor; rings are far apart
/// compared with the spacing along them (10-100 x on the shared HDL-32E frame), so a k-nearest-neighbour
/// graph joins points of one ring only and no triangle could span two rings.

#include <pcl_sparse/cloud/scan_grid.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Arranges the points with used[i] != 0 on a rings x azimuth grid seen from \a sensor (local frame) with
  /// \a orientation (the sensor's z axis is the spin axis). Rings: elevation angles sorted and split where
  /// consecutive ones differ by more than 0.05 degrees; the scan qualifies when there are 2..256 rings, 95 %
  /// of the points are on rings of 32 points or more, no ring is wider than a quarter of the smallest step
  /// between rings, and 90 % of the points find a pixel. Columns: azimuth in steps of the median azimuth
  /// step along the rings, rounded at the points' mean phase within a step; along a ring (by azimuth) a
  /// point whose column is taken takes the next one, and a point that would move further is counted in
  /// \a unplaced.
  ///   returns  false (grid untouched) when the points are not a lidar frame
  bool
  arrangeLidarRings (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& used,
                     const Eigen::Vector3d& sensor, const Eigen::Quaterniond& orientation, ScanGrid& grid,
                     std::size_t& unplaced);
} // namespace pcl_sparse
