#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/nyquist_cap.h>
#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

using namespace pcl_sparse;

namespace
{
  Eigen::MatrixXd
  randomMatrix (int rows, int cols, std::mt19937& rng)
  {
    std::normal_distribution<double> n (0.0, 1.0);
    Eigen::MatrixXd m (rows, cols);
    for (int c = 0; c < cols; ++c)
      for (int r = 0; r < rows; ++r)
        m (r, c) = n (rng) * (1.0 + c % 3);  // unequal column norms: selection must normalise
    return m;
  }

  /// \a count points uniform in [-scale, scale]^2 (into \a points) and \a basis's atoms at them.
  Eigen::MatrixXd
  atomsAtRandomPoints (const SurfaceBasis& basis, int count, double scale, std::mt19937& rng,
                       std::vector<Eigen::Vector2d>& points)
  {
    std::uniform_real_distribution<double> u (-1.0, 1.0);
    points.clear ();
    for (int p = 0; p < count; ++p)
      points.emplace_back (scale * u (rng), scale * u (rng));
    Eigen::MatrixXd D;
    basis.evaluate (points, D);
    return D;
  }
} // namespace

// Every step's coefficients equal the brute-force least squares on the selected support, and each
// selected atom is the best normalised correlation with the residual of the previous support.
TEST (OrthogonalMatchingPursuit, MatchesBruteForceGreedyLeastSquares)
{
  std::mt19937 rng (1);
  for (int trial = 0; trial < 20; ++trial)
  {
    const Eigen::MatrixXd D = randomMatrix (30, 12, rng);
    const Eigen::VectorXd y = randomMatrix (30, 1, rng).col (0);
    const OmpResult result = orthogonalMatchingPursuit (y, D, {}, 1e-9, 6);
    ASSERT_EQ (result.atoms.size (), 6u);

    std::vector<int> support;
    Eigen::VectorXd residual = y;
    for (int step = 0; step < 6; ++step)
    {
      int best = -1;
      double best_score = -1.0;
      for (int k = 0; k < 12; ++k)
      {
        if (std::find (support.begin (), support.end (), k) != support.end ())
          continue;
        const double score = std::abs (D.col (k).dot (residual)) / D.col (k).norm ();
        if (score > best_score)
        {
          best_score = score;
          best = k;
        }
      }
      EXPECT_EQ (result.atoms[step], best);
      support.push_back (best);
      Eigen::MatrixXd Ds (30, support.size ());
      for (std::size_t s = 0; s < support.size (); ++s)
        Ds.col (s) = D.col (support[s]);
      const Eigen::VectorXd a = Ds.colPivHouseholderQr ().solve (y);
      residual = y - Ds * a;
      if (step == 5)
      {
        for (int s = 0; s < 6; ++s)
          EXPECT_NEAR (result.coefficients[s], a[s], 1e-9);
        EXPECT_NEAR (result.residual_norm, residual.norm (), 1e-9);
      }
    }
  }
}

// With orthogonal scores each step takes the atom whose addition leaves the smallest least-squares
// residual (brute force over every candidate), which plain OMP does not always do on these dictionaries.
TEST (OrthogonalMatchingPursuit, OrthogonalScoresTakeTheLargestReduction)
{
  std::mt19937 rng (5);
  OmpSelection orthogonal;
  orthogonal.orthogonal_scores = true;
  int differs = 0;
  for (int trial = 0; trial < 20; ++trial)
  {
    // Correlated columns (a shared part), where the two rules part.
    Eigen::MatrixXd D = randomMatrix (30, 12, rng);
    D.rightCols (6) += 2.0 * D.leftCols (6);
    const Eigen::VectorXd y = randomMatrix (30, 1, rng).col (0);
    const OmpResult result = orthogonalMatchingPursuit (y, D, {}, 1e-9, 6, orthogonal);
    ASSERT_EQ (result.atoms.size (), 6u);
    differs += result.atoms != orthogonalMatchingPursuit (y, D, {}, 1e-9, 6).atoms;
    std::vector<int> support;
    for (int step = 0; step < 6; ++step)
    {
      int best = -1;
      double least = std::numeric_limits<double>::infinity ();
      for (int k = 0; k < 12; ++k)
      {
        if (std::find (support.begin (), support.end (), k) != support.end ())
          continue;
        Eigen::MatrixXd Ds (30, static_cast<Eigen::Index> (support.size () + 1));
        for (std::size_t s = 0; s < support.size (); ++s)
          Ds.col (static_cast<Eigen::Index> (s)) = D.col (support[s]);
        Ds.col (static_cast<Eigen::Index> (support.size ())) = D.col (k);
        const double r = (y - Ds * Ds.colPivHouseholderQr ().solve (y)).norm ();
        if (r < least)
        {
          least = r;
          best = k;
        }
      }
      ASSERT_EQ (result.atoms[step], best) << "trial " << trial << ", step " << step;
      EXPECT_NEAR (result.residual_norms[step + 1], least, 1e-9);
      support.push_back (best);
    }
    // The coefficients are the least-squares fit on the support (the factor's rows come from the scores' rows).
    Eigen::MatrixXd Ds (30, 6);
    for (int s = 0; s < 6; ++s)
      Ds.col (s) = D.col (support[s]);
    const Eigen::VectorXd fit = Ds.colPivHouseholderQr ().solve (y);
    for (int s = 0; s < 6; ++s)
      EXPECT_NEAR (result.coefficients[s], fit[s], 1e-9 * (1.0 + std::abs (fit[s]))) << "trial " << trial;
  }
  EXPECT_GT (differs, 0);
}

TEST (OrthogonalMatchingPursuit, StopsAtTolerance)
{
  std::mt19937 rng (3);
  const Eigen::MatrixXd D = randomMatrix (40, 20, rng);
  const Eigen::VectorXd y = randomMatrix (40, 1, rng).col (0);
  const OmpResult loose = orthogonalMatchingPursuit (y, D, {}, 0.9, 20);
  EXPECT_LE (loose.residual_norm, 0.9 * y.norm ());
  ASSERT_GE (loose.atoms.size (), 2u);
  EXPECT_LT (loose.atoms.size (), 20u);
  // It stopped at the first support meeting the tolerance: one atom fewer does not.
  const int fewer = static_cast<int> (loose.atoms.size ()) - 1;
  EXPECT_GT (orthogonalMatchingPursuit (y, D, {}, 0.9, fewer).residual_norm, 0.9 * y.norm ());
  const OmpResult none = orthogonalMatchingPursuit (Eigen::VectorXd::Zero (40), D, {}, 0.01, 5);
  EXPECT_TRUE (none.atoms.empty ());
  EXPECT_TRUE (none.coefficients.empty ());
}

// A signal made of a few atoms at random points is recovered exactly (atoms and coefficients).
TEST (OrthogonalMatchingPursuit, RecoversSyntheticSparseCosineSignals)
{
  const CosineDictionary dictionary (12);
  std::mt19937 rng (11);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  std::uniform_int_distribution<int> atom (0, 143);
  int recovered = 0;
  for (int trial = 0; trial < 30; ++trial)
  {
    std::vector<Eigen::Vector2d> points;
    const Eigen::MatrixXd D = atomsAtRandomPoints (dictionary, 400, 1.0, rng, points);
    std::vector<int> truth;
    while (truth.size () < 4)
    {
      const int a = atom (rng);
      if (std::find (truth.begin (), truth.end (), a) == truth.end ())
        truth.push_back (a);
    }
    std::vector<double> coefficients;
    Eigen::VectorXd y = Eigen::VectorXd::Zero (400);
    for (int a : truth)
    {
      const double c = (u (rng) > 0 ? 1.0 : -1.0) * (0.5 + 0.5 * std::abs (u (rng)));
      coefficients.push_back (c);
      y += c * D.col (a);
    }
    const OmpResult result = orthogonalMatchingPursuit (y, D, {}, 1e-8, 12);
    std::vector<int> got = result.atoms, want = truth;
    std::sort (got.begin (), got.end ());
    std::sort (want.begin (), want.end ());
    if (got == want)
    {
      ++recovered;
      for (std::size_t k = 0; k < result.atoms.size (); ++k)
      {
        const std::size_t t = std::find (truth.begin (), truth.end (), result.atoms[k]) - truth.begin ();
        EXPECT_NEAR (result.coefficients[k], coefficients[t], 1e-8);
      }
    }
    EXPECT_LE (result.residual_norm, 1e-8 * y.norm ());
  }
  // 400 random points, 144 nearly orthogonal atoms: greedy recovery of 4 atoms should always work.
  EXPECT_EQ (recovered, 30);
}

TEST (OrthogonalMatchingPursuit, NeverSelectsForbiddenAtoms)
{
  const CosineDictionary dictionary (12);
  std::mt19937 rng (5);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<Eigen::Vector2d> points;
    const Eigen::MatrixXd D = atomsAtRandomPoints (dictionary, 64, 1.0, rng, points);
    // High-frequency signal that the forbidden atoms would fit best.
    Eigen::VectorXd y (64);
    for (int p = 0; p < 64; ++p)
      y[p] = std::cos (10 * M_PI * points[p].x ()) + 0.3 * std::cos (9 * M_PI * points[p].y ()) + 0.1 * u (rng);
    const double spacing = 0.1 + 0.05 * trial;
    const std::vector<char> allowed = nyquistAllowedAtoms (dictionary, spacing, 0.5, NyquistRule::Paper);
    const OmpResult result = orthogonalMatchingPursuit (y, D, allowed, 0.01, 12);
    EXPECT_FALSE (result.atoms.empty ());
    for (int a : result.atoms)
    {
      EXPECT_TRUE (allowed[a]) << "atom " << a;
      EXPECT_GT (dictionary.wavelength (a) / 2.0, 0.5 * spacing);
    }
    // Nothing allowed: nothing selected.
    const OmpResult empty = orthogonalMatchingPursuit (y, D, std::vector<char> (144, 0), 0.01, 12);
    EXPECT_TRUE (empty.atoms.empty ());
  }
}

// Preferred atoms (allowed flag 2): with preference 1 a step still takes the best atom (the same code as
// without flags); with 0 the preferred ones come first while they correlate; in between, a preferred atom
// wins when it scores at least that fraction of the best. Forbidden atoms stay forbidden.
TEST (OrthogonalMatchingPursuit, PreferredAtomsFirst)
{
  std::mt19937 rng (11);
  const Eigen::MatrixXd D = randomMatrix (40, 30, rng);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  Eigen::VectorXd y (40);
  for (int p = 0; p < 40; ++p)
    y[p] = u (rng);
  std::vector<char> flags (30, 1);
  for (int k : {3, 7, 21})
    flags[k] = 2;
  flags[5] = 0;
  std::vector<char> without_5 (30, 1);  // what preference 1 must reproduce: the same atoms allowed, none preferred
  without_5[5] = 0;
  const OmpResult plain = orthogonalMatchingPursuit (y, D, without_5, 1e-9, 10);
  const OmpResult unpreferred = orthogonalMatchingPursuit (y, D, flags, 1e-9, 10, OmpSelection{1.0});
  const OmpResult first = orthogonalMatchingPursuit (y, D, flags, 1e-9, 10, OmpSelection{0.0});
  ASSERT_EQ (first.atoms.size (), 10u);
  std::vector<int> head (first.atoms.begin (), first.atoms.begin () + 3);
  std::sort (head.begin (), head.end ());
  EXPECT_EQ (head, (std::vector<int>{3, 7, 21}));
  for (int a : first.atoms)
    EXPECT_NE (a, 5);
  ASSERT_EQ (plain.atoms.size (), 10u);
  EXPECT_EQ (unpreferred.atoms, plain.atoms);
  EXPECT_EQ (unpreferred.coefficients, plain.coefficients);
  EXPECT_NE (first.atoms, plain.atoms);  // preference 0 did change the order
  // Each preferred step of a preference-0.5 run had a score of at least half the best one's: recompute it.
  const OmpResult half = orthogonalMatchingPursuit (y, D, flags, 1e-9, 10, OmpSelection{0.5});
  const Eigen::VectorXd norms = D.colwise ().squaredNorm ().transpose ();
  for (std::size_t step = 0; step < half.atoms.size (); ++step)
  {
    Eigen::VectorXd residual = y;
    if (step > 0)
    {
      Eigen::MatrixXd support (40, static_cast<Eigen::Index> (step));
      for (std::size_t k = 0; k < step; ++k)
        support.col (static_cast<Eigen::Index> (k)) = D.col (half.atoms[k]);
      residual = y - support * support.colPivHouseholderQr ().solve (y);
    }
    const Eigen::VectorXd scores = (D.transpose () * residual).array ().square () / norms.array ();
    double best = 0.0;
    for (int k = 0; k < 30; ++k)
      if (flags[k] && std::find (half.atoms.begin (), half.atoms.begin () + step, k) == half.atoms.begin () + step)
        best = std::max (best, scores[k]);
    const int chosen = half.atoms[step];
    if (flags[chosen] == 2)
      EXPECT_GE (scores[chosen], 0.5 * best * (1.0 - 1e-9)) << "step " << step;
    else
      EXPECT_NEAR (scores[chosen], best, 1e-9 * best) << "step " << step;
  }
}

// The conditioning floors (OmpSelection): samples along a line y = 1e-4 x, where the atom y is nearly zero.
// Plain OMP picks it and codes a slope across the line with a coefficient in the thousands; with the RMS floor
// it is never a candidate. Atoms nearly in the span of the support (1 and 1 + 1e-3 y) are skipped under
// min_new_fraction.
TEST (OrthogonalMatchingPursuit, ConditioningFloors)
{
  const int m = 50;
  Eigen::MatrixXd D (m, 3);
  Eigen::VectorXd y (m);
  for (int p = 0; p < m; ++p)
  {
    const double x = -1.0 + 2.0 * p / (m - 1.0), line_y = 1e-4 * x + 1e-5 * std::sin (7.0 * p);
    D (p, 0) = 1.0;
    D (p, 1) = line_y;              // the monomial y
    D (p, 2) = 1.0 + 1e-3 * line_y;  // nearly the constant
    y[p] = 0.3 * line_y * 1e4 + 0.1;  // a height that varies along the line, not across it
  }
  const OmpResult plain = orthogonalMatchingPursuit (y, D, {}, 1e-9, 3);
  ASSERT_FALSE (plain.atoms.empty ());
  double largest = 0.0;
  for (double c : plain.coefficients)
    largest = std::max (largest, std::abs (c));
  EXPECT_GT (largest, 1000.0);  // what the floors prevent
  OmpSelection floors;
  floors.min_column_rms = 0.01;
  floors.min_new_fraction = 1e-4;
  const OmpResult floored = orthogonalMatchingPursuit (y, D, {}, 1e-9, 3, floors);
  // One of the two near-constants (the other adds 1e-7 of its norm outside its span: skipped), never y.
  ASSERT_EQ (floored.atoms.size (), 1u);
  EXPECT_NE (floored.atoms[0], 1);
  EXPECT_LT (std::abs (floored.coefficients[0]), 1.0);
}

// More atoms than points / dependent atoms: the factor stays valid, the fit is exact at the points.
TEST (OrthogonalMatchingPursuit, HandlesDependentColumns)
{
  std::mt19937 rng (9);
  Eigen::MatrixXd D = randomMatrix (5, 8, rng);
  D.col (3) = 2.0 * D.col (1);  // exactly dependent
  const Eigen::VectorXd y = randomMatrix (5, 1, rng).col (0);
  const OmpResult result = orthogonalMatchingPursuit (y, D, {}, 1e-12, 12);
  EXPECT_LE (result.atoms.size (), 5u);
  EXPECT_LT (result.residual_norm, 1e-8 * y.norm ());
  const bool both = std::find (result.atoms.begin (), result.atoms.end (), 1) != result.atoms.end () &&
                    std::find (result.atoms.begin (), result.atoms.end (), 3) != result.atoms.end ();
  EXPECT_FALSE (both);
}

// Batch OMP codes each signal as orthogonalMatchingPursuit does (the same atoms, coefficients and residuals
// up to round-off), with per-signal tolerances, a zero signal and dependent columns among them.
TEST (BatchOrthogonalMatchingPursuit, EachSignalAsOrthogonalMatchingPursuit)
{
  std::mt19937 rng (11);
  for (int trial = 0; trial < 20; ++trial)
  {
    const int rows = 30 + 10 * (trial % 5), cols = 40 + 7 * (trial % 4);
    Eigen::MatrixXd D = randomMatrix (rows, cols, rng);
    D.col (5) = D.col (2) - 2.0 * D.col (3);  // in the span of two others (a scaled copy would tie exactly)
    // Signals: sparse combinations plus noise, so that some reach their tolerance and some use L atoms.
    Eigen::MatrixXd Y = 0.05 * randomMatrix (rows, 4, rng);
    for (int c = 0; c < 3; ++c)
      for (int k : {1, 2, 7 + c, 20 + 3 * c})
        Y.col (c) += (1.0 + k % 4) * D.col (k);
    Y.col (3).setZero ();
    const std::vector<double> tolerances = {1e-3, 0.05, 0.2, 0.01};
    const int max_atoms = 6 + trial % 7;
    const std::vector<OmpResult> batch = batchOrthogonalMatchingPursuit (Y, D, tolerances, max_atoms);
    ASSERT_EQ (batch.size (), 4u);
    for (int c = 0; c < 4; ++c)
    {
      const OmpResult single = orthogonalMatchingPursuit (Y.col (c), D, {}, tolerances[c], max_atoms);
      ASSERT_EQ (batch[c].atoms, single.atoms) << "trial " << trial << ", signal " << c;
      ASSERT_EQ (batch[c].coefficients.size (), single.coefficients.size ());
      for (std::size_t k = 0; k < single.coefficients.size (); ++k)
        EXPECT_NEAR (batch[c].coefficients[k], single.coefficients[k], 1e-9 * (1.0 + std::abs (single.coefficients[k])));
      EXPECT_NEAR (batch[c].residual_norm, single.residual_norm, 1e-9 * (1.0 + Y.col (c).norm ()));
      EXPECT_EQ (batch[c].residual_norms.size (), single.residual_norms.size ());
    }
    EXPECT_TRUE (batch[3].atoms.empty ());
    EXPECT_EQ (batch[3].residual_norm, 0.0);
    EXPECT_GT (batch[2].residual_norm, 0.0);
  }
  EXPECT_THROW (batchOrthogonalMatchingPursuit (Eigen::MatrixXd::Ones (3, 2), Eigen::MatrixXd::Ones (3, 2), {0.1}, 4),
                std::exception);
}

// Fewer samples than atoms (a small patch): many cosines are nearly dependent at a few points, so atoms are
// skipped after their Gram column was formed; the Gram store must hold more columns than signals x L
// (it overflowed its heap block on such patches of a real scan, found by bench/scans.sh).
TEST (BatchOrthogonalMatchingPursuit, FewerSamplesThanAtoms)
{
  const CosineDictionary dictionary (12);
  std::mt19937 rng (5);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    // Clustered: the cosines are nearly dependent there.
    std::vector<Eigen::Vector2d> points;
    const Eigen::MatrixXd D = atomsAtRandomPoints (dictionary, 3 + trial % 6, 0.05, rng, points);
    Eigen::MatrixXd Y (static_cast<Eigen::Index> (points.size ()), 3);
    for (Eigen::Index r = 0; r < Y.rows (); ++r)
      for (Eigen::Index c = 0; c < 3; ++c)
        Y (r, c) = u (rng);
    const std::vector<OmpResult> batch = batchOrthogonalMatchingPursuit (Y, D, {1e-14, 1e-14, 1e-14}, 12);
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_LE (batch[c].atoms.size (), points.size ());
      ASSERT_EQ (batch[c].coefficients.size (), batch[c].atoms.size ());
      EXPECT_LE (batch[c].residual_norm, Y.col (c).norm () * (1.0 + 1e-12));
      // A few points and 144 cosines: some atom fits, and the fit is no worse than its best single atom's.
      ASSERT_FALSE (batch[c].atoms.empty ());
      double best_single = Y.col (c).norm ();
      for (Eigen::Index a = 0; a < D.cols (); ++a)
        if (D.col (a).squaredNorm () > 1e-12)
          best_single = std::min (best_single, (Y.col (c) - D.col (a) * (D.col (a).dot (Y.col (c)) / D.col (a).squaredNorm ())).norm ());
      EXPECT_LE (batch[c].residual_norm, best_single * (1.0 + 1e-9) + 1e-12) << "trial " << trial;
      for (double a : batch[c].coefficients)
        ASSERT_TRUE (std::isfinite (a));
    }
  }
}
