/// Patch radii on the grid 2^(k / 32) (coding/radius_grid.h): the encoder stores them there, and a quantised
/// file holds them exactly, in one byte plane.

#include "model_helpers.h"

#include <pcl_sparse/coding/radius_grid.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pcl_sparse;
using namespace pcl_sparse_test;

namespace
{
  /// The raw bytes of the section \a tag of a model file (0 without one).
  std::uint64_t
  rawSectionBytes (const std::vector<std::uint8_t>& file, const std::string& tag)
  {
    return fileSection (inspectModel (file.data (), file.size ()), tag).raw_bytes;
  }

  /// The largest |(x', y')| of a patch's vertices: 1 when its radius is the farthest vertex's distance.
  double
  farthestVertex (const PatchCode& patch)
  {
    double farthest = 0.0;
    for (const Eigen::Vector2d& xy : patch.vertex_xy)
      farthest = std::max (farthest, xy.norm ());
    return farthest;
  }
} // namespace

TEST (RadiusGrid, RoundsUpToTheNextStepAndKeepsGridRadii)
{
  const double step = std::exp2 (1.0 / kRadiusStepsPerOctave);
  for (double radius : {1e-7, 0.0131, 0.5, 0.7071, 1.0, 3.7, 12345.6})
  {
    const double grid = radiusOnGrid (radius);
    EXPECT_GE (grid, radius);
    EXPECT_LT (grid, radius * step * (1.0 + 1e-12)) << radius;
    std::int64_t k = 0;
    ASSERT_TRUE (radiusGridStep (grid, k)) << radius;
    EXPECT_NEAR (grid, std::exp2 (static_cast<double> (k) / kRadiusStepsPerOctave), 1e-14 * grid);
    EXPECT_EQ (radiusOnGrid (grid), grid) << "a grid radius stays on its step";
  }
  std::int64_t k = -1;
  EXPECT_EQ (radiusOnGrid (1.0), 1.0);
  ASSERT_TRUE (radiusGridStep (1.0, k));
  EXPECT_EQ (k, 0);
  EXPECT_EQ (radiusOnGrid (4.0), 4.0);
  ASSERT_TRUE (radiusGridStep (4.0, k));
  EXPECT_EQ (k, 2 * kRadiusStepsPerOctave);
  ASSERT_TRUE (radiusGridStep (std::exp (std::log (2.0) * -37.0 / kRadiusStepsPerOctave), k))
      << "as a file's log scale gives it back";
  EXPECT_EQ (k, -37);
  EXPECT_NEAR (radiusOnGrid (1.01), std::exp2 (1.0 / kRadiusStepsPerOctave), 1e-15);

  EXPECT_FALSE (radiusGridStep (1.01, k));
  EXPECT_FALSE (radiusGridStep (0.0, k));
  EXPECT_FALSE (radiusGridStep (-1.0, k));
  EXPECT_FALSE (radiusGridStep (std::numeric_limits<double>::quiet_NaN (), k));
  EXPECT_FALSE (radiusGridStep (std::numeric_limits<double>::infinity (), k));
  EXPECT_EQ (radiusOnGrid (0.0), 0.0);
  EXPECT_EQ (radiusOnGrid (-2.0), -2.0);
  EXPECT_TRUE (std::isnan (radiusOnGrid (std::numeric_limits<double>::quiet_NaN ())));
}

TEST (RadiusGrid, EncoderStoresGridRadiiButThePaperPresetDoesNot)
{
  const auto sphere = std::make_shared<TriangleMesh> (makeIcosphere (3));
  const auto model = encodeMesh (sphere);
  ASSERT_GT (model->numPatches (), 50u);
  double tightest = 1.0;
  for (const PatchCode& patch : model->patches)
  {
    std::int64_t k = 0;
    EXPECT_TRUE (radiusGridStep (patch.radius, k)) << patch.radius;
    const double farthest = farthestVertex (patch);
    EXPECT_LE (farthest, 1.0 + 1e-12) << "the grid radius only grows";
    EXPECT_GE (farthest, std::exp2 (-1.0 / kRadiusStepsPerOctave) - 1e-12) << "by at most one step";
    tightest = std::min (tightest, farthest);
  }
  EXPECT_LT (tightest, 0.999) << "some radius was rounded up";

  const auto paper = encodeMesh (sphere, encoderPresetOptions (EncoderPreset::Paper));
  std::size_t on_grid = 0;
  for (const PatchCode& patch : paper->patches)
  {
    std::int64_t k = 0;
    on_grid += radiusGridStep (patch.radius, k);
    EXPECT_NEAR (farthestVertex (patch), 1.0, 1e-12) << "the paper's r_P: the farthest vertex";
  }
  EXPECT_LT (on_grid, paper->numPatches () / 10);
}

TEST (RadiusGrid, QuantisedFileHoldsGridRadiiExactlyInOneBytePlane)
{
  const auto sphere = std::make_shared<TriangleMesh> (makeIcosphere (3));
  ModelWriteOptions write;
  write.tolerance = 1e-4;
  for (const bool grid : {true, false})
  {
    SparseSurfaceEncoderOptions options;
    options.coding.radius_on_grid = grid;
    const auto model = encodeMesh (sphere, options);
    const std::vector<std::uint8_t> file = encodeModel (*model, write);
    const SparseSurfaceModel decoded = decodeModel (file.data (), file.size ());
    ASSERT_EQ (decoded.numPatches (), model->numPatches ());
    double largest_change = 0.0;
    for (std::size_t p = 0; p < model->numPatches (); ++p)
      largest_change = std::max (largest_change, std::abs (decoded.patches[p].radius / model->patches[p].radius - 1.0));
    const std::uint64_t planes = rawSectionBytes (file, "RADI") / model->numPatches ();
    if (grid)
    {
      EXPECT_LT (largest_change, 1e-14);
      EXPECT_EQ (planes, 1u);
      // Saved again, the decoded radii are still recognised as the grid's.
      const std::vector<std::uint8_t> again = encodeModel (decoded, write);
      EXPECT_EQ (rawSectionBytes (again, "RADI"), decoded.numPatches ());
    }
    else
    {
      EXPECT_GT (largest_change, 1e-9) << "off the grid, the tolerance's step rounds the radii";
      EXPECT_GE (planes, 2u) << "and takes more bits";
    }
  }
}

// Radii a hair off the grid (within radiusGridStep's round-off allowance) are taken as on it only where that
// hair is within the tolerance's own half step: at a fine enough tolerance the file keeps them as they are.
TEST (RadiusGrid, RadiiOffTheGridByMoreThanTheToleranceKeepTheirOwnStep)
{
  const auto sphere = std::make_shared<TriangleMesh> (makeIcosphere (2));
  SparseSurfaceModel model = *encodeMesh (sphere);
  for (PatchCode& patch : model.patches)
    patch.radius *= 1.0 + 2e-8;  // 32 log2 moves by 9e-7: still "on the grid" within round-off
  for (const double tolerance : {1e-4, 1e-9})
  {
    ModelWriteOptions write;
    write.tolerance = tolerance;
    const std::vector<std::uint8_t> file = encodeModel (model, write);
    const SparseSurfaceModel decoded = decodeModel (file.data (), file.size ());
    double largest_change = 0.0;
    for (std::size_t p = 0; p < model.numPatches (); ++p)
      largest_change = std::max (largest_change, std::abs (decoded.patches[p].radius / model.patches[p].radius - 1.0));
    if (tolerance > 1e-6)
    {
      EXPECT_NEAR (largest_change, 2e-8, 1e-9) << "snapped to the grid, well within the tolerance's step";
      EXPECT_EQ (rawSectionBytes (file, "RADI"), model.numPatches ());
    }
    else
      EXPECT_LT (largest_change, 5e-9) << "the tolerance's own step (about 5e-9 here)";
  }
}
