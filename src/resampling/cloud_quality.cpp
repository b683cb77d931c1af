#include <pcl_sparse/resampling/cloud_quality.h>

#include <pcl_sparse/geometry/nearest_face_normal.h>
#include <pcl_sparse/geometry/point_kd_tree.h>
#include <pcl_sparse/geometry/triangle_tree.h>
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/surface_sampling.h>

#include <pcl/common/io.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
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

    /// Per point, the exact distance to the nearest triangle (TriangleTree) and the angle (degrees) between
    /// its normal and the surface normal there (NearestFaceNormal: at an edge or corner, the closest of the
    /// normals of the faces sharing it).
    void
    measureSurfaceError (const TriangleMesh& mesh, const pcl::PointCloud<pcl::PointNormal>& points,
                         std::vector<double>& distance, std::vector<double>& angle)
    {
      const NearestFaceNormal surface (mesh, 0);  // every thread, as the distances below
      const std::size_t n = points.size ();
      distance.resize (n);
      angle.resize (n);
#pragma omp parallel
      {
        std::vector<TriangleTree::Nearest> tied;  // per thread: a point allocates nothing
#pragma omp for schedule(dynamic, 256)
        for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (n); ++i)
        {
          const pcl::PointNormal& point = points[i];
          double cosine;
          distance[i] = surface.nearest (point.getVector3fMap ().cast<double> (),
                                         point.getNormalVector3fMap ().cast<double> ().normalized (), cosine, tied)
                          .distance;
          angle[i] = std::acos (std::clamp (cosine, -1.0, 1.0)) * 180.0 / M_PI;
        }
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
    measureSurfaceError (mesh, *valid, distance, angle);
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
