#include <pcl_sparse/resampling/cloud_quality.h>

#include <pcl_sparse/common/upper_median.h>
#include <pcl_sparse/geometry/point_kd_tree.h>
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/surface_sampling.h>

#include <pcl/common/io.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  namespace
  {
    /// The points of \a cloud with a finite position and normal.
    pcl::PointCloud<pcl::PointNormal>::Ptr
    finitePoints (const pcl::PointCloud<pcl::PointNormal>& cloud)
    {
      pcl::PointCloud<pcl::PointNormal>::Ptr valid (new pcl::PointCloud<pcl::PointNormal>);
      for (const auto& point : cloud)
        if (std::isfinite (point.x) && std::isfinite (point.y) && std::isfinite (point.z) && std::isfinite (point.normal_x) &&
            std::isfinite (point.normal_y) && std::isfinite (point.normal_z))
          valid->push_back (point);
      return valid;
    }

    /// Points on every triangle, each point of a triangle within \a reach of one of its triangle's, and the
    /// triangle of each: rows parallel to the longest edge, \a reach apart from it up to the opposite corner,
    /// each row sampled \a reach apart between the two other edges (a point lies within reach / 2 of a row
    /// and reach / 2 along it). About area / reach^2 + longest / reach points: a barycentric grid of
    /// (longest / reach)^2 / 2 points took 455 MB for one sliver 5000 reaches long (found by a review).
    pcl::PointCloud<pcl::PointXYZ>::Ptr
    coverTriangles (const TriangleMesh& mesh, double reach, std::vector<int>& owners)
    {
      pcl::PointCloud<pcl::PointXYZ>::Ptr points (new pcl::PointCloud<pcl::PointXYZ>);
      owners.clear ();
      auto add = [&] (const Eigen::Vector3d& q, std::size_t f) {
        points->push_back (pcl::PointXYZ (static_cast<float> (q.x ()), static_cast<float> (q.y ()), static_cast<float> (q.z ())));
        owners.push_back (static_cast<int> (f));
      };
      for (std::size_t f = 0; f < mesh.numTriangles (); ++f)
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        // Corners: a, b the longest edge, c the opposite corner.
        std::array<Eigen::Vector3d, 3> corner = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
        int opposite = 2;
        double longest = (corner[1] - corner[0]).norm ();
        for (int k = 0; k < 2; ++k)
        {
          const double edge = (corner[(k + 2) % 3] - corner[k + 1]).norm ();
          if (edge > longest)
            longest = edge, opposite = k;
        }
        const Eigen::Vector3d &a = corner[(opposite + 1) % 3], &b = corner[(opposite + 2) % 3], &c = corner[opposite];
        const Eigen::Vector3d ab = b - a;
        const double height = longest > 0.0 ? ab.cross (c - a).norm () / longest : 0.0;
        const int rows = std::max (1, static_cast<int> (std::ceil (height / reach)));
        for (int i = 0; i <= rows; ++i)
        {
          // The row at fraction s of the way to c runs from a + s (c - a) to b + s (c - b).
          const double s = static_cast<double> (i) / rows;
          const Eigen::Vector3d from = a + s * (c - a), to = b + s * (c - b);
          const int steps = std::max (1, static_cast<int> (std::ceil ((to - from).norm () / reach)));
          for (int j = 0; j <= steps; ++j)
            add (from + (static_cast<double> (j) / steps) * (to - from), f);
        }
      }
      return points;
    }

    /// Per point, the distance to the nearest triangle and the angle (degrees) between its normal and that
    /// triangle's. Exact: the triangles of the \a k nearest cover points give a first distance d, then
    /// every triangle with a cover point within d + reach is measured (the nearest triangle has one). The
    /// triangles with the \a k nearest centroids alone miss it where large triangles meet small ones or
    /// at thin parts, and the normal of a wrong face was counted as flipped (sword, cheese-cgal).
    void
    measureSurfaceError (const TriangleMesh& mesh, const pcl::PointCloud<pcl::PointNormal>& points, int k,
                         std::vector<double>& distance, std::vector<double>& angle)
    {
      const std::vector<Eigen::Vector3d> face_normals = computeFaceNormals (mesh);
      // reach: the median longest edge, at least the edge of an average triangle, so that the cover has
      // a few points per triangle (more only on the triangles far longer than most).
      std::vector<double> longest (mesh.numTriangles ());
      double area = 0.0;
      for (std::size_t f = 0; f < mesh.numTriangles (); ++f)
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        const Eigen::Vector3d ab = mesh.vertices[t[1]] - mesh.vertices[t[0]], ac = mesh.vertices[t[2]] - mesh.vertices[t[0]];
        longest[f] = std::max ({ab.norm (), ac.norm (), (ac - ab).norm ()});
        area += 0.5 * ab.cross (ac).norm ();
      }
      double reach = std::max (upperMedian (longest), std::sqrt (2.0 * area / static_cast<double> (mesh.numTriangles ())));
      if (!(reach > 0.0))
        reach = 1.0;
      // Float cover points and queries are off by up to about 1e-7 of the coordinates' size.
      double largest = 0.0;
      for (const Eigen::Vector3d& v : mesh.vertices)
        largest = std::max (largest, v.cwiseAbs ().maxCoeff ());
      const double slack = 1e-6 * largest;
      // Two faces' distances to their shared edge differ by rounding only (double arithmetic).
      const double tie = 1e-12 * largest;
      std::vector<int> owners;
      const pcl::PointCloud<pcl::PointXYZ>::Ptr cover = coverTriangles (mesh, reach, owners);
      const PointKdTree cover_tree (*cover);
      k = std::max (1, std::min (k, static_cast<int> (cover->size ())));

      const std::size_t n = points.size ();
      distance.resize (n);
      angle.resize (n);
#pragma omp parallel for schedule(dynamic, 256)
      for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (n); ++i)
      {
        std::vector<int> index (k);
        std::vector<float> d2 (k);
        const pcl::PointNormal& point = points[i];
        pcl::PointXYZ query;
        query.getVector3fMap () = point.getVector3fMap ();
        const Eigen::Vector3d p = point.getVector3fMap ().cast<double> ();
        double best = std::numeric_limits<double>::infinity ();
        int best_face = owners[0];
        std::vector<std::pair<int, double>> measured;  // faces and their distances, sorted by face
        std::vector<int> candidates;
        auto measure = [&] () {  // the faces of the cover points in index that are not measured yet
          candidates.clear ();
          for (int c : index)
            candidates.push_back (owners[c]);
          std::sort (candidates.begin (), candidates.end ());
          candidates.erase (std::unique (candidates.begin (), candidates.end ()), candidates.end ());
          const std::size_t old = measured.size ();
          for (int f : candidates)
          {
            const auto known = std::lower_bound (measured.begin (), measured.begin () + old, std::make_pair (f, -1.0));
            if (known != measured.begin () + old && known->first == f)
              continue;
            const Eigen::Vector3i& t = mesh.triangles[f];
            const double d = pointTriangleDistance (p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
            measured.emplace_back (f, d);
            if (d < best || (d == best && f < best_face))
            {
              best = d;
              best_face = f;
            }
          }
          std::inplace_merge (measured.begin (), measured.begin () + old, measured.end ());
        };
        cover_tree.nearestK (query, k, index, d2);
        measure ();
        const double radius = best + reach + slack;
        cover_tree.radius (query, radius, index, d2);
        measure ();
        distance[i] = best;
        // Where the nearest surface point lies on an edge or corner, every face sharing it is nearest (the
        // distances agree up to rounding) and the surface normal there is any of theirs: a point just past
        // a knife edge matches the face it came from, not the one its index happened to sort first.
        const Eigen::Vector3d normal = point.getNormalVector3fMap ().cast<double> ().normalized ();
        double cosine = normal.dot (face_normals[best_face]);
        for (const auto& [f, d] : measured)
          if (d <= best + tie)
            cosine = std::max (cosine, normal.dot (face_normals[f]));
        angle[i] = std::acos (std::clamp (cosine, -1.0, 1.0)) * 180.0 / M_PI;
      }
    }

    /// Distance and normal-angle statistics of the per-point errors (n > 0).
    void
    summariseSurfaceError (const std::vector<double>& distance, const std::vector<double>& angle, CloudQuality& quality)
    {
      const std::size_t n = distance.size ();
      for (std::size_t i = 0; i < n; ++i)
      {
        quality.rms_distance += distance[i] * distance[i];
        quality.mean_distance += distance[i];
        quality.max_distance = std::max (quality.max_distance, distance[i]);
        quality.mean_normal_angle += angle[i];
        quality.flipped += angle[i] > 120.0 ? 1 : 0;
      }
      quality.rms_distance = std::sqrt (quality.rms_distance / n);
      quality.mean_distance /= n;
      quality.mean_normal_angle /= n;
      std::vector<double> sorted = angle;
      std::sort (sorted.begin (), sorted.end ());
      quality.median_normal_angle = sorted[n / 2];
      quality.p90_normal_angle = sorted[std::min (n - 1, (9 * n) / 10)];
    }

    /// Coefficient of variation of the nearest-neighbour distances of the points in \a tree.
    double
    nearestNeighbourVariation (const PointKdTree& tree, const pcl::PointCloud<pcl::PointXYZ>& points)
    {
      const std::size_t n = points.size ();
      std::vector<double> nearest (n);
#pragma omp parallel for schedule(dynamic, 256)
      for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (n); ++i)
      {
        std::vector<int> index (2);
        std::vector<float> d2 (2);
        tree.nearestK (points[i], 2, index, d2);
        nearest[i] = std::sqrt (static_cast<double> (d2.back ()));
      }
      double mean = 0.0, square = 0.0;
      for (double d : nearest)
        mean += d;
      mean /= n;
      for (double d : nearest)
        square += (d - mean) * (d - mean);
      return mean > 0.0 ? std::sqrt (square / n) / mean : 0.0;
    }

    /// \a count points uniform by area on the mesh (sampleMeshSurfaceWith, std::mt19937_64 seeded with \a seed).
    std::vector<pcl::PointXYZ>
    sampleProbes (const TriangleMesh& mesh, std::size_t count, std::uint64_t seed)
    {
      std::mt19937_64 random (seed);
      std::vector<Eigen::Vector3d> points;
      sampleMeshSurfaceWith (mesh, count, random, points);
      std::vector<pcl::PointXYZ> probes (points.size ());
      for (std::size_t i = 0; i < points.size (); ++i)
        probes[i].getVector3fMap () = points[i].cast<float> ();
      return probes;
    }

    /// Holes: completeness and largest gap of the probes against the points in \a tree (quality.spacing set).
    void
    measureHoles (const PointKdTree& tree, const std::vector<pcl::PointXYZ>& probes,
                  double hole_spacings, CloudQuality& quality)
    {
      std::vector<double> gap (probes.size ());
#pragma omp parallel for schedule(dynamic, 256)
      for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (probes.size ()); ++i)
      {
        std::vector<int> index (1);
        std::vector<float> d2 (1);
        tree.nearestK (probes[i], 1, index, d2);
        gap[i] = std::sqrt (static_cast<double> (d2[0])) / quality.spacing;
      }
      std::size_t covered = 0;
      for (double g : gap)
      {
        covered += g <= hole_spacings ? 1 : 0;
        quality.largest_gap = std::max (quality.largest_gap, g);
      }
      quality.completeness = probes.empty () ? 1.0 : static_cast<double> (covered) / probes.size ();
    }
  } // namespace

  CloudQuality
  evaluateCloudQuality (const TriangleMesh& mesh, const pcl::PointCloud<pcl::PointNormal>& cloud,
                        const CloudQualityOptions& options)
  {
    CloudQuality quality;
    if (mesh.vertices.empty () || mesh.triangles.empty ())
      return quality;
    quality.bbox_diagonal = boundingBoxDiagonal (mesh);
    const pcl::PointCloud<pcl::PointNormal>::Ptr valid = finitePoints (cloud);
    quality.invalid = cloud.size () - valid->size ();
    if (valid->empty ())
      return quality;

    // Distance and normal against the nearest triangle.
    std::vector<double> distance, angle;
    const int k = std::min<int> (options.nearest_triangles, static_cast<int> (mesh.numTriangles ()));
    measureSurfaceError (mesh, *valid, k, distance, angle);
    summariseSurfaceError (distance, angle, quality);
    if (options.keep_per_point)
    {
      quality.point_distances = distance;
      quality.point_normal_angles = angle;
    }

    // Spacing uniformity, then holes: probes uniform by area on the mesh.
    pcl::PointCloud<pcl::PointXYZ> positions;
    pcl::copyPointCloud (*valid, positions);
    const PointKdTree cloud_tree (positions);
    quality.nn_cv = nearestNeighbourVariation (cloud_tree, positions);
    const std::vector<double> areas = computeFaceAreas (mesh);
    double area = 0.0;
    for (double a : areas)
      area += a;
    quality.spacing = std::sqrt (area / static_cast<double> (valid->size ()));
    const std::vector<pcl::PointXYZ> probes = sampleProbes (mesh, options.probes, options.seed);
    measureHoles (cloud_tree, probes, options.hole_spacings, quality);
    return quality;
  }
} // namespace pcl_sparse
