#pragma once
/// \file model_mesh_distance.h
/// The Chamfer distance between a sparse surface model and the mesh it codes: the mean distance from points
/// resampled on the model to the mesh, and from points drawn on the mesh to the model's surface, averaged.
/// bench/bench_format measures the files against Draco with it (200k points a side), and measuredWriteOptions
/// (encoder/measured_write_options.h) chooses the default file with it (fewer points).

#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/mesh/surface_sampling.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl_sparse/geometry/ball_grid.h>
#include <pcl_sparse/geometry/point_kd_tree.h>
#include <pcl_sparse/geometry/triangle_tree.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  /// Distance from a point to a mesh: exact, the nearest of its triangles (TriangleTree), as bench/bench_format
  /// measures; or, built from a sampling of the mesh, the nearest of the triangles under the \a k nearest samples
  /// of a point: exact to those triangles, a little long where the sampling misses the nearest one (sparse
  /// samplings of dense meshes), which adds to every distance alike. measuredWriteOptions' first pass measures
  /// that way (its allowance is set by the readings it gives; exact, they read 1-5 points higher:
  /// bench/results/triangle_tree.md).
  class MeshSurfaceDistance
  {
  public:
    /// \brief Exact. Build O(T log T) for T triangles.
    /// \param[in] mesh         the surface (its triangles copied)
    /// \param[in] num_threads  OpenMP threads of the triangle tree's build (TriangleTree)
    /// \throws pcl_sparse::Error for a mesh without triangles or with a triangle requireMeasurableTriangles refuses
    explicit MeshSurfaceDistance (const TriangleMesh& mesh, int num_threads = 1);

    /// How the sampled form draws its samples: a type of its own, so that a count is never taken for the exact
    /// form's thread count (MeshSurfaceDistance (mesh, 100) is exact, on 100 threads).
    struct Sampling
    {
      std::size_t samples = 0;  ///< points drawn on the mesh (at least one is)
      unsigned seed = 7;        ///< of the draws (sampleMeshSurface)
      int k = 16;               ///< nearest samples whose triangles are measured (at least one is)
    };

    /// \brief From sampling.samples points drawn on \a mesh. Build O(S log S) for S samples, a query O(log S + k).
    /// \param[in] mesh      the surface (kept by reference: it must outlive this)
    /// \param[in] sampling  how many points are drawn, their seed, how many are looked at a query
    /// \throws pcl_sparse::Error for a mesh without triangles or with a triangle requireMeasurableTriangles refuses
    ///         (a corner index out of range, a non-finite corner, a coordinate over 1e75), checked on every face
    MeshSurfaceDistance (const TriangleMesh& mesh, const Sampling& sampling);

    /// Distance from \a p to the mesh. Thread-safe.
    double operator() (const Eigen::Vector3d& p) const;

  private:
    const TriangleMesh& mesh_;
    std::unique_ptr<TriangleTree> triangles_;  ///< exact (null: sampled)
    int k_ = 0;
    std::vector<int> sample_triangle_;
    std::unique_ptr<PointKdTree> samples_;     ///< over the samples (null: exact)
  };

  /// Distance from a point to a model's surface: over the patches whose footprint holds its projection (looked
  /// for among those whose seed lies within 1.5 x radius x largest extent of it, their reach, found in a
  /// BallGrid), the height difference to the
  /// code, to first order (|z - h| r / sqrt (1 + |grad h|^2)), capped by the distance to the nearest of a
  /// cloud resampled from the model (a patch across a thin part can hold the projection and report the
  /// part's thickness; a resampled point lies on the surface).
  class ModelSurfaceDistance
  {
  public:
    /// \param[in] model      the model (kept by reference)
    /// \param[in] resampled  points resampled from it (kept)
    ModelSurfaceDistance (const SparseSurfaceModel& model, const std::vector<Eigen::Vector3d>& resampled);

    /// Distance from \a p to the model's surface. Thread-safe.
    double operator() (const Eigen::Vector3d& p) const;

  private:
    const SparseSurfaceModel& model_;
    std::vector<double> beyond_;                ///< per patch: squared local distances past its footprint
    std::vector<double> reach_squared_;         ///< per patch: its reach squared (world units)
    std::unique_ptr<BallGrid> reaches_;         ///< the patches' reach balls around their seeds
    std::unique_ptr<PointKdTree> cloud_;        ///< over the resampled points
    std::vector<Eigen::Vector3d> points_;
  };

  /// Both halves of a Chamfer distance (world units).
  struct ChamferDistance
  {
    double model_to_mesh = 0.0;      ///< mean distance of the model's resampled points to the mesh
    double mesh_to_model = 0.0;      ///< mean distance of the points drawn on the mesh to the model
    double largest = 0.0;            ///< the largest of both (a Hausdorff estimate)
    std::size_t model_points = 0;    ///< points resampled from the model
    double resample_seconds = 0.0;   ///< time taken to resample the model
    /// The Chamfer distance: the two means averaged.
    double value () const { return 0.5 * (model_to_mesh + mesh_to_model); }
  };

  /// Mean and largest of \a d, summed in order (the same sum whatever thread computed each); both 0 when empty.
  inline void
  meanAndLargest (const std::vector<double>& d, double& mean, double& largest)
  {
    mean = 0.0;
    largest = 0.0;
    for (double x : d)
    {
      mean += x;
      largest = std::max (largest, x);
    }
    mean /= static_cast<double> (std::max<std::size_t> (d.size (), 1));
  }

  /// \brief Mean and largest of \a distance (a callable double (const Eigen::Vector3d&), thread-safe) over
  /// \a points on \a num_threads OpenMP threads (0: OpenMP's default, resolveThreadCount); both 0 without points.
  template <typename Distance>
  void
  meanAndLargestDistance (const std::vector<Eigen::Vector3d>& points, const Distance& distance, double& mean, double& largest,
                          int num_threads = 0)
  {
    std::vector<double> d (points.size ());
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (points.size ()); ++i)
      d[i] = distance (points[i]);
    meanAndLargest (d, mean, largest);
  }

  /// \brief The Chamfer distance between \a model and a mesh: \a points points resampled from the model
  /// (SparseSurfaceResampling with \a resampling, \a num_threads) measured by \a to_mesh, and \a on_mesh
  /// (points drawn on the mesh, e.g. by sampleMeshSurface) measured by ModelSurfaceDistance; both halves on
  /// \a num_threads threads as well.
  ChamferDistance
  modelChamferDistance (const SparseSurfaceModel::ConstPtr& model, const MeshSurfaceDistance& to_mesh,
                        const std::vector<Eigen::Vector3d>& on_mesh, std::size_t points,
                        const SparseSurfaceResamplingOptions& resampling = SparseSurfaceResamplingOptions (),
                        int num_threads = 0);
} // namespace pcl_sparse
