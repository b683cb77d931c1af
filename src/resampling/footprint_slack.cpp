#include <pcl_sparse/resampling/footprint_slack.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/parallel_failure.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/patch_geometry.h>
#include <pcl_sparse/resampling/patch_ownership.h>

#include <cmath>

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

  std::vector<FootprintSlack>
  footprintSlack (const SparseSurfaceModel& model, const FootprintSlackOptions& options, int threads)
  {
    options.validate ();
    threads = resolveThreadCount (threads);
    const PatchEvaluator evaluator (model);
    const PatchOwnership ownership (evaluator, PatchOwnershipOptions (), threads);
    const double max_slope_squared = ownership.maxSlopeSquared ();
    const long m = static_cast<long> (model.patches.size ());
    std::vector<FootprintSlack> slack (model.patches.size ());
    constexpr int steps = 3;  // places tested each way: a third of the way, two thirds, all of it
    ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads) if(m > 64)
    for (long p = 0; p < m; ++p)
      failure.run ([&] {
        const PatchCode& code = model.patches[p];
        const std::vector<float>& extent = code.footprint.extent;
        const std::size_t k = extent.size ();
        FootprintSlack& s = slack[p];
        s.lower = extent;
        s.upper = extent;
        for (std::size_t i = 0; i < k; ++i)
        {
          const double turn = static_cast<double> (i) / static_cast<double> (k);
          const double c = std::cos (2.0 * M_PI * turn), sn = std::sin (2.0 * M_PI * turn);
          // Whether the place of p's surface at t along the ray is held by a neighbour at most as centrally as
          // \a centrality.
          auto held = [&] (double t, double centrality) {
            const HeightSample h = evaluator.sample (static_cast<std::size_t> (p), t * c, t * sn, false);
            if (!isValidPlace (h, ownership.options (), max_slope_squared))
              return false;
            return ownership.heldByAnother (static_cast<std::size_t> (p), patchPoint (code, t * c, t * sn, h),
                                            centrality, turn);
          };
          const double e = extent[i];
          if (!(e > 0.0) || !held (e, options.max_centrality))
            continue;
          // Drawn further in, the places left go to the neighbour, whose own border may be drawn as far in: held
          // that much more centrally, they stay inside it.
          const double inner_centrality = options.max_centrality * (1.0 - options.inward);
          if (held (e, inner_centrality))
            for (int j = 1; j <= steps && held (e * (1.0 - options.inward * j / steps), inner_centrality); ++j)
              s.lower[i] = static_cast<float> (e * (1.0 - options.inward * j / steps));
          for (int j = 1; j <= steps && held (e * (1.0 + options.outward * j / steps), options.max_centrality); ++j)
            s.upper[i] = static_cast<float> (e * (1.0 + options.outward * j / steps));
        }
      });
    failure.rethrow ();
    return slack;
  }
} // namespace pcl_sparse
