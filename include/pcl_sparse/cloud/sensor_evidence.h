#pragma once
/// \file sensor_evidence.h
/// Whether a scan's points look taken from a given place. PCL writes the pose (0, 0, 0), identity, into every
/// cloud whose sensor nobody set, so a sensor at the origin is also what "no sensor stated" reads as: an
/// airborne tile moved near the origin (to fit float coordinates) then had its normals turned toward a
/// "sensor" under the ground. A sensor samples at fixed angles, so its points lie farther apart the farther
/// they are from it; points that do not thin out with the distance from that place were not taken from it.

#include <pcl_sparse/io/scan_cloud.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// What sensorSpacingEvidence measured.
  struct SensorSpacingEvidence
  {
    std::size_t sampled = 0;     ///< points compared (a stride sample of the finite points)
    double range_ratio = 0.0;    ///< 95th / 5th percentile of their distances to the place
    double correlation = 0.0;    ///< Spearman rank correlation of distance and nearest-neighbour spacing
    /// False only when the distances vary enough to tell (range_ratio >= 2) and the spacing does not grow
    /// with them (correlation < 0.3): measured 0.73 on a Velodyne frame and 0.86 on a room scan, both with
    /// their sensor at the origin, and 0.04 on an airborne tile moved near it.
    bool consistent = true;
  };

  /// \brief Measures whether \a points (with \a finite flags) thin out with their distance from \a place, as
  /// points a sensor there sampled do. Deterministic: a stride sample of at most 4096 points, spacings to
  /// the nearest other point of the sample (a sample thins out as its points do).
  /// \param[in] points the points
  /// \param[in] finite one flag per point: 1 for points to use
  /// \param[in] place  the supposed sensor position (same frame as \a points)
  SensorSpacingEvidence
  sensorSpacingEvidence (const std::vector<Eigen::Vector3d>& points, const std::vector<std::uint8_t>& finite,
                         const Eigen::Vector3d& place);

  /// \brief True when \a scan is a list of points (not organized) that states PCL's default sensor pose
  /// (origin 0, identity orientation) and its points do not thin out with their distance from that origin
  /// (sensorSpacingEvidence): no sensor stood there, and the pose should not orient normals. False for any
  /// other pose (set by someone), for organized clouds (a camera's image, taken from its pose) and for a
  /// tile's scan (ScanCloud::sensor_pose_checked: its source judged the pose on the whole input).
  /// \param[in] scan   the scan (positions in its local frame)
  /// \param[in] finite one flag per point: 1 for points to use
  bool
  defaultPoseIsUnsupported (const ScanCloud& scan, const std::vector<std::uint8_t>& finite);
} // namespace pcl_sparse
