#include <pcl_sparse/cloud/cloud_surface.h>

#include <pcl_sparse/cloud/cloud_outliers.h>
#include <pcl_sparse/cloud/depth_quantization.h>
#include <pcl_sparse/cloud/depth_steps_removal.h>
#include <pcl_sparse/cloud/grid_neighborhoods.h>
#include <pcl_sparse/cloud/grid_triangulation.h>
#include <pcl_sparse/cloud/knn_neighborhoods.h>
#include <pcl_sparse/cloud/lidar_rings.h>
#include <pcl_sparse/cloud/normal_orientation.h>
#include <pcl_sparse/cloud/pca_normals.h>
#include <pcl_sparse/cloud/scan_noise.h>
#include <pcl_sparse/cloud/sensor_evidence.h>
#include <pcl_sparse/cloud/small_hole_filling.h>
#include <pcl_sparse/cloud/tangent_triangulation.h>
#include <pcl_sparse/cloud/triangle_winding.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/upper_median.h>
#include <pcl_sparse/mesh/bounding_box.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// Holes of the local triangulation up to this many edges are closed (the gap rule still applies).
    const std::size_t kSmallHoleEdges = 12;

    /// What buildCloudSurface works with besides the scan.
    struct Work
    {
      std::vector<std::uint8_t> usable;  // Surface points
      Viewpoints viewpoints;             // local frame
      Eigen::Quaterniond sensor_orientation = Eigen::Quaterniond::Identity ();
      ShadowRule shadow;
      ScanGrid grid;                     // image grid / lidar rings
      GridEdges edges;
      DepthQuantization steps;           // depth stored in steps (image grids seen from a viewpoint)
      PointNeighborhoods hoods;
      PointNeighborhoods symmetric;      // hoods made symmetric, for the spanning tree and the kNN triangles
    };

    /// Refuses a scan the surface cannot be built from; returns the finite flags.
    std::vector<std::uint8_t>
    checkScan (const ScanCloud& scan, const CloudSurfaceOptions& options)
    {
      const std::size_t n = scan.size ();
      if (n == 0)
        throw Error ("buildCloudSurface: " + scan.report.emptyScanMessage ());
      if (!scan.normals.empty () && scan.normals.size () != n)
        throw Error ("buildCloudSurface: the scan has " + std::to_string (scan.normals.size ()) + " normals for " +
                     std::to_string (n) + " points");
      if (!options.point_viewpoints.empty () && options.point_viewpoints.size () != n)
        throw Error ("buildCloudSurface: option point_viewpoints has " + std::to_string (options.point_viewpoints.size ()) +
                     " entries for " + std::to_string (n) + " points");
      if (options.use_given_normals && scan.normals.empty ())
        throw Error ("buildCloudSurface: option use_given_normals is set but the scan has no normals");
      std::vector<std::uint8_t> finite (n);
      std::size_t count = 0;
      for (std::size_t i = 0; i < n; ++i)
        count += (finite[i] = scan.positions[i].allFinite () ? 1 : 0);
      if (count == 0)
        throw Error ("buildCloudSurface: the scan has no finite point (all " + std::to_string (n) + " are NaN/Inf)");
      // As the encoder refuses (coordinateRangeProblem), but before the kd-tree: a cloud read with the wrong
      // byte order reached 1e38 and aborted in FLANN's tree (found by a review of the ROS node).
      const double largest = largestCoordinate (scan.positions, scan.origin);
      if (!(largest <= max_coordinate))
      {
        std::ostringstream message;
        message.precision (3);
        message << "buildCloudSurface: the scan's coordinates reach " << largest
                << ", beyond the 1e30 that float clouds hold (a wrong byte order?)";
        throw Error (message.str ());
      }
      // As the encoder refuses too, but before the kd-tree and the covariances: under 1e-30 squared lengths
      // underflow (every normal came out (1, 0, 0)), under 1e-308 the tree's power-of-two scale overflows.
      const double diagonal = finiteBoundingBox (scan.positions).diagonal ().stableNorm ();
      if (diagonal > 0.0 && diagonal < 1e-30)
      {
        std::ostringstream message;
        message.precision (3);
        message << "buildCloudSurface: the scan's bounding-box diagonal is " << diagonal
                << ", under 1e-30, where squared lengths underflow: rescale the input";
        throw Error (message.str ());
      }
      return finite;
    }

    /// A sensor position is plausible within 100 bounding-box diagonals of the points.
    bool
    plausibleViewpoint (const ScanCloud& scan, const Eigen::Vector3d& v)
    {
      const Eigen::AlignedBox3d box = finiteBoundingBox (scan.positions);
      const double outside = (box.min () - v).cwiseMax (v - box.max ()).cwiseMax (0.0).norm ();
      return v.allFinite () && outside <= 100.0 * box.diagonal ().norm ();
    }

    /// Resolves the orientation mode and the viewpoints (local frame) from the options and the scan. A list
    /// of points (unorganized) stating PCL's default pose keeps it only if its points thin out with their
    /// distance from it (sensorSpacingEvidence); an organized cloud is a camera's image, taken from its pose.
    NormalOrientation
    planOrientation (const ScanCloud& scan, const CloudSurfaceOptions& options, const std::vector<std::uint8_t>& finite,
                     Work& work, CloudSurface& surface)
    {
      if (!options.point_viewpoints.empty ())
        for (const auto& v : options.point_viewpoints)
          work.viewpoints.points.push_back (v - scan.origin);
      else if (options.has_viewpoint)
        work.viewpoints.points.push_back (options.viewpoint - scan.origin);
      const Eigen::Vector3d sensor = scan.sensor_origin - scan.origin;
      bool sensor_ok = scan.has_sensor_pose && plausibleViewpoint (scan, sensor);
      if (sensor_ok && options.point_viewpoints.empty () && !options.has_viewpoint &&
          defaultPoseIsUnsupported (scan, finite))
      {
        sensor_ok = false;
        surface.default_pose_ignored = true;
      }
      NormalOrientation mode = options.orientation;
      if (mode == NormalOrientation::Auto)
      {
        if (options.use_given_normals)
          mode = NormalOrientation::Given;
        else if (!work.viewpoints.empty () || sensor_ok)
          mode = NormalOrientation::Viewpoint;
        else
          mode = scan.isOrganized () ? NormalOrientation::ImageGrid : NormalOrientation::SpanningTree;
      }
      // The scan's sensor serves as the viewpoint when no other is given (also for the lidar rings).
      if (work.viewpoints.empty () && (mode == NormalOrientation::Viewpoint || sensor_ok))
      {
        work.viewpoints.points.push_back (sensor);
        work.sensor_orientation = scan.sensor_orientation;
      }
      if (mode == NormalOrientation::ImageGrid && !scan.isOrganized ())
        mode = NormalOrientation::SpanningTree;
      return mode;
    }

    /// Lidar rings for an unorganized scan: around its single viewpoint, or around the file's origin when
    /// it has none (a lidar frame in its sensor's coordinates, as PLY files keep them); then the origin
    /// becomes the viewpoint, if the orientation is Auto.
    void
    findLidarRings (const ScanCloud& scan, const CloudSurfaceOptions& options, const std::vector<std::uint8_t>& finite,
                    Work& work, CloudSurface& surface)
    {
      if (scan.isOrganized () || !options.use_lidar_rings || work.viewpoints.points.size () > 1)
        return;
      const bool known = work.viewpoints.points.size () == 1;
      const Eigen::Vector3d sensor = known ? work.viewpoints.points[0] : Eigen::Vector3d (-scan.origin);
      if (!arrangeLidarRings (scan.positions, finite, sensor, work.sensor_orientation, work.grid, surface.unplaced))
        return;
      surface.neighborhood = CloudNeighborhood::LidarRings;
      if (!known && options.orientation == NormalOrientation::Auto && !options.use_given_normals)
      {
        work.viewpoints.points.push_back (sensor);
        surface.orientation = NormalOrientation::Viewpoint;
      }
    }

    /// \a input, or a copy with its depth steps taken out (options.remove_depth_steps) in \a storage. Steps
    /// found and left in go to work.steps for the gap rule (options.bridge_depth_steps).
    const ScanCloud&
    withoutDepthSteps (const ScanCloud& input, const CloudSurfaceOptions& options, const std::vector<std::uint8_t>& finite,
                       Work& work, ScanCloud& storage, CloudSurface& surface)
    {
      if (!options.remove_depth_steps || work.viewpoints.points.size () != 1)
        return input;
      const Eigen::Vector3d& viewpoint = work.viewpoints.points[0];
      DepthQuantization steps = findDepthQuantization (input.positions, finite, viewpoint, input.stepped_axes);
      std::vector<Eigen::Vector3d> moved;
      bool removed = false;
      if (input.isOrganized ())
      {
        const ShadowRule shadow (&work.viewpoints, options.shadow_angle_degrees);
        work.grid = organizedScanGrid (input, finite);  // pixels only: the same for the moved points
        removed = removeDepthSteps (input.positions, finite, work.grid, steps, viewpoint, shadow, options.gap_factor,
                                    options.num_threads, moved);
      }
      else
        removed = removeDepthSteps (input.positions, finite, steps, viewpoint, options.num_threads, moved);
      if (!removed)
      {
        if (options.bridge_depth_steps)
          work.steps = std::move (steps);
        return input;
      }
      storage = input;
      storage.positions = std::move (moved);
      surface.depth_levels = steps.levels.size ();
      surface.depth_steps_removed = true;
      return storage;
    }

    /// Neighbourhoods and edge counts: image grid, lidar rings (already arranged) or kNN.
    void
    buildNeighborhoods (const ScanCloud& scan, const CloudSurfaceOptions& options, const std::vector<std::uint8_t>& finite,
                        Work& work, CloudSurface& surface)
    {
      const int threads = options.num_threads;
      if (scan.isOrganized ())
      {
        if (work.grid.cells.empty ())  // not made yet by withoutDepthSteps
          work.grid = organizedScanGrid (scan, finite);
        surface.neighborhood = CloudNeighborhood::ImageGrid;
      }
      if (surface.neighborhood != CloudNeighborhood::Knn)
      {
        if (options.bridge_depth_steps && !surface.depth_steps_removed && !work.steps.active () &&
            work.viewpoints.points.size () == 1)
          work.steps = findDepthQuantization (scan.positions, finite, work.viewpoints.points[0], scan.stepped_axes);
        if (!surface.depth_steps_removed)
          surface.depth_levels = work.steps.levels.size ();
        work.edges = classifyGridEdges (work.grid, scan.positions, options.gap_factor, work.shadow, threads, &work.steps);
        countGridEdges (work.edges, surface.candidate_edges, surface.refused_edges, surface.shadowed_edges);
        work.hoods = gridNeighborhoods (work.grid, scan.positions, work.edges, options.window_radius, options.gap_factor,
                                        threads, &work.steps);
        return;
      }
      const KnnGraph graph = findKNearestNeighbors (scan.positions, finite, options.k, threads);
      KnnEdgeCounts counts;
      work.hoods = acceptKnnEdges (scan.positions, graph, options.gap_factor, work.shadow, counts, threads);
      surface.candidate_edges = counts.candidates;
      surface.refused_edges = counts.refused;
      surface.shadowed_edges = counts.shadowed;
    }

    double
    medianSpacing (const PointNeighborhoods& hoods, const std::vector<std::uint8_t>& usable)
    {
      std::vector<double> values;
      for (std::size_t i = 0; i < hoods.size (); ++i)
        if (usable[i] && hoods.spacing[i] > 0.0)
          values.push_back (hoods.spacing[i]);
      return upperMedian (values);
    }

    /// PCA normals, or the given ones where asked and present; returns the points whose normal was
    /// estimated although given normals were asked for.
    std::vector<int>
    estimateNormals (const ScanCloud& scan, const CloudSurfaceOptions& options, const Work& work,
                     std::vector<Eigen::Vector3d>& normals)
    {
      estimatePcaNormals (scan.positions, work.hoods, work.usable, options.num_threads, normals);
      std::vector<int> estimated;
      if (!options.use_given_normals)
        return estimated;
      for (std::size_t i = 0; i < scan.size (); ++i)
      {
        if (!work.usable[i])
          continue;
        const Eigen::Vector3d& given = scan.normals[i];
        if (given.allFinite () && given.norm () > 0.0)
          normals[i] = given.normalized ();
        else if (normals[i].squaredNorm () > 0.5)
          estimated.push_back (static_cast<int> (i));
      }
      return estimated;
    }

    /// The usable points with a neighbour flagged in \a flags.
    std::vector<int>
    neighborsOfFlagged (const PointNeighborhoods& hoods, const std::vector<std::uint8_t>& usable,
                        const std::vector<std::uint8_t>& flags)
    {
      std::vector<int> points;
      for (std::size_t i = 0; i < hoods.size (); ++i)
        if (usable[i])
          for (const int j : hoods.of (i))
            if (flags[j])
            {
              points.push_back (static_cast<int> (i));
              break;
            }
      return points;
    }

    /// Outliers in two passes, because an outlier tilts its neighbours' planes toward itself: candidates
    /// by a quarter of the rule, their neighbours' normals again without them, then the rule itself on the
    /// candidates; at last the normals around the outliers without them. Marks kinds and usable.
    void
    removeOutliers (const ScanCloud& scan, const CloudSurfaceOptions& options, Work& work, CloudSurface& surface)
    {
      const auto& p = scan.positions;
      auto& normals = surface.normals;
      const bool estimated = !options.use_given_normals;
      const std::vector<std::uint8_t> candidate = findCloudOutliers (
        p, work.hoods, normals, work.usable, surface.noise, 0.25 * options.outlier_factor, 0.25 * options.outlier_spacing,
        options.num_threads);
      std::vector<int> candidates;
      for (std::size_t i = 0; i < p.size (); ++i)
        if (candidate[i])
          candidates.push_back (static_cast<int> (i)), work.usable[i] = 0;
      if (candidates.empty ())
        return;
      std::vector<int> around = neighborsOfFlagged (work.hoods, work.usable, candidate);
      if (estimated)
        estimatePcaNormals (p, work.hoods, work.usable, options.num_threads, normals, &around);
      // Each candidate against its neighbours that are not candidates.
      const std::vector<std::uint8_t> outlier =
        findCloudOutliers (p, work.hoods, normals, work.usable, surface.noise, options.outlier_factor,
                           options.outlier_spacing, options.num_threads, &candidates);
      for (const int i : candidates)
        if (outlier[i])
          surface.kinds[i] = CloudPointKind::Outlier;
        else
          work.usable[i] = 1;
      if (!estimated)
        return;
      around = neighborsOfFlagged (work.hoods, work.usable, candidate);
      estimatePcaNormals (p, work.hoods, work.usable, options.num_threads, normals, &around);
      for (const int i : around)
        if (!(normals[i].squaredNorm () > 0.5))
          surface.kinds[i] = CloudPointKind::Isolated, work.usable[i] = 0;
    }

    /// Orients the normals before triangulation (ImageGrid waits for the grid's triangles).
    void
    orientNormals (const ScanCloud& scan, const CloudSurfaceOptions& options, const std::vector<int>& estimated,
                   Work& work, CloudSurface& surface)
    {
      if (surface.orientation == NormalOrientation::SpanningTree || surface.neighborhood == CloudNeighborhood::Knn)
        work.symmetric = symmetricNeighborhoods (work.hoods, options.num_threads);
      switch (surface.orientation)
      {
        case NormalOrientation::Viewpoint:
          orientTowardViewpoints (scan.positions, work.viewpoints, work.hoods, work.usable, surface.normals);
          break;
        case NormalOrientation::SpanningTree:
          orientBySpanningTree (scan.positions, work.symmetric, work.usable, surface.normals);
          break;
        case NormalOrientation::Given:
          orientLikeNeighbors (work.hoods, work.usable, estimated, surface.normals);
          break;
        default:
          break;
      }
    }

    void
    triangulate (const ScanCloud& scan, const CloudSurfaceOptions& options, const Work& work, CloudSurface& surface)
    {
      auto& triangles = surface.mesh.triangles;
      if (surface.neighborhood == CloudNeighborhood::Knn)
      {
        triangles = triangulateTangentFans (scan.positions, work.symmetric, surface.normals, work.usable, options.gap_factor,
                                            work.shadow, options.num_threads);
        surface.filled_holes = fillSmallHoles (scan.positions, surface.normals, work.hoods.spacing, options.gap_factor,
                                               kSmallHoleEdges, triangles);
      }
      else
      {
        triangles = triangulateImageGrid (work.grid, scan.positions, work.edges, work.usable, options.gap_factor,
                                          work.shadow, options.num_threads, nullptr, 1.0, &work.steps);
        if (surface.orientation == NormalOrientation::ImageGrid)
          orientByImageGrid (scan.positions, triangles, work.hoods, work.usable, surface.normals);
        // Again, now that the normals and the side the image's triangles face are known, choosing the
        // diagonals that do not fold.
        const double facing = imageFacing (scan.positions, surface.normals, triangles);
        triangles = triangulateImageGrid (work.grid, scan.positions, work.edges, work.usable, options.gap_factor,
                                          work.shadow, options.num_threads, &surface.normals, facing, &work.steps);
        surface.folded_triangles = windImageTrianglesLikeNormals (scan.positions, surface.normals, triangles);
        return;
      }
      windTrianglesLikeNormals (scan.positions, surface.normals, triangles);
    }

    /// Zero normals where there is none, and the counts.
    void
    finish (CloudSurface& surface)
    {
      const std::size_t n = surface.kinds.size ();
      std::vector<std::uint8_t> referenced (n, 0);
      for (const auto& t : surface.mesh.triangles)
        referenced[t[0]] = referenced[t[1]] = referenced[t[2]] = 1;
      for (std::size_t i = 0; i < n; ++i)
      {
        const CloudPointKind kind = surface.kinds[i];
        if (kind == CloudPointKind::Isolated || kind == CloudPointKind::NonFinite || !surface.normals[i].allFinite ())
          surface.normals[i].setZero ();
        surface.outliers += kind == CloudPointKind::Outlier ? 1 : 0;
        surface.isolated += kind == CloudPointKind::Isolated ? 1 : 0;
        surface.non_finite += kind == CloudPointKind::NonFinite ? 1 : 0;
        surface.unreferenced += referenced[i] ? 0 : 1;
      }
    }
  } // namespace

  CloudSurface
  buildCloudSurface (const ScanCloud& input, const CloudSurfaceOptions& options)
  {
    validateCloudSurfaceOptions (options);
    const std::vector<std::uint8_t> finite = checkScan (input, options);
    const std::size_t n = input.size ();
    CloudSurface surface;
    Work work;
    surface.orientation = planOrientation (input, options, finite, work, surface);
    ScanCloud without_steps;
    const ScanCloud& scan = withoutDepthSteps (input, options, finite, work, without_steps, surface);
    surface.mesh.vertices = scan.positions;
    findLidarRings (scan, options, finite, work, surface);
    if (surface.orientation == NormalOrientation::Viewpoint)
      work.shadow = ShadowRule (&work.viewpoints, options.shadow_angle_degrees);
    surface.has_viewpoint = work.viewpoints.points.size () == 1 && surface.orientation == NormalOrientation::Viewpoint;
    if (surface.has_viewpoint)
      surface.viewpoint = work.viewpoints.points[0];

    buildNeighborhoods (scan, options, finite, work, surface);
    surface.kinds.assign (n, CloudPointKind::Surface);
    work.usable.assign (n, 1);
    for (std::size_t i = 0; i < n; ++i)
      if (!finite[i])
        surface.kinds[i] = CloudPointKind::NonFinite, work.usable[i] = 0;
      else if (work.hoods.offsets[i + 1] - work.hoods.offsets[i] < 2)
        surface.kinds[i] = CloudPointKind::Isolated, work.usable[i] = 0;
    surface.spacing = medianSpacing (work.hoods, work.usable);

    const std::vector<int> estimated = estimateNormals (scan, options, work, surface.normals);
    for (std::size_t i = 0; i < n; ++i)
      if (work.usable[i] && !(surface.normals[i].squaredNorm () > 0.5))  // no plane: neighbours all unusable
        surface.kinds[i] = CloudPointKind::Isolated, work.usable[i] = 0;
    surface.noise = estimateScanNoise (scan.positions, work.hoods, surface.normals, work.usable, options.num_threads);
    removeOutliers (scan, options, work, surface);
    orientNormals (scan, options, estimated, work, surface);
    triangulate (scan, options, work, surface);
    finish (surface);
    return surface;
  }
} // namespace pcl_sparse
