#include <pcl_sparse/format/coding_order.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/parallel_failure.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/geometry/morton_order.h>
#include <pcl_sparse/model/tiled_model.h>

#include <algorithm>
#include <numeric>

namespace pcl_sparse
{
  std::vector<int>
  seedMortonOrder (const SparseSurfaceModel& model)
  {
    std::vector<Eigen::Vector3d> seeds (model.patches.size ());
    for (std::size_t p = 0; p < seeds.size (); ++p)
      seeds[p] = model.patches[p].origin;
    std::vector<int> order = mortonOrder (seeds);
    std::stable_partition (order.begin (), order.end (), [&] (int p) { return !model.patches[p].atoms.empty (); });
    return order;
  }

  std::vector<int>
  smallerCodingOrder (const SparseSurfaceModel& model, int num_threads, std::size_t max_trial_patches, double tolerance)
  {
    std::vector<int> own (model.patches.size ());
    std::iota (own.begin (), own.end (), 0);
    std::vector<int> morton = seedMortonOrder (model);
    if (morton == own || model.patches.size () > max_trial_patches)
      return morton;
    ModelWriteOptions options;
    options.tolerance = tolerance;
    // The slack (resampling/footprint_slack.h) takes most of a write's time and moves both files alike: spot
    // 0.15 s with it, 0.05 s without; zstd at level 1 (only RADI compresses) a quarter of what is left. The
    // same choice on every shared mesh.
    options.footprint_slack = false;
    options.zstd_level = 1;
    // Whole copies: a field left out would be left out of the trial's file too (the vertex lists, which the
    // file does not hold, cost koala-loop1-200k's 1721 patches no measurable time).
    SparseSurfaceModel reordered = subModel (model, 0, 0);
    reordered.patches.reserve (model.patches.size ());
    for (int p : morton)
      reordered.patches.push_back (model.patches[p]);
    // The two trials at once (each writes its own bytes: the same sizes for any thread count). A model a trial
    // cannot write (e.g. no bbox diagonal) keeps its order: the writer will say why; any other failure (an
    // allocation) reaches the caller.
    std::size_t sizes[2] = {0, 0};
    bool refused = false;
    ParallelFailure failure;
#pragma omp parallel for num_threads (std::min (2, resolveThreadCount (num_threads))) schedule (static, 1)
    for (int k = 0; k < 2; ++k)
      failure.run ([&] {
        try
        {
          sizes[k] = encodeModel (k == 0 ? model : reordered, options).size ();
        }
        catch (const Error&)
        {
#pragma omp atomic write
          refused = true;
        }
      });
    failure.rethrow ();
    if (refused)
      return own;
    return sizes[1] < sizes[0] ? morton : own;
  }
} // namespace pcl_sparse
