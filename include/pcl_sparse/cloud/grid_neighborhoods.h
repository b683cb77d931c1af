#pragma once
/// \file grid_neighborhoods.h
/// Neighbourhoods on a range image (scan_grid.h): the gap rule per grid edge against the edges of the same
/// direction around it, and the window neighbourhood of each pixel for the normals.
///
/// Why medians of nearby edges of the same direction: they give the local spacing in that direction, so the
/// rule holds on anisotropic grids (lidar rings far apart, surfaces seen at a slant), while a depth jump
/// makes one line of long edges, a minority in every window around it (a one-pixel pole has two).

#include <pcl_sparse/cloud/depth_quantization.h>
#include <pcl_sparse/cloud/edge_rules.h>
#include <pcl_sparse/cloud/point_neighborhoods.h>
#include <pcl_sparse/cloud/scan_grid.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// What the rules made of a grid edge.
  enum class GridEdgeState : std::uint8_t
  {
    Missing = 0,   ///< a pixel of the edge holds no point
    Accepted = 1,
    Gap = 2,       ///< longer than gap_factor x the median of the same-direction edges around it
    Shadow = 3     ///< within the shadow angle of the line of sight
  };

  /// Per grid edge, indexed by its first pixel y * width + x: horizontal edges join (x, y) and (x + 1, y),
  /// vertical ones (x, y) and (x, y + 1).
  ///   *_state    width * height states (Missing where the edge does not exist)
  ///   *_spacing  width * height local spacings: the median of three medians of the existing same-direction
  ///              edges, 5 along the edge's line centred on it and 5 along each parallel line beside it (a
  ///              5 x 3 window, 3 x 5 for vertical edges), 0 where there is none
  struct GridEdges
  {
    std::vector<GridEdgeState> horizontal_state, vertical_state;
    std::vector<float> horizontal_spacing, vertical_spacing;
  };

  /// Classifies every grid edge by the gap rule and then the shadow rule (ShadowRule::shadowed with the
  /// viewpoint of the edge's first point). With \a steps, lengths (edges and spacings) are measured over
  /// the depth steps (DepthQuantization::effectiveLength).
  GridEdges
  classifyGridEdges (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, double gap_factor,
                     const ShadowRule& shadow, int num_threads, const DepthQuantization* steps = nullptr);

  /// Counts over existing edges: candidates, refused (gap or shadow), shadowed.
  void
  countGridEdges (const GridEdges& edges, std::size_t& candidates, std::size_t& refused, std::size_t& shadowed);

  /// Window neighbourhoods: the points of the (2 r + 1)^2 pixels around each pixel that lie within
  /// gap_factor x |(dx s_x, dy s_y)| of it (s_x, s_y: the pixel's spacings along the two grid directions,
  /// from the medians of its edges). Spacing of a point: sqrt (s_x s_y). (No shadow rule here: these
  /// neighbourhoods serve the normals, and a shadowed neighbour within the gap rule is on the same
  /// surface seen at a grazing angle; the triangles apply it.) Distances over the depth \a steps if given.
  /// With \a steps and \a steps_reached > 0 the window is a lattice of (2 r + 1)^2 pixels k apart, k (1..12)
  /// such that it reaches about \a steps_reached depth steps of the pixel's level sideways (r k spacings):
  /// windows that see a staircase's slope instead of one terrace (depth_steps_removal.h).
  /// On lidar rings the window also takes the columns c t apart, c = 1 .. r, t = round (grid.row_to_column_angle
  /// / 2) at most 8, those beyond the adjacent ones: it reaches half as far along the ring as across rings.
  PointNeighborhoods
  gridNeighborhoods (const ScanGrid& grid, const std::vector<Eigen::Vector3d>& positions, const GridEdges& edges,
                     int window_radius, double gap_factor, int num_threads, const DepthQuantization* steps = nullptr,
                     double steps_reached = 0.0);
} // namespace pcl_sparse
