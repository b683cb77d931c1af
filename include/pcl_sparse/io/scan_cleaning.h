#pragma once
/// \file scan_cleaning.h
/// Cleaning a scan before any geometry sees it. Real files lie (measured on the shared scans,
/// ../shared/clouds/README.md): PCL marks clouds full of NaN as dense, lidar drivers write "no return" as
/// (0, 0, 0), and some scans store every point twice. Each cause is dropped and counted.

#include <pcl_sparse/io/scan_cloud.h>

#include <Eigen/Core>

#include <optional>

namespace pcl_sparse
{
  /// Options for cleanScan. Non-finite points are always dropped: nothing downstream can use them.
  struct ScanCleaningOptions
  {
    /// Drop points exactly at the sensor position (scan.sensor_origin; (0, 0, 0) when the file gives none):
    /// a surface point cannot be at the sensor, but "no return" is written there.
    bool drop_at_sensor_origin = true;
    /// Where the sensor stood, in the file's coordinates, when the caller knows it (the tools' -viewpoint):
    /// the points exactly there are dropped, not those at the file's sensor origin (a point at (0, 0, 0) of
    /// a cloud without a pose is a surface point then). None: the file's sensor origin.
    std::optional<Eigen::Vector3d> sensor_position;
    /// Keep only the first of points with exactly the same position (their attributes are dropped with them).
    bool merge_duplicates = true;
  };

  /// Cleans \a scan in place, in this order: drops points with a NaN/Inf coordinate (whatever is_dense said),
  /// then points exactly at the sensor position, then merges exact duplicate positions keeping the first in
  /// file order. The kept points stay in their order, with their attributes and file indices; scan.report
  /// gets the counts (and is returned). An empty scan.indices is taken as 0, 1, 2, ... Deterministic: the
  /// result depends only on the input.
  ///
  /// The positions are compared in the local frame: p == sensor_origin - origin, the subtraction the loader
  /// applied to every point, so a point stored at the sensor position is found exactly.
  /// Throws pcl_sparse::Error if an attribute vector (normals, colors, intensities, indices) is neither
  /// empty nor one entry per point.
  ScanCleaningReport
  cleanScan (ScanCloud& scan, const ScanCleaningOptions& options = ScanCleaningOptions ());

  /// The sensor position cleaning drops points at, in the file's coordinates: options.sensor_position if
  /// given, else \a file_sensor_origin (the file's).
  inline Eigen::Vector3d
  cleaningSensorPosition (const ScanCleaningOptions& options, const Eigen::Vector3d& file_sensor_origin)
  {
    return options.sensor_position.value_or (file_sensor_origin);
  }
} // namespace pcl_sparse
