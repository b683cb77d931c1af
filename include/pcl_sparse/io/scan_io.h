#pragma once
/// \file scan_io.h
/// Loading a scanned point cloud for the point-cloud path: every point of the file in double precision,
/// in a local frame (scan_cloud.h), cleaned (scan_cleaning.h) unless asked not to.
///
/// Why not pcl::io::loadPCDFile into a typed cloud (measured with PCL 1.13 on ../shared/clouds): it reads
/// x y z stored as double (TYPE F, SIZE 8) as all zeros, trusts the counts of a lying header, and crashes
/// on some garbage files (and on binary data whose first bytes spell a header keyword such as POINTS, which
/// it parses as a header line); our PCD header check runs first, DATA binary is read by us at the checked
/// layout, and the fields are read at their own precision.

#include <pcl_sparse/io/scan_cleaning.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <string>

namespace pcl_sparse
{
  /// Options for loadScanCloud.
  struct ScanLoadOptions
  {
    /// Clean the scan (cleanScan); when false every point of the file is kept, NaN and all, and the report
    /// says input_points = kept.
    bool clean = true;
    /// What cleaning drops besides non-finite points.
    ScanCleaningOptions cleaning;
  };

  /// Loads the scan in \a path, dispatching on the extension (any case):
  ///   .pcd   ascii, binary or binary_compressed; any numeric field types, read at their own precision
  ///          (double x y z stay double); organized width x height kept; VIEWPOINT as the sensor pose;
  ///          normal_x/y/z, rgb/rgba and intensity fields as attributes;
  ///   .ply   the vertex element (x y z, and nx ny nz, red green blue [alpha], intensity or scalar_intensity
  ///          when present); with a Stanford range_grid element the scan is organized num_cols x num_rows and
  ///          empty cells count as non-finite points; faces, if any, are ignored;
  ///   .xyz   "x y z" or "x y z nx ny nz" per line;
  ///   .obj .off .stl   the vertices.
  /// The scan is cleaned as \a options say (in the file's frame), then moved to the local frame of
  /// localFrameOrigin of the kept points (of all finite points when not cleaned).
  /// Throws pcl_sparse::Error with one line naming the file and the problem for a missing file, a
  /// directory, an unknown extension, an empty file, garbage, a truncated file, a header that lies about its
  /// counts, no x/y/z, a file with no points, or a range grid that does not match its vertices.
  void
  loadScanCloud (const std::string& path, ScanCloud& scan, const ScanLoadOptions& options = ScanLoadOptions ());

  /// True if \a path has an extension loadScanCloud reads (.pcd .ply .xyz .obj .off .stl, any case).
  bool
  isScanFileExtension (const std::string& path);
} // namespace pcl_sparse
