#pragma once
/// \file cloud_surface.h
/// The neighbourhood surface of a scan (issue 12, points 3, 4 and 6): a triangle mesh over the scan's own
/// points with oriented normals, so that every mesh stage (normals, Harris 3D, patches, coding) runs on
/// scans unchanged. Organized scans (and spinning-lidar frames) are triangulated on their image grid,
/// other scans by local Delaunay fans in the tangent planes of their k-nearest-neighbour graph; edges
/// across gaps, depth discontinuities and shadows are refused, outliers are counted and left out.

#include <pcl_sparse/cloud/cloud_surface_options.h>
#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// What became of a point. Only Surface points are corners of triangles (some Surface points are in
  /// none, e.g. on a thin line).
  enum class CloudPointKind : std::uint8_t
  {
    Surface = 0,    ///< has a neighbourhood and a normal
    Outlier = 1,    ///< farther than the outlier rule from the tangent plane of every neighbour
    Isolated = 2,   ///< fewer than 2 usable neighbours within the gap rule: no plane, no triangle
    NonFinite = 3   ///< a NaN/Inf coordinate (the scan was not cleaned)
  };

  /// Which neighbourhood the surface was built on.
  enum class CloudNeighborhood
  {
    ImageGrid,   ///< the organized scan's width x height grid
    LidarRings,  ///< an unorganized spinning-lidar frame arranged as rings x azimuth
    Knn          ///< the k-nearest-neighbour graph (PointKdTree, FLANN)
  };

  /// A scan's surface. Every per-point vector has #P entries, in the scan's order.
  struct CloudSurface
  {
    /// vertices: the scan's positions, all of them, in order, in its local frame (world = scan.origin +
    /// v); triangles: counter-clockwise seen from the side the normals point to (their geometric normals
    /// agree with the point normals). Outliers, isolated and non-finite points are unreferenced vertices.
    TriangleMesh mesh;
    std::vector<Eigen::Vector3d> normals;  ///< #P unit oriented normals; zero for Isolated and NonFinite points
    std::vector<CloudPointKind> kinds;     ///< #P what each point is
    double spacing = 0.0;   ///< median local spacing (about the square root of the area per point), local units
    double noise = 0.0;     ///< robust estimate of the noise along the normal (standard deviation), local units
    std::size_t outliers = 0;          ///< points of kind Outlier
    std::size_t isolated = 0;          ///< points of kind Isolated
    std::size_t non_finite = 0;        ///< points of kind NonFinite
    std::size_t unreferenced = 0;      ///< vertices in no triangle (all kinds)
    std::size_t refused_edges = 0;     ///< candidate edges refused by the gap and shadow rules (see below)
    std::size_t shadowed_edges = 0;    ///< of which refused by the shadow rule alone
    /// Image grid / lidar rings: grid edges whose two pixels hold points; kNN: ordered pairs (i, j) with j
    /// among the k nearest of i (a mutual pair counts twice).
    std::size_t candidate_edges = 0;
    std::size_t unplaced = 0;          ///< lidar rings: points that found no free cell of the grid
    /// Image grid / lidar rings: triangles left out because their geometric normal points against their
    /// corners' normals (a noise spike or a surface seen edge-on; see windImageTrianglesLikeNormals).
    std::size_t folded_triangles = 0;
    /// The number of distinct depths when the depth is stored in steps and options.remove_depth_steps took
    /// them out (any scan) or options.bridge_depth_steps measured lengths over them (image grid / lidar rings);
    /// 0 otherwise.
    std::size_t depth_levels = 0;
    /// The steps were taken out (options.remove_depth_steps): mesh.vertices are the moved points.
    bool depth_steps_removed = false;
    /// kNN: boundary loops of up to 12 edges closed after the local triangulation (small_hole_filling.h).
    std::size_t filled_holes = 0;
    CloudNeighborhood neighborhood = CloudNeighborhood::Knn;  ///< which neighbourhood was used
    NormalOrientation orientation = NormalOrientation::Auto;  ///< how normals were oriented (never Auto)
    bool has_viewpoint = false;        ///< a single viewpoint was used (normals, shadow rule)
    /// The scan stated PCL's default sensor pose (0, 0, 0), but its points do not thin out with their distance
    /// from there (sensorSpacingEvidence): no sensor stood there, and the pose was not used.
    bool default_pose_ignored = false;
    Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero ();     ///< that viewpoint, in the local frame
  };

  /// Builds the surface of \a scan (positions in its local frame; clean it first with cleanScan, which
  /// loadScanCloud does by default):
  ///   1. neighbourhoods: the image grid of an organized scan (scan.indices give each point's pixel), the
  ///      rings of a spinning lidar (options.use_lidar_rings), else the k nearest neighbours; edges are
  ///      refused by the gap rule and, toward a viewpoint, by the shadow rule;
  ///   2. normals: PCA of each point's accepted neighbourhood (double precision, in parallel,
  ///      deterministic), oriented as options.orientation says;
  ///   3. noise: the median leave-one-out residual of local quadric fits (curvature does not count as
  ///      noise), scaled to a standard deviation; outliers by the rule of the options, then the normals
  ///      of their neighbours again without them;
  ///   4. triangles: on a grid, two per 2 x 2 cell where no edge is refused, across the diagonal whose
  ///      triangles face like the normals (then the shorter), all wound alike, folded ones left out;
  ///      without a grid, local Delaunay fans in each point's tangent plane, each triangle taken when it
  ///      overlaps no triangle proposed by more corners, then holes of up to 12 edges closed under the gap
  ///      rule; wound like the normals.
  /// The result is the same for any number of threads, and no randomness is involved (no seed).
  /// Throws pcl_sparse::Error with a one-line message for an empty scan, a scan without a finite point,
  /// normals, indices or point_viewpoints of the wrong size, pixel indices outside width x height or
  /// shared by two points, use_given_normals on a scan without normals, or options out of range
  /// (validateCloudSurfaceOptions).
  CloudSurface
  buildCloudSurface (const ScanCloud& scan, const CloudSurfaceOptions& options = CloudSurfaceOptions ());
} // namespace pcl_sparse
