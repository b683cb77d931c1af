#include <pcl_sparse/encoder/measured_write_options.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/parallel_failure.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/resampling/footprint_slack.h>
#include <pcl_sparse/resampling/model_mesh_distance.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// A file measuredWriteOptions tries.
    struct Tried
    {
      ModelWriteOptions options;
      std::vector<std::uint8_t> bytes;
      double distance = -1.0;  ///< measured with MeasuredWriteOptions::points (-1: not measured)
    };

    /// The file of \a start, then those of the \a candidates, in that order, with the footprints' \a slack.
    std::vector<Tried>
    encodeCandidates (const SparseSurfaceModel& model, const ModelWriteOptions& start,
                      const std::vector<WriteCandidate>& candidates, const std::vector<FootprintSlack>& slack)
    {
      std::vector<Tried> tried;
      tried.push_back ({start, encodeModel (model, start, slack)});
      for (const WriteCandidate& c : candidates)
      {
        Tried t{start, {}};
        t.options.tolerance = std::clamp (start.tolerance * c.tolerance_scale, 1e-7, 0.1);
        t.options.extent_bits = std::clamp (start.extent_bits + c.extent_bits_change, 2, 8);
        t.options.footprint_refine_steps = c.refine_steps;
        t.bytes = encodeModel (model, t.options, slack);
        tried.push_back (std::move (t));
      }
      return tried;
    }

    /// Both halves of the Chamfer distance to the surface: a distance to it, and points drawn on it (as many as
    /// are resampled from each model).
    struct Yardstick
    {
      std::unique_ptr<MeshSurfaceDistance> to_surface;
      std::vector<Eigen::Vector3d> on_surface;
    };

    std::vector<Eigen::Vector3d>
    pointsOn (const TriangleMesh& surface, std::size_t points, std::uint64_t seed)
    {
      std::vector<Eigen::Vector3d> on_surface;
      sampleMeshSurface (surface, points, static_cast<unsigned> (seed), on_surface);
      return on_surface;
    }
    /// The files of encodeCandidates, and the first measurement's \a quick yardstick (a sampling of \a surface
    /// with 2 T + 50000 points in a k-d tree, and options.points points on it). Both are serial (the yardstick
    /// 0.36 s on koala-loop1-200k): built side by side, after the footprints' slack (on every thread).
    std::vector<Tried>
    encodeBesideQuickYardstick (const SparseSurfaceModel& model, const TriangleMesh& surface,
                                const ModelWriteOptions& start, const MeasuredWriteOptions& options, Yardstick& quick)
    {
      // The footprints' slack depends on the model only: found once for every candidate.
      std::vector<FootprintSlack> slack;
      if (start.footprint_slack)
        slack = footprintSlack (model, FootprintSlackOptions (), options.num_threads);
      std::vector<Tried> tried;
      ParallelFailure failure;
#pragma omp parallel sections num_threads (std::min (2, resolveThreadCount (options.num_threads)))
      {
#pragma omp section
        failure.run ([&] { tried = encodeCandidates (model, start, options.candidates, slack); });
#pragma omp section
        failure.run ([&] {
          quick = {std::make_unique<MeshSurfaceDistance> (
                     surface, MeshSurfaceDistance::Sampling {2 * surface.triangles.size () + 50000}),
                   pointsOn (surface, options.points, options.seed)};
        });
      }
      failure.rethrow ();
      return tried;
    }
  } // namespace

  void
  MeasuredWriteOptions::validate () const
  {
    if (!(max_increase > 0.0 && max_increase <= 1.0))
      throw Error ("MeasuredWriteOptions: max_increase must be in (0, 1], got " + std::to_string (max_increase));
    if (points < 1000)
      throw Error ("MeasuredWriteOptions: points must be at least 1000, got " + std::to_string (points));
    if (confirm_points > 0 && confirm_points < 1000)
      throw Error ("MeasuredWriteOptions: confirm_points must be 0 or at least 1000, got " + std::to_string (confirm_points));
    if (!(confirm_max_increase > 0.0 && confirm_max_increase <= 1.0) || !(confirm_band >= max_increase) ||
        !std::isfinite (confirm_band))
      throw Error ("MeasuredWriteOptions: confirm_max_increase must be in (0, 1] and confirm_band finite and at least "
                   "max_increase");
    for (const WriteCandidate& c : candidates)
      if (!(c.tolerance_scale > 0.0 && c.tolerance_scale <= 100.0) || c.extent_bits_change < -6 ||
          c.extent_bits_change > 6 || !(c.refine_steps >= 0.0) || !std::isfinite (c.refine_steps))
        throw Error ("MeasuredWriteOptions: a candidate needs tolerance_scale in (0, 100], extent_bits_change in "
                     "[-6, 6] and refine_steps finite and >= 0");
  }

  MeasuredWriteChoice
  measuredWriteOptions (const SparseSurfaceModel& model, const TriangleMesh& surface, const ModelWriteOptions& start,
                        const MeasuredWriteOptions& options, const ProgressCallback& progress)
  {
    options.validate ();
    if (!(start.tolerance > 0.0))
      throw Error ("measuredWriteOptions: the start must be a quantised file's options (tolerance > 0)");
    MeasuredWriteChoice choice;
    choice.options = start;

    // Both halves of the Chamfer distance, as bench/bench_format measures it: first with fewer points and a
    // sampling of the surface (a nearest triangle found among those of the nearest samples); the confirmation
    // as the bench does (as many points, the distance to the surface exact).
    Yardstick quick;
    std::vector<Tried> tried = encodeBesideQuickYardstick (model, surface, start, options, quick);
    choice.start_bytes = choice.bytes = tried.front ().bytes.size ();
    choice.file = tried.front ().bytes;
    // Smallest first; equal sizes in the candidates' order, the start before them.
    std::stable_sort (tried.begin (), tried.end (),
                      [] (const Tried& a, const Tried& b) { return a.bytes.size () < b.bytes.size (); });

    Yardstick confirm;  // made for the first confirmation
    SparseSurfaceResamplingOptions resampling;
    resampling.seed = options.seed;
    auto distanceOf = [&] (const SparseSurfaceModel::ConstPtr& m, const Yardstick& y) {
      return modelChamferDistance (m, *y.to_surface, y.on_surface, y.on_surface.size (), resampling, options.num_threads)
        .value ();
    };
    auto decoded = [] (const Tried& t) {
      return std::make_shared<const SparseSurfaceModel> (decodeModel (t.bytes.data (), t.bytes.size ()));
    };
    // The model itself, not a copy: a pointer that owns nothing (shared_ptr's aliasing constructor), which
    // the resampling holds only while it measures.
    const SparseSurfaceModel::ConstPtr lossless (SparseSurfaceModel::ConstPtr (), &model);
    // Progress: measurements done of the most there can be (the lossless model and every file; with a
    // confirmation, the lossless model again and every file but the largest), each a resampling and its distances.
    const double most = static_cast<double> (1 + tried.size () + (options.confirm_points > 0 ? tried.size () : 0));
    std::size_t measurements = 0;
    auto measured = [&] () {
      if (progress)
        progress ("file", std::min (1.0, static_cast<double> (++measurements) / most));
    };
    auto finished = [&] () {  // the stage ends at 1 whichever way it returns
      if (progress)
        progress ("file", 1.0);
    };
    if (progress)
      progress ("file", 0.0);
    choice.lossless_distance = distanceOf (lossless, quick);
    measured ();
    if (!(choice.lossless_distance > 0.0) || !std::isfinite (choice.lossless_distance))
    {
      finished ();
      return choice;  // an exact model: no increase is measurable against it, keep the bound's file
    }
    auto choose = [&] (const Tried& t, double distance) {
      choice.options = t.options;
      choice.bytes = t.bytes.size ();
      choice.file = t.bytes;
      choice.distance = distance;
    };
    // The first within the allowance; none: the nearest.
    double nearest = std::numeric_limits<double>::infinity ();
    std::size_t chosen = 0;
    for (std::size_t i = 0; i < tried.size (); ++i)
    {
      Tried& t = tried[i];
      t.distance = distanceOf (decoded (t), quick);
      measured ();
      ++choice.measured;
      if (t.distance < nearest)  // a file that passes is nearer than every one measured before it (they failed)
      {
        nearest = t.distance;
        chosen = i;
        choose (t, t.distance);
      }
      if (t.distance <= (1.0 + options.max_increase) * choice.lossless_distance)
        break;
    }
    // Smaller files that read just over the allowance, measured again with as many points as the bench.
    if (options.confirm_points == 0)
    {
      finished ();
      return choice;
    }
    double lossless_confirmed = -1.0;
    for (std::size_t i = 0; i < chosen; ++i)
    {
      const Tried& t = tried[i];
      if (!(t.distance > 0.0) || t.distance > (1.0 + options.confirm_band) * choice.lossless_distance)
        continue;
      if (lossless_confirmed < 0.0)
      {
        confirm = {std::make_unique<MeshSurfaceDistance> (surface, options.num_threads),
                   pointsOn (surface, options.confirm_points, options.seed)};
        lossless_confirmed = distanceOf (lossless, confirm);
        measured ();
        if (!(lossless_confirmed > 0.0) || !std::isfinite (lossless_confirmed))
          break;  // nothing to measure an increase against
      }
      const double distance = distanceOf (decoded (t), confirm);
      measured ();
      ++choice.confirmed;
      if (distance <= (1.0 + options.confirm_max_increase) * lossless_confirmed)
      {
        choose (t, choice.lossless_distance * distance / lossless_confirmed);  // on the first measurement's scale
        choice.chosen_by_confirmation = true;
        break;
      }
    }
    finished ();
    return choice;
  }
} // namespace pcl_sparse
