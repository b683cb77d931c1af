#pragma once
/// \file normal_orientation.h
/// Giving PCA normals a sign: toward the sensor for a single scan, per point for a merged scan with its
/// viewpoints, by the image grid's winding for an organized scan without a sensor, and by propagation
/// over a minimum spanning tree otherwise (Hoppe et al. 1992).
///
/// The spanning forest is our own Kruskal (sort + union-find): Boost.Graph's kruskal_minimum_spanning_tree
/// on an adjacency_list took about 3 times longer on samp11-utm.pcd (a heap of edge descriptors).

#include <pcl_sparse/cloud/edge_rules.h>
#include <pcl_sparse/cloud/point_neighborhoods.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Flips each normal so that it points toward the viewpoint of its point, except where it is within 10
  /// degrees of perpendicular to the line of sight (silhouettes, surfaces seen at a grazing angle): there
  /// the sign toward the viewpoint is decided by the estimation error, so such a usable point takes the
  /// sign of the sum of its decided neighbours' normals instead, spreading in passes from the decided
  /// points; a point no pass reaches keeps the viewpoint's sign.
  void
  orientTowardViewpoints (const std::vector<Eigen::Vector3d>& positions, const Viewpoints& viewpoints,
                          const PointNeighborhoods& neighborhoods, const std::vector<std::uint8_t>& usable,
                          std::vector<Eigen::Vector3d>& normals);

  /// Consistent orientation over the minimum spanning forest of the neighbourhood graph (\a neighborhoods
  /// symmetric, see symmetricNeighborhoods; edges between usable points with normals, weight
  /// 1 - |n_i . n_j|). In each tree the root is the point with the largest |n . (p - c)| (c: the tree's
  /// centroid), oriented so that n . (p - c) > 0 (outward on a closed surface), and each other normal is
  /// flipped to agree with its parent's. A flat tree (the standard deviation of its points along their
  /// thinnest direction is under a tenth of that along the widest: a terrain, a wall) has no outward, and
  /// propagation goes astray across roof edges and vegetation: it is oriented as if seen from far along
  /// its thinnest axis, taken pointing up (+z; for a vertical wall, toward its largest positive
  /// coordinate), as orientTowardViewpoints does. Trees of 1 or 2 points get n_z >= 0.
  void
  orientBySpanningTree (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                        const std::vector<std::uint8_t>& usable, std::vector<Eigen::Vector3d>& normals);

  /// Organized scans: \a image_triangles all wound the same way in the image, so all face the same side
  /// of the sensor. Each normal is flipped to agree with the sum of its triangles' (area-weighted)
  /// normals; a normal with no triangle agrees with the sum of its neighbours' oriented normals. Then all
  /// are flipped if the sum of n . (p - centroid) over usable points is negative (outward, as for an
  /// object on a turntable).
  void
  orientByImageGrid (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3i>& image_triangles,
                     const PointNeighborhoods& neighborhoods, const std::vector<std::uint8_t>& usable,
                     std::vector<Eigen::Vector3d>& normals);

  /// Flips the normal of each point of \a points (e.g. estimated where a given normal was missing) to
  /// agree with the sum of the normals of its usable neighbours that are not in \a points.
  void
  orientLikeNeighbors (const PointNeighborhoods& neighborhoods, const std::vector<std::uint8_t>& usable,
                       const std::vector<int>& points, std::vector<Eigen::Vector3d>& normals);
} // namespace pcl_sparse
