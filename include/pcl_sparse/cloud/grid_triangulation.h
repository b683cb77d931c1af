#pragma once
/// \file grid_triangulation.h
/// Triangles of a range image: two per 2 x 2 cell across the shorter diagonal, where the corners hold
/// usable points and no edge is refused (the grid edges by classifyGridEdges, the diagonal by the same
/// rules against the cell's spacings).

#include <pcl_sparse/cloud/edge_rules.h>
#include <pcl_sparse/cloud/grid_neighborhoods.h>
#include <pcl_sparse/cloud/scan_grid.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// The cell (x, y) has corners a (x, y), b (x + 1, y), c (x, y + 1), d (x + 1, y + 1). With all four
  /// usable, one of the diagonals a-d and b-c that pass the rules (length <= gap_factor x |(s_x, s_y)|,
  /// s_x and s_y the mean spacings of the cell's horizontal and vertical edges; shadow rule) splits it,
  /// and each of its two triangles is kept when its two grid edges are accepted; with three, their
  /// triangle under the same conditions. The diagonal: the shorter one, unless \a normals are given and
  /// the other split has more triangles facing like their corners' normals (facing x (area . sum of the
  /// normals) > 0): on quantized depth (Kinect terraces) the shorter diagonal often folds over a step.
  /// Triangles come in cell order, all wound alike in the image (a, c, d), (a, d, b) or (a, c, b),
  /// (b, c, d): clockwise in pixel coordinates with y down.
  std::vector<Eigen::Vector3i>
  triangulateImageGrid (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, const GridEdges& edges,
                        const std::vector<std::uint8_t>& usable, double gap_factor, const ShadowRule& shadow,
                        int num_threads, const std::vector<Eigen::Vector3d>* normals = nullptr, double facing = 1.0);
} // namespace pcl_sparse
