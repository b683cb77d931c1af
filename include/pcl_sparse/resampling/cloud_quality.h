#pragma once
/// \file cloud_quality.h
/// How well a point cloud with normals samples a triangle mesh: distance to the surface, normal error,
/// flipped normals, holes, spacing uniformity. Used by the resampling tests and bench/bench_resample, and
/// handy for comparing resamplers (e.g. against pcl::MovingLeastSquares).

#include <pcl_sparse/geometry/point_triangle_distance.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Options of evaluateCloudQuality.
  struct CloudQualityOptions
  {
    /// Points drawn uniformly by area on the mesh to look for holes.
    std::size_t probes = 50000;
    /// A probe is covered if a cloud point lies within this many spacings, spacing = sqrt(area / #points).
    double hole_spacings = 3.0;
    /// Seed of the probes.
    std::uint64_t seed = 1;
    /// Keep the per-point distances and normal angles in CloudQuality (for diagnostics).
    bool keep_per_point = false;
  };

  /// How well a cloud samples a mesh (evaluateCloudQuality).
  struct CloudQuality
  {
    double rms_distance = 0.0;   ///< RMS distance of the points to the mesh (world units)
    double mean_distance = 0.0;  ///< mean distance of the points to the mesh
    double max_distance = 0.0;   ///< largest distance of a point to the mesh
    double mean_normal_angle = 0.0;  ///< mean angle (degrees) between a point's normal and its nearest face's normal (see flipped)
    double median_normal_angle = 0.0;  ///< median of the same angles
    double p90_normal_angle = 0.0;     ///< 90th percentile of the same angles
    /// Points whose normal is more than 120 degrees from the nearest face normal: pointing to the other side.
    /// (Not 90: at a sharp 90-degree edge a point may be nearest to the other face.) Where several faces
    /// are nearest (the nearest surface point is on their shared edge or corner) the closest of their
    /// normals counts: the surface normal there is any of them.
    std::size_t flipped = 0;
    std::size_t invalid = 0;         ///< points with a non-finite position or normal (ignored above)
    double completeness = 0.0;       ///< fraction of probes with a point within hole_spacings spacings
    double largest_gap = 0.0;        ///< largest probe-to-point distance, in spacings
    double spacing = 0.0;            ///< sqrt(mesh area / #points)
    double nn_cv = 0.0;              ///< coefficient of variation of nearest-neighbour distances
    double bbox_diagonal = 0.0;      ///< of the mesh
    /// Per valid point (in cloud order, invalid points skipped): distance to the mesh and normal angle
    /// (degrees); filled only when CloudQualityOptions::keep_per_point is set.
    std::vector<double> point_distances, point_normal_angles;
  };

  /// Measures a point cloud with normals against the mesh it samples.
  /// \param[in] mesh     the reference surface
  /// \param[in] cloud    the points; those with a non-finite position or normal count as invalid
  /// \param[in] options  probes, hole threshold, seed
  /// \return distances (exact, to the nearest triangle), normal errors, flipped and invalid points, completeness,
  /// spacing uniformity; all zero for a mesh without vertices or triangles
  /// \throws pcl_sparse::Error for a triangle with a non-finite corner, a corner index out of range or a coordinate
  ///         over 1e75 (TriangleTree)
  CloudQuality
  evaluateCloudQuality (const TriangleMesh& mesh, const pcl::PointCloud<pcl::PointNormal>& cloud,
                        const CloudQualityOptions& options = CloudQualityOptions ());
} // namespace pcl_sparse
