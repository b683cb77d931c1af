#include <pcl_sparse/format/file_tolerance.h>

#include <pcl_sparse/common/error.h>

#include <limits>

namespace pcl_sparse
{
  SortedVertexErrors
  sortedVertexErrors (const std::vector<double>& vertex_errors)
  {
    SortedVertexErrors sorted;
    sorted.errors.reserve (vertex_errors.size ());
    for (double e : vertex_errors)
      if (std::isfinite (e) && e >= 0.0)
        sorted.errors.push_back (e);
    std::sort (sorted.errors.begin (), sorted.errors.end ());
    sorted.sum.assign (sorted.errors.size () + 1, 0.0);
    sorted.sum_squares.assign (sorted.errors.size () + 1, 0.0);
    for (std::size_t k = 0; k < sorted.errors.size (); ++k)
    {
      sorted.sum[k + 1] = sorted.sum[k] + sorted.errors[k];
      sorted.sum_squares[k + 1] = sorted.sum_squares[k] + sorted.errors[k] * sorted.errors[k];
    }
    return sorted;
  }

  double
  expectedQuantisationIncrease (const SortedVertexErrors& errors, double displacement)
  {
    if (!(displacement > 0.0) || errors.errors.empty ())
      return 0.0;
    // Sum over the errors below a of (a - e)^2 / (2 a) = (k a^2 - 2 a S1 + S2) / (2 a).
    const std::size_t k = static_cast<std::size_t> (
      std::lower_bound (errors.errors.begin (), errors.errors.end (), displacement) - errors.errors.begin ());
    const double a = displacement;
    const double below = std::max (0.0, static_cast<double> (k) * a * a - 2.0 * a * errors.sum[k] + errors.sum_squares[k]);
    const double total = errors.sum.back ();
    if (!(total > 0.0))
      return std::numeric_limits<double>::infinity ();
    return below / (2.0 * a) / total;
  }

  ModelWriteOptions
  derivedWriteOptions (const ModelStatistics& stats, const std::vector<double>& vertex_errors, double bbox_diagonal,
                       const ModelWriteOptions& base, const DerivedFileOptions& options)
  {
    if (!(options.max_fraction > 0.0) || !(options.distance_budget > 0.0) || !(options.spread > 0.0) ||
        !std::isfinite (options.max_fraction + options.distance_budget + options.spread))
      throw Error ("derivedWriteOptions: max_fraction, distance_budget and spread must be positive and finite");
    ModelWriteOptions derived = base;
    derived.tolerance = derivedFileTolerance (stats, options.max_fraction);
    if (vertex_errors.empty () || !(bbox_diagonal > 0.0) || !std::isfinite (bbox_diagonal))
      return derived;
    const SortedVertexErrors sorted = sortedVertexErrors (vertex_errors);
    auto increase = [&] (double tolerance) {
      return expectedQuantisationIncrease (sorted, options.spread * tolerance * bbox_diagonal);
    };
    if (increase (derived.tolerance) <= options.distance_budget)
      return derived;
    // The increase grows with the tolerance: bisect log t between the floor and the bound.
    double low = 1e-7, high = derived.tolerance;
    if (increase (low) > options.distance_budget)
      high = low;
    for (int i = 0; i < 60 && high > low * (1.0 + 1e-9); ++i)
    {
      const double middle = std::sqrt (low * high);
      (increase (middle) <= options.distance_budget ? low : high) = middle;
    }
    derived.tolerance = low;
    // A concentrated error: borders across creases are what the file loses most, so finer extents, refined
    // as many of their levels apart as before (half the distance: merged patches have longer borders).
    if (base.extent_bits < 8)
      derived.extent_bits = base.extent_bits + 1;
    return derived;
  }
} // namespace pcl_sparse
