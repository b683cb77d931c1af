/// Rate against distortion (issue 13): SparseSurfaceEncoderOptions::atom_loss_allowance leaves out the atoms
/// that buy least (allocateAtomsWithinLoss over patchAtomGains) while the model's squared error grows by at
/// most the allowance.

#include <pcl_sparse/coding/atom_budget.h>
#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/patch_coder.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/patch_ownership.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "knife_mesh.h"
#include "model_helpers.h"

using namespace pcl_sparse;

namespace
{
  SparseSurfaceModel
  encode (const TriangleMesh::ConstPtr& mesh, double allowance, int threads = 1)
  {
    SparseSurfaceEncoderOptions options;
    options.atom_loss_allowance = allowance;
    return *pcl_sparse_test::encodeMesh (mesh, options, threads);
  }

  double
  meanSquaredError (const SparseSurfaceModel& model, const TriangleMesh& mesh)
  {
    const double rmse = model.statistics (mesh.vertices).rmse;
    return rmse * rmse;
  }
} // namespace

TEST (AtomLoss, StopsOnceWhatIsLeftOutIsWithinTheAllowance)
{
  // Gains 5, 1, 0.5 and 3, 2 (11.5 in all), given in the order 5, 3, 2, 1, 0.5.
  const AtomGains gains = {{5.0, 1.0, 0.5}, {3.0, 2.0}};
  EXPECT_EQ (allocateAtomsWithinLoss (gains, 1.6), (std::vector<int>{1, 2}));  // 1.5 left out
  EXPECT_EQ (allocateAtomsWithinLoss (gains, 1.4), (std::vector<int>{2, 2}));  // 0.5 left out
  EXPECT_EQ (allocateAtomsWithinLoss (gains, 0.0), (std::vector<int>{3, 2}));  // every code whole
  EXPECT_EQ (allocateAtomsWithinLoss (gains, 11.5), (std::vector<int>{0, 0}));
  // Atoms that gain nothing are left out even without an allowance.
  EXPECT_EQ (allocateAtomsWithinLoss ({{1.0, 0.0}}, 0.0), (std::vector<int>{1}));
}

TEST (AtomLoss, ShortestPrefixWithinBoundsTheHeightsChange)
{
  // Coefficients 1, 0.5, 0.02; OMP's prefixes (0.9), (1, 0.48), then the code. Cut to k atoms the heights
  // move by at most 1.52, 0.62, 0.04 and 0 for k = 0, 1, 2, 3 (these cosines are bounded by 1).
  PatchCode code;
  code.atoms = {0, 3, 7};
  code.coefficients = {1.0, 0.5, 0.02};
  PatchCodingInfo info;
  info.prefix_coefficients = {0.9, 1.0, 0.48, 1.0, 0.5, 0.02};
  const SurfaceBasis::ConstPtr basis = makeCosineBasis (CosineBasisKind::DctQuadric, 12);
  EXPECT_EQ (shortestPrefixWithin (code, *basis, info, 2.0), 0);
  EXPECT_EQ (shortestPrefixWithin (code, *basis, info, 1.0), 1);
  EXPECT_EQ (shortestPrefixWithin (code, *basis, info, 0.05), 2);
  EXPECT_EQ (shortestPrefixWithin (code, *basis, info, 0.01), 3);
  EXPECT_EQ (shortestPrefixWithin (code, *basis, PatchCodingInfo (), 2.0), 3);  // no prefixes: the whole code

  // The second atom x^2 (the quadric's) on a footprint reaching 1.5: it moves heights by up to 2.25 times its
  // coefficient's change, so cut to two atoms they move by up to 0.02 x 2.25 + 0.02 = 0.065, not 0.04.
  code.atoms = {0, 144 + 2, 7};
  code.footprint.extent.assign (8, 1.5f);
  EXPECT_EQ (shortestPrefixWithin (code, *basis, info, 0.05), 3);
  code.footprint.extent.assign (8, 1.0f);
  EXPECT_EQ (shortestPrefixWithin (code, *basis, info, 0.05), 2);
}

TEST (AtomLoss, FewerAtomsForAtMostTheAllowedError)
{
  // A torus is curved everywhere and no quadric: OMP takes its L atoms on every patch, the last ones fitting
  // little. The allowance is measured on the patches' samples; the vertices' squared error follows it.
  const auto torus = std::make_shared<TriangleMesh> (makeTorus (96, 32));
  const SparseSurfaceModel whole = encode (torus, 0.0);
  const SparseSurfaceModel cut = encode (torus, 0.2);
  ASSERT_EQ (cut.numPatches (), whole.numPatches ());
  const double whole_error = meanSquaredError (whole, *torus), cut_error = meanSquaredError (cut, *torus);
  std::cout << "atoms " << whole.numNonZeros () << " -> " << cut.numNonZeros () << ", mean squared error x "
            << cut_error / whole_error << std::endl;
  EXPECT_LT (cut.numNonZeros (), 0.9 * whole.numNonZeros ());
  EXPECT_LE (cut_error, 1.25 * whole_error);
  EXPECT_GT (cut_error, whole_error);
  // Each code is a prefix of its whole code: what OMP with fewer atoms gives.
  for (std::size_t p = 0; p < cut.numPatches (); ++p)
  {
    const std::vector<int>& a = cut.patches[p].atoms;
    const std::vector<int>& b = whole.patches[p].atoms;
    ASSERT_LE (a.size (), b.size ());
    EXPECT_TRUE (std::equal (a.begin (), a.end (), b.begin ())) << "patch " << p;
  }
  // The same model for any number of threads.
  const SparseSurfaceModel threaded = encode (torus, 0.2, 4);
  ASSERT_EQ (threaded.numPatches (), cut.numPatches ());
  for (std::size_t p = 0; p < cut.numPatches (); ++p)
  {
    EXPECT_EQ (threaded.patches[p].atoms, cut.patches[p].atoms);
    EXPECT_EQ (threaded.patches[p].coefficients, cut.patches[p].coefficients);
  }
}

TEST (AtomLoss, PatchesFacingAcrossAKnifeEdgeMoveWithinAThirdOfTheClearance)
{
  // Resampling clears a patch's places within opposite_clearance (0.03 of the radius) of a facing-away
  // patch's surface; a code moved further crosses it (the 10-degree knife flipped 1-2 points with every
  // patch's atoms left out as the allowance alone decides). Those patches keep the atoms that hold their
  // heights within a third of it, the others lose what the allowance gives.
  const auto knife = std::make_shared<TriangleMesh> (pcl_sparse_test::makeKnife (48, 10.0));
  const SparseSurfaceModel whole = encode (knife, 0.0);
  const SparseSurfaceModel cut = encode (knife, 0.2);
  ASSERT_EQ (cut.numPatches (), whole.numPatches ());
  const PatchEvaluator evaluator (whole);
  const PatchOwnership ownership (evaluator);
  const double bound = PatchOwnershipOptions ().opposite_clearance / 3.0;
  std::size_t facing = 0, facing_shortened = 0, other_shortened = 0;
  for (std::size_t p = 0; p < whole.numPatches (); ++p)
  {
    const PatchCode& a = whole.patches[p];
    const PatchCode& b = cut.patches[p];
    ASSERT_LE (b.atoms.size (), a.atoms.size ());
    const bool shortened = b.atoms.size () < a.atoms.size ();
    if (ownership.oppositeDisks (p).empty ())
    {
      other_shortened += shortened;
      continue;
    }
    ++facing;
    facing_shortened += shortened;
    double change = 0.0;  // bounds the heights' change, the atoms being bounded by 1
    for (std::size_t i = 0; i < a.atoms.size (); ++i)
      change += std::abs (a.coefficients[i] - (i < b.atoms.size () ? b.coefficients[i] : 0.0));
    EXPECT_LE (change, bound) << "patch " << p;
  }
  std::cout << whole.numPatches () << " patches, " << facing << " facing across the edge (" << facing_shortened
            << " shortened), " << other_shortened << " of the others shortened" << std::endl;
  EXPECT_GT (facing, 0u);
  EXPECT_GT (facing_shortened, 0u);
  EXPECT_GT (other_shortened, 0u);
}

TEST (AtomLoss, ScansAndThePaperPresetKeepEveryCode)
{
  EXPECT_EQ (SparseSurfaceEncoderOptions ().atom_loss_allowance, 0.0);
  EXPECT_EQ (encoderPresetOptions (EncoderPreset::Paper).atom_loss_allowance, 0.0);
  // A noisy plane as a scan: its codes stop at its noise floor, and no atom is left out for the allowance.
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  std::mt19937 random (3);
  std::uniform_real_distribution<float> u (-1.0f, 1.0f);
  std::normal_distribution<float> noise (0.0f, 0.003f);
  for (int i = 0; i < 6000; ++i)
  {
    const float x = u (random), y = u (random);
    cloud->push_back (pcl::PointXYZ (x, y, 2.0f + 0.2f * x * x + 0.1f * std::sin (3.0f * y) + noise (random)));
  }
  auto encodeScan = [&] (double allowance) {
    SparseSurfaceEncoderOptions options;
    options.atom_loss_allowance = allowance;
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputCloud (cloud);
    encoder.setOptions (options);
    SparseSurfaceModel model;
    encoder.compute (model);
    return model;
  };
  const SparseSurfaceModel with = encodeScan (0.2), without = encodeScan (0.0);
  ASSERT_EQ (with.numPatches (), without.numPatches ());
  ASSERT_GT (with.numNonZeros (), 0u);
  for (std::size_t p = 0; p < with.numPatches (); ++p)
    EXPECT_EQ (with.patches[p].atoms, without.patches[p].atoms) << "patch " << p;
}

TEST (AtomLoss, NegativeOrNonFiniteAllowanceIsRefused)
{
  SparseSurfaceEncoderOptions options;
  options.atom_loss_allowance = -0.1;
  EXPECT_THROW (options.validate (), Error);
  options.atom_loss_allowance = std::numeric_limits<double>::infinity ();
  EXPECT_THROW (options.validate (), Error);
  options.atom_loss_allowance = 0.0;
  EXPECT_NO_THROW (options.validate ());
}
