// The quantised file's options derived from the model's vertex errors (format/file_tolerance.h).
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/file_tolerance.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// The statistics derivedWriteOptions reads of a model with these vertex errors and bbox diagonal 1.
  ModelStatistics
  statisticsOf (const std::vector<double>& errors)
  {
    ModelStatistics stats;
    double sum = 0.0;
    for (double e : errors)
      sum += e;
    stats.num_vertices = errors.size ();
    stats.mean_error_over_diagonal = sum / static_cast<double> (errors.size ());
    return stats;
  }
} // namespace

TEST (FileTolerance, ExpectedIncreaseIsTheMeanDistanceAddedByAnEvenDisplacement)
{
  // E|e + d| for d even over [-a, a]: (a^2 + e^2) / (2 a) below a, e above. Errors 0, 1, 2, 3 (mean 1.5).
  const SortedVertexErrors errors = sortedVertexErrors ({3.0, 0.0, 2.0, 1.0});
  ASSERT_EQ (errors.errors, (std::vector<double>{0.0, 1.0, 2.0, 3.0}));
  EXPECT_DOUBLE_EQ (expectedQuantisationIncrease (errors, 0.0), 0.0);
  // a = 1: only the 0 moves, to 1/2 on average: +0.5 over a sum of 6.
  EXPECT_DOUBLE_EQ (expectedQuantisationIncrease (errors, 1.0), 0.5 / 6.0);
  // a = 2.5: (6.25 + 0) / 5 - 0, (6.25 + 1) / 5 - 1, (6.25 + 4) / 5 - 2.
  const double added = 6.25 / 5.0 + (7.25 / 5.0 - 1.0) + (10.25 / 5.0 - 2.0);
  EXPECT_NEAR (expectedQuantisationIncrease (errors, 2.5), added / 6.0, 1e-15);
  // Far larger than every error: every distance becomes about a / 2.
  EXPECT_NEAR (expectedQuantisationIncrease (errors, 1e6), (4 * 0.5e6 - 6.0) / 6.0, 1e-3);
  // A model with no error at all: any displacement is an infinite share of nothing.
  EXPECT_EQ (expectedQuantisationIncrease (sortedVertexErrors ({0.0, 0.0}), 1.0), std::numeric_limits<double>::infinity ());
  // Non-finite errors are dropped.
  EXPECT_EQ (sortedVertexErrors ({1.0, std::nan (""), std::numeric_limits<double>::infinity (), -1.0}).errors.size (), 1u);
}

TEST (FileTolerance, ErrorsSpreadEvenlyKeepTheBoundOfTheMeanError)
{
  // Every vertex 1e-4 off: at 3 x the mean error the displacements (0.12 x 3e-4) stay below every error,
  // no increase expected, the options are derivedFileTolerance's with 4-bit extents.
  const std::vector<double> errors (1000, 1e-4);
  const ModelWriteOptions derived = derivedWriteOptions (statisticsOf (errors), errors, 1.0);
  EXPECT_NEAR (derived.tolerance, 3e-4, 1e-15);
  EXPECT_EQ (derived.extent_bits, 4);
  EXPECT_EQ (derived.footprint_refine_steps, 2.0);
}

TEST (FileTolerance, ConcentratedErrorsLowerTheToleranceToTheBudget)
{
  // Half the vertices exact, half 1e-4 off (mean 5e-5): at 3 x the mean error (a = 0.12 x 1.5e-4 = 1.8e-5)
  // the exact half moves by a / 2 on average: +a / 2 / (2 x mean) = 9 %, over the 5 % budget. The budget is
  // met at a / (2 x 1e-4) = 0.05 (a below every non-zero error): a = 1e-5, tolerance 1e-5 / 0.12.
  std::vector<double> errors (1000, 0.0);
  for (std::size_t i = 0; i < errors.size (); i += 2)
    errors[i] = 1e-4;
  ModelWriteOptions base;
  base.zstd_level = 7;
  const ModelWriteOptions derived = derivedWriteOptions (statisticsOf (errors), errors, 1.0, base);
  EXPECT_NEAR (derived.tolerance, 1e-5 / 0.12, 1e-12);
  EXPECT_EQ (derived.extent_bits, 5);
  EXPECT_EQ (derived.footprint_refine_steps, 2.0);  // as many of the finer levels: refined half as far
  EXPECT_EQ (derived.zstd_level, 7);  // the other fields kept
  // Extents already at the format's 8 bits stay there, refined at the same steps.
  base.extent_bits = 8;
  const ModelWriteOptions finest = derivedWriteOptions (statisticsOf (errors), errors, 1.0, base);
  EXPECT_EQ (finest.extent_bits, 8);
  EXPECT_EQ (finest.footprint_refine_steps, 2.0);
  // In the bbox diagonal's units: a diagonal of 10 scales the errors' tolerance down by 10.
  ModelStatistics scaled = statisticsOf (errors);
  scaled.mean_error_over_diagonal /= 10.0;
  EXPECT_NEAR (derivedWriteOptions (scaled, errors, 10.0).tolerance, 1e-6 / 0.12, 1e-13);
  // A larger budget keeps the bound.
  DerivedFileOptions generous;
  generous.distance_budget = 0.1;
  EXPECT_NEAR (derivedWriteOptions (statisticsOf (errors), errors, 1.0, {}, generous).tolerance, 1.5e-4, 1e-15);
}

TEST (FileTolerance, WithoutVertexErrorsTheBoundOfTheMeanErrorAlone)
{
  // A tiled model's case: the statistics only.
  std::vector<double> errors (1000, 0.0);
  errors[0] = 1.0;
  const ModelWriteOptions derived = derivedWriteOptions (statisticsOf (errors), {}, 1.0);
  EXPECT_NEAR (derived.tolerance, 3e-3, 1e-15);
  EXPECT_EQ (derived.extent_bits, 4);
}

TEST (FileTolerance, AnExactModelGetsTheSmallestTolerance)
{
  const std::vector<double> errors (10, 0.0);
  const ModelWriteOptions derived = derivedWriteOptions (statisticsOf (errors), errors, 1.0);
  EXPECT_DOUBLE_EQ (derived.tolerance, 1e-7);
}

TEST (FileTolerance, BadRuleParametersAreRefused)
{
  const std::vector<double> errors (10, 1.0);
  for (double bad : {0.0, -1.0, std::nan (""), std::numeric_limits<double>::infinity ()})
  {
    DerivedFileOptions options;
    options.distance_budget = bad;
    EXPECT_THROW (derivedWriteOptions (statisticsOf (errors), errors, 1.0, {}, options), Error) << bad;
    options = {};
    options.spread = bad;
    EXPECT_THROW (derivedWriteOptions (statisticsOf (errors), errors, 1.0, {}, options), Error) << bad;
  }
}
