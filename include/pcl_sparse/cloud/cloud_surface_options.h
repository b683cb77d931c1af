#pragma once
/// \file cloud_surface_options.h
/// The options of buildCloudSurface (cloud_surface.h): neighbourhoods, the gap rule, normal orientation,
/// outliers. Every default is stated; validateCloudSurfaceOptions says which values are out of range.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// How the point normals are oriented (a PCA normal has no sign).
  enum class NormalOrientation
  {
    /// The first that applies: Given when use_given_normals and the scan has normals; Viewpoint when
    /// point_viewpoints or viewpoint is set, or when the scan states a sensor pose whose origin is
    /// plausible (within 100 bounding-box diagonals of the points: a PCD's default VIEWPOINT 0 0 0 is
    /// not a sensor for map coordinates); ImageGrid for an organized scan; SpanningTree otherwise.
    Auto,
    /// Toward the viewpoint: point_viewpoints[i] for point i when given, else viewpoint, else the scan's
    /// sensor origin (a single scan sees only the sides of surfaces that face the sensor).
    Viewpoint,
    /// Consistent orientation propagated over a minimum spanning tree of the neighbourhood graph with
    /// weights 1 - |n_i . n_j| (Hoppe et al. 1992), in each connected component from the point where the
    /// outward direction is clearest (largest |n . (p - centroid)|), oriented away from the component's
    /// centroid: outward on closed surfaces; +z for a flat component (a terrain; see orientBySpanningTree).
    SpanningTree,
    /// Organized scans: every triangle of the image grid faces the same side of the image (a range
    /// image sees the front of every surface), the side chosen so that most normals point away from
    /// the centroid. Unorganized scans: as SpanningTree.
    ImageGrid,
    /// The normals stored in the scan, with their signs (requires use_given_normals).
    Given
  };

  /// Options of buildCloudSurface. Lengths are relative (factors of the local spacing), so the defaults
  /// hold for any unit and any density.
  struct CloudSurfaceOptions
  {
    /// Unorganized scans: neighbours per point from the kd-tree (PointKdTree, FLANN), for the
    /// normals, the noise, the outliers and the local triangulation. 3..64.
    int k = 16;
    /// Organized scans (and lidar rings): the normals use the (2 r + 1)^2 image window around each pixel.
    /// 1..5.
    int window_radius = 2;
    /// Gap rule: an edge (i, j) is refused when longer than gap_factor x the local spacing (unorganized:
    /// the smaller of the two points' spacings; image grids: the median length of the grid edges of the
    /// same direction around it), so that no triangle bridges a hole or a depth discontinuity. > 1.
    double gap_factor = 3.0;
    /// Shadow rule, used when the normals are oriented toward a viewpoint: an edge within this angle of
    /// the line of sight (PCL's OrganizedFastMesh calls such edges shadowed) joins a foreground and a
    /// background surface and is refused. Degrees, 0 (off) .. 30.
    double shadow_angle_degrees = 5.0;
    /// How normals are oriented (see NormalOrientation).
    NormalOrientation orientation = NormalOrientation::Auto;
    /// Use the normals stored in the scan (normalised) instead of estimating them; points whose given
    /// normal is zero or not finite get an estimated one.
    bool use_given_normals = false;
    /// A single viewpoint in the file's frame (the frame of scan.sensor_origin); overrides the scan's
    /// sensor origin when set.
    bool has_viewpoint = false;
    Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero ();
    /// Merged scans: one viewpoint per point (file's frame), or empty.
    std::vector<Eigen::Vector3d> point_viewpoints;
    /// Unorganized scans: when the points lie on a few exact elevation angles seen from the viewpoint (or,
    /// without one, from the file's origin: a lidar frame in its sensor's coordinates), they are a spinning
    /// lidar's rings; the scan is then a range image (rows = rings, columns = azimuth) instead of a kNN
    /// graph, because rings are far apart compared with the points along them and a kNN graph never joins
    /// two rings. Found around the file's origin, that origin is the viewpoint for Auto orientation.
    bool use_lidar_rings = true;
    /// Image grids and lidar rings seen from a viewpoint: when the depth is stored in steps (Kinect-class
    /// disparity: fewer distinct depths than 1 % of the points; depth_quantization.h), lengths are measured
    /// over one step of depth, so that a slanted surface's staircase is not cut into terraces by the gap
    /// rule.
    bool bridge_depth_steps = true;
    /// Scans seen from one viewpoint, depth stored in steps: each point is first moved along its line of
    /// sight onto the plane of the points within about a step around it, never out of its step's bin
    /// (depth_steps_removal.h; only where the steps are wider than the sampling), so that normals, noise and
    /// patches see the surface the staircase samples (ours; office1.pcd: resampled normals more than 10 degrees
    /// past perpendicular to the line of sight 5516 -> 845, patches 29512 -> 14456; bench/results/scans-notes.md).
    /// The surface's vertices are then the moved points. Off: the staircase as measured (bridged for the gap
    /// rule by bridge_depth_steps).
    bool remove_depth_steps = true;
    /// Outlier rule: a point is an outlier when its distance to the tangent plane of every neighbour
    /// exceeds max (outlier_factor x noise, outlier_spacing x that neighbour's local spacing). > 0.
    double outlier_factor = 6.0;
    double outlier_spacing = 1.0;
    /// OpenMP threads; 0 = OpenMP's default. The result does not depend on it.
    int num_threads = 0;
  };

  /// Throws pcl_sparse::Error with a one-line message naming the first option out of range.
  void
  validateCloudSurfaceOptions (const CloudSurfaceOptions& options);
} // namespace pcl_sparse
