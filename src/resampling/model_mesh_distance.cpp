#include <pcl_sparse/resampling/model_mesh_distance.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/parallel_failure.h>
#include <pcl_sparse/common/upper_median.h>
#include <pcl_sparse/geometry/measurable_triangles.h>
#include <pcl_sparse/resampling/cloud_quality.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include <omp.h>

namespace pcl_sparse
{
  namespace
  {
    pcl::PointCloud<pcl::PointXYZ>::Ptr
    toCloud (const std::vector<Eigen::Vector3d>& points)
    {
      pcl::PointCloud<pcl::PointXYZ>::Ptr cloud (new pcl::PointCloud<pcl::PointXYZ>);
      cloud->reserve (points.size ());
      for (const auto& p : points)
        cloud->push_back (pcl::PointXYZ (static_cast<float> (p.x ()), static_cast<float> (p.y ()), static_cast<float> (p.z ())));
      return cloud;
    }

    pcl::PointXYZ
    toPoint (const Eigen::Vector3d& p)
    {
      return pcl::PointXYZ (static_cast<float> (p.x ()), static_cast<float> (p.y ()), static_cast<float> (p.z ()));
    }
  } // namespace

  MeshSurfaceDistance::MeshSurfaceDistance (const TriangleMesh& mesh, int num_threads)
    : mesh_ (mesh), triangles_ (std::make_unique<TriangleTree> (mesh, num_threads))
  {
  }

  MeshSurfaceDistance::MeshSurfaceDistance (const TriangleMesh& mesh, const Sampling& sampling)
    : mesh_ (mesh), k_ (std::max (1, sampling.k))
  {
    // Every face, not only those the samples land on: one infinite corner makes the total area infinite or NaN,
    // and the draws then land where CumulativeAreaSearch puts non-finite draws, on sound faces as likely.
    requireMeasurableTriangles (mesh, "MeshSurfaceDistance");
    std::vector<Eigen::Vector3d> points;
    sampleMeshSurface (mesh, std::max<std::size_t> (sampling.samples, 1), sampling.seed, points, &sample_triangle_);
    samples_ = std::make_unique<PointKdTree> (*toCloud (points));
  }

  double
  MeshSurfaceDistance::operator() (const Eigen::Vector3d& p) const
  {
    if (triangles_)
      return triangles_->nearest (p).distance;
    // Per thread: a query allocates nothing. A face drawn several times among the k samples is measured once.
    thread_local std::vector<int> indices, faces;
    thread_local std::vector<float> squared;
    samples_->nearestK (toPoint (p), k_, indices, squared);
    faces.clear ();
    double best = std::numeric_limits<double>::infinity ();
    for (int i : indices)
    {
      const int t = sample_triangle_[i];
      if (std::find (faces.begin (), faces.end (), t) != faces.end ())
        continue;
      faces.push_back (t);
      const auto& f = mesh_.triangles[t];
      best = std::min (best, pointTriangleDistance (p, mesh_.vertices[f[0]], mesh_.vertices[f[1]], mesh_.vertices[f[2]]));
    }
    return best;
  }

  ModelSurfaceDistance::ModelSurfaceDistance (const SparseSurfaceModel& model, const std::vector<Eigen::Vector3d>& resampled)
    : model_ (model), points_ (resampled)
  {
    if (model.patches.empty () || resampled.empty ())
      throw Error ("ModelSurfaceDistance: the model has no patch or no resampled point");
    // A patch holds the projection of a point only within its reach of its seed: the reach balls are filed in
    // a grid of cells about the median reach, so a point's patches are one lookup away. (A seeds' k-d tree
    // searched as wide as the largest reach took 2 s for 50k points on turbine, whose reaches spread over 10x;
    // one as wide as twice the median, the larger patches checked one by one, took a fifth of the default
    // file's writing on bunny-npm-1k.)
    std::vector<double> reach (model.patches.size ());
    beyond_.resize (model.patches.size ());
    reach_squared_.resize (model.patches.size ());
    for (std::size_t i = 0; i < model.patches.size (); ++i)
    {
      const PatchCode& patch = model.patches[i];
      const double e = patch.footprint.largestExtent ();
      reach[i] = 1.5 * patch.radius * patch.boundHalfWidth ();
      // The footprint's extents interpolate between its largest and smallest: a point whose projection lies
      // farther from the seed than the largest (and a margin for rounding) lies outside it.
      beyond_[i] = std::pow (1.000001 * e, 2);
      reach_squared_[i] = reach[i] * reach[i];
    }
    std::vector<double> sorted = reach;
    const double median = upperMedian (sorted);
    std::vector<Eigen::Vector3d> seeds;
    seeds.reserve (model.patches.size ());
    for (const PatchCode& patch : model.patches)
      seeds.push_back (patch.origin);
    reaches_ = std::make_unique<BallGrid> (seeds, reach, median > 0.0 && std::isfinite (median) ? median : 1.0);
    cloud_ = std::make_unique<PointKdTree> (*toCloud (resampled));
  }

  double
  ModelSurfaceDistance::operator() (const Eigen::Vector3d& p) const
  {
    const pcl::PointXYZ q = toPoint (p);
    double best = std::numeric_limits<double>::infinity ();
    auto measure = [&] (int i) {
      const PatchCode& patch = model_.patches[i];
      // Each patch within its own reach only: the seeds search reaches twice the median, and on CAD parts
      // (wide extents) finds 176 seeds a point, of which 7 hold its projection (cheese-cgal).
      if ((p - patch.origin).squaredNorm () > reach_squared_[i])
        return;
      const Eigen::Vector3d local = patch.frame.transpose () * (p - patch.origin) / patch.radius;
      if (local.head<2> ().squaredNorm () > beyond_[i] || !patch.footprint.contains (local.x (), local.y ()))
        return;
      const HeightSample h = model_.evaluate (i, local.x (), local.y ());
      best = std::min (best, std::abs (local.z () - h.value) * patch.radius / std::sqrt (1.0 + h.gradient.squaredNorm ()));
    };
    const auto [first, last] = reaches_->candidates (p);  // the nearest is taken: any order does
    for (const int* i = first; i != last; ++i)
      measure (*i);
    // A patch across a thin part can contain the projection of p and report the part's thickness, so the
    // nearest resampled point (an upper bound: it lies on the decoded surface) always caps it. Only a point
    // nearer than best can: the search stops at best (a hair wider, for the float distances it compares),
    // which prunes most of it, as best is mostly far below the points' spacing.
    const float bound = std::isfinite (best) ? static_cast<float> (best * best * (1.0 + 1e-4)) + std::numeric_limits<float>::min ()
                                             : std::numeric_limits<float>::infinity ();
    int nearest = -1;
    float squared = 0.0f;
    if (!cloud_->nearestWithin (q, bound, nearest, squared))
      return best;
    return std::min (best, (p - points_[nearest]).norm ());
  }

  ChamferDistance
  modelChamferDistance (const SparseSurfaceModel::ConstPtr& model, const MeshSurfaceDistance& to_mesh,
                        const std::vector<Eigen::Vector3d>& on_mesh, std::size_t points,
                        const SparseSurfaceResamplingOptions& resampling, int num_threads)
  {
    ChamferDistance result;
    const auto start = std::chrono::steady_clock::now ();
    SparseSurfaceResampling<pcl::PointNormal> resampler;
    resampler.setOptions (resampling);
    resampler.setNumberOfThreads (num_threads);
    resampler.setInputModel (model);
    resampler.setPointCount (points);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampler.compute (cloud);
    result.resample_seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
    result.model_points = cloud.size ();
    std::vector<Eigen::Vector3d> on_model;
    on_model.reserve (cloud.size ());
    for (const auto& p : cloud)
      on_model.emplace_back (p.x, p.y, p.z);
    // ModelSurfaceDistance builds its k-d tree on one thread (FLANN's build is serial: a fifth of a 200k-point
    // measurement), so one thread builds it while the others measure the model's points to the mesh, and joins
    // them when it is done (a dynamic schedule hands it what is left).
    std::unique_ptr<const ModelSurfaceDistance> to_model;
    std::vector<double> to_mesh_distances (on_model.size ());
    ParallelFailure failure;
#pragma omp parallel num_threads (resolveThreadCount (num_threads))
    {
      if (omp_get_thread_num () == omp_get_num_threads () - 1)
        failure.run ([&] { to_model = std::make_unique<const ModelSurfaceDistance> (*model, on_model); });
#pragma omp for schedule (dynamic, 1024)
      for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (on_model.size ()); ++i)
        to_mesh_distances[i] = to_mesh (on_model[i]);
    }
    failure.rethrow ();
    double max_a = 0.0, max_b = 0.0;
    meanAndLargest (to_mesh_distances, result.model_to_mesh, max_a);
    meanAndLargestDistance (on_mesh, *to_model, result.mesh_to_model, max_b, num_threads);
    result.largest = std::max (max_a, max_b);
    return result;
  }
} // namespace pcl_sparse
