#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/model/sparse_surface_model.h>

#include <gtest/gtest.h>

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
