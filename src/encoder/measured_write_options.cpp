#include <pcl_sparse/encoder/measured_write_options.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/resampling/footprint_slack.h>
#include <pcl_sparse/resampling/model_mesh_distance.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace pcl_sparse
{
  void
  MeasuredWriteOptions::validate () const
  {
    if (!(max_increase > 0.0 && max_increase <= 1.0))
      throw Error ("MeasuredWriteOptions: max_increase must be in (0, 1], got " + std::to_string (max_increase));
    if (points < 1000)
      throw Error ("MeasuredWriteOptions: points must be at least 1000, got " + std::to_string (points));
    for (const WriteCandidate& c : candidates)
      if (!(c.tolerance_scale > 0.0 && c.tolerance_scale <= 100.0) || c.extent_bits_change < -6 ||
          c.extent_bits_change > 6 || !(c.refine_steps >= 0.0) || !std::isfinite (c.refine_steps))
        throw Error ("MeasuredWriteOptions: a candidate needs tolerance_scale in (0, 100], extent_bits_change in "
                     "[-6, 6] and refine_steps finite and >= 0");
  }

  MeasuredWriteChoice
  measuredWriteOptions (const SparseSurfaceModel& model, const TriangleMesh& surface, const ModelWriteOptions& start,
                        const MeasuredWriteOptions& options)
  {
    options.validate ();
    if (!(start.tolerance > 0.0))
      throw Error ("measuredWriteOptions: the start must be a quantised file's options (tolerance > 0)");
    MeasuredWriteChoice choice;
    choice.options = start;

    struct Tried
    {
      ModelWriteOptions options;
      std::vector<std::uint8_t> bytes;
    };
    // The footprints' slack depends on the model only: found once for every candidate.
    const std::vector<FootprintSlack> slack = start.footprint_slack ? footprintSlack (model) : std::vector<FootprintSlack> ();
    std::vector<Tried> tried;
    tried.push_back ({start, encodeModel (model, start, slack)});
    choice.start_bytes = choice.bytes = tried.front ().bytes.size ();
    choice.file = tried.front ().bytes;
    for (const WriteCandidate& c : options.candidates)
    {
      Tried t{start, {}};
      t.options.tolerance = std::clamp (start.tolerance * c.tolerance_scale, 1e-7, 0.1);
      t.options.extent_bits = std::clamp (start.extent_bits + c.extent_bits_change, 2, 8);
      t.options.footprint_refine_steps = c.refine_steps;
      t.bytes = encodeModel (model, t.options, slack);
      tried.push_back (std::move (t));
    }
    // Smallest first; equal sizes in the candidates' order, the start before them.
    std::stable_sort (tried.begin (), tried.end (),
                      [] (const Tried& a, const Tried& b) { return a.bytes.size () < b.bytes.size (); });

    // Both halves of the Chamfer distance, as bench/bench_format measures it, with fewer points.
    const MeshSurfaceDistance to_surface (surface, 2 * surface.triangles.size () + 50000);
    std::vector<Eigen::Vector3d> on_surface;
    sampleMeshSurface (surface, options.points, static_cast<unsigned> (options.seed), on_surface);
    SparseSurfaceResamplingOptions resampling;
    resampling.seed = options.seed;
    auto distanceOf = [&] (const SparseSurfaceModel::ConstPtr& m) {
      return modelChamferDistance (m, to_surface, on_surface, options.points, resampling, options.num_threads).value ();
    };
    // The model itself, not a copy: a pointer that owns nothing (shared_ptr's aliasing constructor), which
    // the resampling holds only while it measures.
    choice.lossless_distance = distanceOf (SparseSurfaceModel::ConstPtr (SparseSurfaceModel::ConstPtr (), &model));
    if (!(choice.lossless_distance > 0.0) || !std::isfinite (choice.lossless_distance))
      return choice;  // an exact model: no increase is measurable against it, keep the bound's file
    // The first within the allowance; none: the nearest.
    double nearest = std::numeric_limits<double>::infinity ();
    for (const Tried& t : tried)
    {
      const double distance = distanceOf (std::make_shared<const SparseSurfaceModel> (decodeModel (t.bytes.data (), t.bytes.size ())));
      ++choice.measured;
      if (distance < nearest)  // a file that passes is nearer than every one measured before it (they failed)
      {
        nearest = distance;
        choice.options = t.options;
        choice.bytes = t.bytes.size ();
        choice.file = t.bytes;
        choice.distance = distance;
      }
      if (distance <= (1.0 + options.max_increase) * choice.lossless_distance)
        break;
    }
    return choice;
  }
} // namespace pcl_sparse
