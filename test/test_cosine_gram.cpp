#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/cosine_gram.h>
#include <pcl_sparse/coding/dct_cosine_dictionary.h>
#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pcl_sparse;

namespace
{
  std::vector<Eigen::Vector2d>
  randomPoints (int count, std::mt19937& rng)
  {
    std::uniform_real_distribution<double> u (-1.0, 1.0);
    std::vector<Eigen::Vector2d> points;
    for (int p = 0; p < count; ++p)
      points.emplace_back (u (rng), u (rng));
    return points;
  }

  /// Atoms (i, j) with max(i, j) <= m (a Nyquist cap), every third one skipped when \a sparse.
  std::vector<int>
  cappedAtoms (const CosineAtoms& basis, int m, bool sparse)
  {
    std::vector<int> atoms;
    for (int i = 0; i <= m; ++i)
      for (int j = 0; j <= m; ++j)
        if (!sparse || (i + 2 * j) % 3 != 0)
          atoms.push_back (basis.atomIndex (i, j));
    return atoms;
  }
} // namespace

// Every column equals D^T d_k formed from the evaluated atoms, for both cosine kinds and the quadric basis's
// cosines, whole and capped atom lists, unordered lists and more atoms than points.
TEST (CosineGram, ColumnsEqualTheDictionaryProducts)
{
  std::mt19937 rng (3);
  const CosineDictionary paper (12);
  const DctCosineDictionary dct (12);
  const CosineAtoms::ConstPtr quadric = makeCosineBasis (CosineBasisKind::DctQuadric, 12);
  for (const CosineAtoms* basis : {static_cast<const CosineAtoms*> (&paper), static_cast<const CosineAtoms*> (&dct),
                                   quadric.get ()})
    for (int trial = 0; trial < 6; ++trial)
    {
      const std::vector<Eigen::Vector2d> points = randomPoints (trial == 5 ? 20 : 60 + 40 * trial, rng);
      std::vector<int> atoms = trial < 2 ? cappedAtoms (*basis, 11, false) : cappedAtoms (*basis, 3 + trial, trial % 2 == 1);
      if (trial == 4)
        std::shuffle (atoms.begin (), atoms.end (), rng);
      Eigen::MatrixXd D;
      basis->evaluate (points, atoms, D);
      const Eigen::MatrixXd expected = D.transpose () * D;
      const CosineGram gram (*basis, points, atoms);
      ASSERT_EQ (gram.size (), static_cast<int> (atoms.size ()));
      Eigen::VectorXd column (static_cast<Eigen::Index> (atoms.size ()));
      double worst = 0.0;
      for (int k = 0; k < gram.size (); ++k)
      {
        gram.column (k, column);
        worst = std::max (worst, (column - expected.col (k)).cwiseAbs ().maxCoeff ());
      }
      // Round-off of sums of #P terms of size at most 1.
      EXPECT_LT (worst, 1e-12 * static_cast<double> (points.size ())) << "kind " << static_cast<int> (basis->kind ())
                                                                        << ", trial " << trial;
    }
  // The quadric basis's monomials are no cosines.
  EXPECT_THROW (CosineGram (*quadric, randomPoints (10, rng), {0, 144}), std::exception);
  EXPECT_THROW (CosineGram (dct, randomPoints (10, rng), {-1}), std::exception);
}

// Batch OMP with the Gram columns from CosineGram chooses the atoms and coefficients it chooses with D^T d_j
// (a colour patch's three channels: smooth values and noise, most atoms allowed).
TEST (CosineGram, BatchOmpChoosesTheSameCodes)
{
  std::mt19937 rng (17);
  std::normal_distribution<double> noise (0.0, 0.02);
  const DctCosineDictionary dct (12);
  for (int trial = 0; trial < 10; ++trial)
  {
    const std::vector<Eigen::Vector2d> points = randomPoints (40 + 30 * trial, rng);
    const std::vector<int> atoms = cappedAtoms (dct, 6 + trial / 2, false);
    Eigen::MatrixXd D;
    dct.evaluate (points, atoms, D);
    Eigen::MatrixXd Y (D.rows (), 3);
    for (Eigen::Index p = 0; p < D.rows (); ++p)
    {
      const double x = points[p].x (), y = points[p].y ();
      Y (p, 0) = 0.5 + 0.3 * std::sin (2.0 * x + y) + noise (rng);
      Y (p, 1) = 0.4 + 0.2 * x * y + noise (rng);
      Y (p, 2) = 0.6 - 0.3 * std::exp (-4.0 * (x * x + y * y)) + noise (rng);
    }
    const std::vector<double> tolerances = {0.01, 0.03, 0.003};
    const CosineGram gram (dct, points, atoms);
    const GramColumnFunction from_sums = [&gram] (int j, Eigen::Ref<Eigen::VectorXd> column) { gram.column (j, column); };
    const std::vector<OmpResult> direct = batchOrthogonalMatchingPursuit (Y, D, tolerances, 12);
    const std::vector<OmpResult> summed = batchOrthogonalMatchingPursuit (Y, D, tolerances, 12, from_sums);
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_FALSE (direct[c].atoms.empty ());
      ASSERT_EQ (summed[c].atoms, direct[c].atoms) << "trial " << trial << ", channel " << c;
      for (std::size_t k = 0; k < direct[c].coefficients.size (); ++k)
        EXPECT_NEAR (summed[c].coefficients[k], direct[c].coefficients[k], 1e-9 * (1.0 + std::abs (direct[c].coefficients[k])));
      EXPECT_NEAR (summed[c].residual_norm, direct[c].residual_norm, 1e-9);
    }
  }
}
