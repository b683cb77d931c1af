#pragma once
/// \file scan_grid.h
/// A range image: the points of a scan on a width x height grid of pixels, at most one point per pixel.
/// An organized scan is one already (scan.indices give each point's pixel); a spinning lidar frame
/// becomes one (lidar_rings.h).

#include <pcl_sparse/io/scan_cloud.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// cells[y * width + x] is the index of the point at pixel (x, y), or -1.
  struct ScanGrid
  {
    int width = 0;
    int height = 0;
    std::vector<int> cells;
    /// A column repeating another's points, or -1: a lidar frame's full turn closed behind the sensor (the
    /// first column again after the last). Edges and triangles use it; loops over the points skip it.
    int wrap_column = -1;
    /// The angle between rows over the angle between columns as the sensor sees them: 1 for a camera's image;
    /// a spinning lidar's rings lie several times further apart than its columns (the shared HDL-32E frames:
    /// 1.33 against 0.17 degrees), and the normals' window reaches along a ring half as far as across rings
    /// (gridNeighborhoods).
    double row_to_column_angle = 1.0;

    int at (int x, int y) const { return cells[static_cast<std::size_t> (y) * width + x]; }
  };

  /// The image grid of an organized scan: point i at pixel scan.indices[i] (row * width + column; i when
  /// indices is empty), for points with placed[i] != 0.
  /// Throws pcl_sparse::Error if indices has the wrong size (or is empty for fewer or more points than
  /// pixels), a pixel is outside width x height, or two points claim the same pixel.
  ScanGrid
  organizedScanGrid (const ScanCloud& scan, const std::vector<std::uint8_t>& placed);

  /// Makes \a part, some points of an organized scan of \a width x \a height pixels whose indices name each
  /// point's pixel (row * width + column), an organized scan itself: its width, height and indices become
  /// those of the smallest window of the image that holds its points, with at least two rows where the image
  /// has them (one row would be read as a list of points). A tile of a camera frame keeps the frame's image
  /// grid this way, in memory proportional to its own window. Throws pcl_sparse::Error if indices has the
  /// wrong size or names a pixel outside the image.
  void
  cropToPixelWindow (ScanCloud& part, std::uint32_t width, std::uint32_t height);
} // namespace pcl_sparse
