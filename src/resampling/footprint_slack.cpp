#include <pcl_sparse/resampling/footprint_slack.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/parallel_failure.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/model/tiled_model.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/patch_geometry.h>
#include <pcl_sparse/resampling/patch_ownership.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace pcl_sparse
{
  void
  FootprintSlackOptions::validate () const
  {
    auto fail = [] (const std::string& field, double value, const std::string& range) {
      throwOutOfRange ("FootprintSlackOptions", field, value, range);
    };
    if (!(max_centrality > 0.0 && max_centrality <= 1.0))
      fail ("max_centrality", max_centrality, "0 < max_centrality <= 1");
    if (!(inward >= 0.0 && inward < 1.0))
      fail ("inward", inward, "0 <= inward < 1");
    if (!(outward >= 0.0) || !std::isfinite (outward))
      fail ("outward", outward, "outward >= 0, finite");
  }

  namespace
  {
    /// The slack of the patches in \a which (indices into \a model), in that order.
    std::vector<FootprintSlack>
    slackOf (const SparseSurfaceModel& model, const std::vector<std::size_t>& which, const FootprintSlackOptions& options,
             int threads)
    {
      const PatchEvaluator evaluator (model);
      const PatchOwnership ownership (evaluator, PatchOwnershipOptions (), threads);
      const double max_slope_squared = ownership.maxSlopeSquared ();
      const long n = static_cast<long> (which.size ());
      std::vector<FootprintSlack> slack (which.size ());
      constexpr int steps = 3;  // places tested each way: a third of the way, two thirds, all of it
      // A border on a knife edge is found at the extent or this far in (its place may lie just outside the
      // other side's footprint, whose border meets it at the edge).
      constexpr double knife_edge_depth = 0.1;
      ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads) if(n > 64)
      for (long w = 0; w < n; ++w)
        failure.run ([&] {
          const std::size_t p = which[static_cast<std::size_t> (w)];
          const PatchCode& code = model.patches[p];
          const std::vector<float>& extent = code.footprint.extent;
          const std::size_t k = extent.size ();
          FootprintSlack& s = slack[static_cast<std::size_t> (w)];
          s.lower = extent;
          s.upper = extent;
          for (std::size_t i = 0; i < k; ++i)
          {
            const double turn = static_cast<double> (i) / static_cast<double> (k);
            const double c = std::cos (2.0 * M_PI * turn), sn = std::sin (2.0 * M_PI * turn);
            // The place of p's surface at t along the ray, if it is a valid place of p.
            auto place = [&] (double t, Eigen::Vector3d& q) {
              const HeightSample h = evaluator.sample (p, t * c, t * sn, false);
              if (!isValidPlace (h, ownership.options (), max_slope_squared))
                return false;
              q = patchPoint (code, t * c, t * sn, h);
              return true;
            };
            // Whether that place is held by a neighbour at most as centrally as \a centrality.
            auto held = [&] (double t, double centrality) {
              Eigen::Vector3d q;
              return place (t, q) && ownership.heldByAnother (p, q, centrality, turn);
            };
            const double e = extent[i];
            Eigen::Vector3d border;
            if (!(e > 0.0) || !place (e, border))
              continue;
            if (!ownership.heldByAnother (p, border, options.max_centrality, turn))
            {
              Eigen::Vector3d inside;
              if (ownership.clearedByFacingAway (p, border, turn) ||
                  (place (e * (1.0 - knife_edge_depth), inside) && ownership.clearedByFacingAway (p, inside, turn)))
              {
                s.knife_edge.resize (k, 0);
                s.knife_edge[i] = 1;
              }
              continue;
            }
            // Drawn further in, the places left go to the neighbour, whose own border may be drawn as far in:
            // held that much more centrally, they stay inside it.
            const double inner_centrality = options.max_centrality * (1.0 - options.inward);
            if (ownership.heldByAnother (p, border, inner_centrality, turn))
              for (int j = 1; j <= steps && held (e * (1.0 - options.inward * j / steps), inner_centrality); ++j)
                s.lower[i] = static_cast<float> (e * (1.0 - options.inward * j / steps));
            // Past a trim cut the code's normal points away from the surface: a place there is the patch's
            // own to leave, not one it may take from the neighbour.
            const bool cut = code.footprint.trimmed.size () == k && code.footprint.trimmed[i];
            for (int j = 1; !cut && j <= steps && held (e * (1.0 + options.outward * j / steps), options.max_centrality); ++j)
              s.upper[i] = static_cast<float> (e * (1.0 + options.outward * j / steps));
          }
          // A knife edge's border runs over neighbouring angles; one whose place lies a hair outside the other
          // side's footprint is one too.
          if (!s.knife_edge.empty ())
          {
            const std::vector<char> found = s.knife_edge;
            for (std::size_t i = 0; i < k; ++i)
              s.knife_edge[i] = found[i] || found[(i + 1) % k] || found[(i + k - 1) % k];
          }
        });
      failure.rethrow ();
      return slack;
    }

    /// A bound on the world radius of the ball around a patch's seed that holds its surface where resampling
    /// keeps it (PatchOwnership's reach: the largest extent and |h| <= max_height, 1% margin).
    double
    reachBound (const PatchCode& code, double max_height)
    {
      const double extent = code.footprint.extent.empty () ? 1.0 : code.footprint.largestExtent ();
      return code.radius * std::sqrt (extent * extent + max_height * max_height) * 1.02;
    }
  } // namespace

  std::vector<FootprintSlack>
  footprintSlack (const SparseSurfaceModel& model, const FootprintSlackOptions& options, int threads)
  {
    return footprintSlack (model, 0, model.patches.size (), options, threads);
  }

  std::vector<FootprintSlack>
  footprintSlack (const SparseSurfaceModel& model, std::size_t first, std::size_t count, const FootprintSlackOptions& options,
                  int threads)
  {
    options.validate ();
    threads = resolveThreadCount (threads);
    const std::size_t m = model.patches.size ();
    if (first > m || count > m - first)
      throw Error ("footprintSlack: patches [" + std::to_string (first) + ", " + std::to_string (first + count) +
                   ") outside the model's " + std::to_string (m));
    std::vector<std::size_t> run (count);
    std::iota (run.begin (), run.end (), first);
    if (count == m)
      return slackOf (model, run, options, threads);
    // Only the patches whose balls can meet those of the run's patches take part (in the model's order, so
    // that ties between contenders fall as in the whole model): the slack is the whole model's, in a tile's
    // memory.
    const double max_height = PatchOwnershipOptions ().max_height;
    Eigen::AlignedBox3d box;
    double run_reach = 0.0;
    for (std::size_t p = first; p < first + count; ++p)
    {
      box.extend (model.patches[p].origin);
      run_reach = std::max (run_reach, reachBound (model.patches[p], max_height));
    }
    SparseSurfaceModel near = subModel (model, 0, 0);
    std::vector<std::size_t> which;
    for (std::size_t p = 0; p < m; ++p)
    {
      const bool in_run = p >= first && p < first + count;
      if (in_run || (count > 0 && box.exteriorDistance (model.patches[p].origin) <= reachBound (model.patches[p], max_height) + run_reach))
      {
        if (in_run)
          which.push_back (near.patches.size ());
        near.patches.push_back (model.patches[p]);
      }
    }
    return slackOf (near, which, options, threads);
  }
} // namespace pcl_sparse
