#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/model/sparse_surface_model.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace pcl_sparse;

namespace
{
  /// Two patches over three vertices: A (radius 2, constant height 0.5) covers vertices 0 and 1, B (flat,
  /// at (1, 0, 0)) covers vertex 1; vertex 2 is in no patch.
  SparseSurfaceModel
  twoPatchModel ()
  {
    SparseSurfaceModel model;
    model.basis = std::make_shared<CosineDictionary> (12);
    PatchCode a;
    a.radius = 2.0;
    a.atoms = {0};
    a.coefficients = {0.5};
    a.vertices = {0, 1};
    a.vertex_xy = {Eigen::Vector2d (0.0, 0.0), Eigen::Vector2d (0.5, 0.0)};
    PatchCode b;
    b.origin = Eigen::Vector3d (1.0, 0.0, 0.0);
    b.vertices = {1};
    b.vertex_xy = {Eigen::Vector2d (0.0, 0.0)};
    model.patches = {a, b};
    model.num_input_vertices = 3;
    return model;
  }
} // namespace

TEST (SparseSurfaceModel, ReconstructBlendsThePatchesEstimates)
{
  const SparseSurfaceModel model = twoPatchModel ();
  const std::vector<Eigen::Vector3d> v = model.reconstructVertices (3);
  ASSERT_EQ (v.size (), 3u);
  EXPECT_TRUE (v[0].isApprox (Eigen::Vector3d (0.0, 0.0, 1.0)));     // s + r (0, 0, 0.5)
  EXPECT_TRUE (v[1].isApprox (Eigen::Vector3d (1.0, 0.0, 0.5)));     // mean of (1, 0, 1) and (1, 0, 0)
  EXPECT_TRUE (std::isnan (v[2].x ()));                              // in no patch
  EXPECT_EQ (model.numNonZeros (), 1u);
  EXPECT_DOUBLE_EQ (model.compressionRatio (), (13.0 * 2 + 1) / 9.0);
}

TEST (SparseSurfaceModel, StatisticsAgainstTheInput)
{
  SparseSurfaceModel model = twoPatchModel ();
  model.bbox_diagonal = 2.0;
  const std::vector<Eigen::Vector3d> input = {Eigen::Vector3d (0.0, 0.0, 1.0), Eigen::Vector3d (1.0, 0.0, 0.0),
                                              Eigen::Vector3d (5.0, 5.0, 5.0)};
  std::vector<double> errors;
  const ModelStatistics s = model.statistics (input, &errors);
  EXPECT_EQ (s.num_vertices, 3u);
  EXPECT_EQ (s.num_patches, 2u);
  EXPECT_EQ (s.num_nonzeros, 1u);
  EXPECT_EQ (s.uncovered, 1u);
  ASSERT_EQ (errors.size (), 3u);
  EXPECT_NEAR (errors[0], 0.0, 1e-15);
  EXPECT_NEAR (errors[1], 0.5, 1e-15);
  EXPECT_EQ (errors[2], 0.0);
  EXPECT_NEAR (s.rmse, std::sqrt (0.25 / 2.0), 1e-15);  // over the two covered vertices
  EXPECT_NEAR (s.rmse_over_diagonal, s.rmse / 2.0, 1e-15);
  EXPECT_NEAR (s.max_error, 0.5, 1e-15);
  EXPECT_NEAR (s.compression_ratio, 3.0, 1e-15);
}

TEST (SparseSurfaceModel, EvaluateUsesTheBasis)
{
  SparseSurfaceModel model = twoPatchModel ();
  model.patches[0].atoms = {12 * 1 + 0};  // cos(pi x)
  model.patches[0].coefficients = {2.0};
  const HeightSample h = model.evaluate (0, 0.25, 0.7);
  EXPECT_NEAR (h.value, 2.0 * std::cos (M_PI * 0.25), 1e-14);
  EXPECT_NEAR (h.gradient.x (), -2.0 * M_PI * std::sin (M_PI * 0.25), 1e-13);
  EXPECT_NEAR (h.gradient.y (), 0.0, 1e-14);
}

TEST (PatchFootprint, ContainsAndExtent)
{
  PatchFootprint f;
  f.extent = {1.0f, 0.5f, 1.0f, 0.5f};  // angles 0, pi/2, pi, 3 pi/2
  EXPECT_NEAR (f.extentAt (0.0), 1.0, 1e-7);
  EXPECT_NEAR (f.extentAt (M_PI / 4), 0.75, 1e-7);
  EXPECT_NEAR (f.extentAt (-M_PI / 2), 0.5, 1e-7);
  EXPECT_TRUE (f.contains (0.9, 0.0));
  EXPECT_FALSE (f.contains (0.0, 0.6));
  EXPECT_TRUE (f.contains (0.0, -0.4));
}

TEST (PatchCode, HeightBoundHoldsOverAFootprintReachingBeyondTheSquare)
{
  // The quadric's monomials exceed 1 where a footprint reaches past the unit square (merged patches): x^2 is
  // 2.56 at x = 1.6, so the sum of the coefficients' magnitudes is no bound there.
  const SurfaceBasis::ConstPtr basis = makeCosineBasis (CosineBasisKind::DctQuadric, 12);
  const int x2 = 144 + 2, xy = 144 + 3, y2 = 144 + 4;
  EXPECT_DOUBLE_EQ (basis->atomBound (x2, 1.6), 1.6 * 1.6);
  EXPECT_DOUBLE_EQ (basis->atomBound (144, 1.6), 1.6);  // x
  EXPECT_DOUBLE_EQ (basis->atomBound (5, 1.6), 1.0);    // a cosine
  PatchCode code;
  code.atoms = {0, x2, xy, y2, 13};
  code.coefficients = {0.1, 0.8, -0.3, 0.5, 0.2};
  code.footprint.extent.assign (16, 1.6f);
  const double bound = code.heightBound (*basis);
  double largest = 0.0, sum = 0.0;
  for (double c : code.coefficients)
    sum += std::abs (c);
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j)
    {
      const double x = 1.6 * i / 40.0, y = 1.6 * j / 40.0;
      if (code.footprint.contains (x, y))
        largest = std::max (largest, std::abs (basis->evaluateCodeValue (code.atoms, code.coefficients, x, y)));
    }
  EXPECT_GT (largest, sum);  // the old bound fails here
  EXPECT_LE (largest, bound);
  EXPECT_LE (bound, 2.5 * largest);  // and not far off

  // Cosines alone, a footprint within the square: the sum of the magnitudes.
  PatchCode cosines;
  cosines.atoms = {0, 13, 27};
  cosines.coefficients = {0.4, -0.25, 0.1};
  cosines.footprint.extent.assign (8, 0.7f);
  EXPECT_DOUBLE_EQ (cosines.heightBound (*basis), 0.75);
}
