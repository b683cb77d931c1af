#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/dct_cosine_dictionary.h>
#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>
#include <pcl_sparse/coding/nyquist_cap.h>
#include <pcl_sparse/common/error.h>

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <iostream>
#include <functional>
#include <random>

using namespace pcl_sparse;

namespace
{
  /// Ten random atoms of 144 and coefficients in [-1, 1].
  void
  randomCode (std::mt19937& rng, std::vector<int>& atoms, std::vector<double>& coefficients)
  {
    std::uniform_real_distribution<double> u (-1.0, 1.0);
    std::uniform_int_distribution<int> atom (0, 143);
    for (int k = 0; k < 10; ++k)
    {
      atoms.push_back (atom (rng));
      coefficients.push_back (u (rng));
    }
  }

  /// A code's gradient and Hessian at (x, y) against central differences of its values and gradients.
  template <typename Dictionary>
  void
  expectDerivativesMatchFiniteDifferences (const Dictionary& dictionary, const std::vector<int>& atoms,
                                           const std::vector<double>& coefficients, double x, double y)
  {
    // Central differences err by about h^2 (11 pi)^2 / 6 = 2e-8 relative to the derivative they estimate
    // (atoms up to frequency 11), rounding by about 1e-11: 1e-6 of the magnitude leaves a margin of 50.
    const double h = 1e-5;
    auto f = [&] (double a, double b) { return dictionary.evaluateCode (atoms, coefficients, a, b); };
    const HeightSample s = f (x, y);
    const double scale = 1.0 + s.gradient.norm ();
    EXPECT_NEAR (s.gradient.x (), (f (x + h, y).value - f (x - h, y).value) / (2 * h), 1e-6 * scale);
    EXPECT_NEAR (s.gradient.y (), (f (x, y + h).value - f (x, y - h).value) / (2 * h), 1e-6 * scale);
    const double hscale = 1.0 + s.hessian.norm ();
    EXPECT_NEAR (s.hessian (0, 0), (f (x + h, y).gradient.x () - f (x - h, y).gradient.x ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (0, 1), (f (x, y + h).gradient.x () - f (x, y - h).gradient.x ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (1, 0), (f (x + h, y).gradient.y () - f (x - h, y).gradient.y ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (1, 1), (f (x, y + h).gradient.y () - f (x, y - h).gradient.y ()) / (2 * h), 1e-6 * hscale);
  }
} // namespace

TEST (CosineDictionary, LayoutAndWavelengths)
{
  const CosineDictionary dictionary;
  EXPECT_EQ (dictionary.size (), 144);
  EXPECT_EQ (dictionary.atomIndex (3, 5), 41);
  EXPECT_EQ (dictionary.frequencyX (41), 3);
  EXPECT_EQ (dictionary.frequencyY (41), 5);
  EXPECT_TRUE (std::isinf (dictionary.wavelength (0)));
  EXPECT_DOUBLE_EQ (dictionary.wavelength (dictionary.atomIndex (0, 4)), 0.5);
  EXPECT_DOUBLE_EQ (dictionary.wavelength (dictionary.atomIndex (11, 2)), 2.0 / 11.0);
  EXPECT_THROW (CosineDictionary (0), Error);
  EXPECT_THROW (CosineDictionary (1000), Error);
}

TEST (CosineDictionary, EvaluateMatchesDirectCosines)
{
  const CosineDictionary dictionary (12);
  std::mt19937 rng (42);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 50; ++k)
    points.emplace_back (u (rng), u (rng));
  Eigen::MatrixXd values;
  dictionary.evaluate (points, values);
  ASSERT_EQ (values.rows (), 50);
  ASSERT_EQ (values.cols (), 144);
  double worst = 0.0;
  for (int p = 0; p < 50; ++p)
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j)
        worst = std::max (worst, std::abs (values (p, i * 12 + j) -
                                           std::cos (i * M_PI * points[p].x ()) * std::cos (j * M_PI * points[p].y ())));
  EXPECT_LT (worst, 1e-12);
}

// The cosine tables come from our own sin/cos of pi x (quadrant reduction + series): check them against
// libm on and beyond the square, at quadrant boundaries too.
TEST (CosineDictionary, SingleAtomsMatchLibmEverywhere)
{
  const CosineDictionary dictionary (12);
  double worst = 0.0;
  for (int s = -4000; s <= 4000; ++s)
  {
    const double x = s / 1000.0 + 1e-7 * (s % 7);
    for (int i = 0; i < 12; ++i)
    {
      const HeightSample h = dictionary.evaluateCode ({dictionary.atomIndex (i, 0)}, {1.0}, x, 0.3);
      const double c = std::cos (i * M_PI * x), sn = std::sin (i * M_PI * x);
      worst = std::max (worst, std::abs (h.value - c));
      worst = std::max (worst, std::abs (h.gradient.x () + i * M_PI * sn) / (1.0 + i * M_PI));
    }
  }
  EXPECT_LT (worst, 1e-12);
}

TEST (CosineDictionary, CodeDerivativesMatchFiniteDifferences)
{
  const CosineDictionary dictionary (12);
  std::mt19937 rng (7);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<int> atoms;
    std::vector<double> coefficients;
    randomCode (rng, atoms, coefficients);
    const double x = 0.9 * u (rng), y = 0.9 * u (rng);
    const HeightSample s = dictionary.evaluateCode (atoms, coefficients, x, y);
    double direct = 0.0;
    for (int k = 0; k < 10; ++k)
      direct += coefficients[k] * std::cos (M_PI * dictionary.frequencyX (atoms[k]) * x) *
                std::cos (M_PI * dictionary.frequencyY (atoms[k]) * y);
    EXPECT_NEAR (s.value, direct, 1e-12);
    EXPECT_NEAR (dictionary.evaluateCodeValue (atoms, coefficients, x, y), direct, 1e-12);

    expectDerivativesMatchFiniteDifferences (dictionary, atoms, coefficients, x, y);
  }
}

TEST (NyquistCap, Conventions)
{
  const CosineDictionary dictionary (12);
  // mu = 0.25, f = 0.5: paper allows 1 / max(i, j) > 0.125, i.e. max(i, j) < 8; authors' code
  // 2 / max(i, j) >= 0.125, i.e. max(i, j) <= 16 (all 144).
  const std::vector<char> paper = nyquistAllowedAtoms (dictionary, 0.25, 0.5, NyquistRule::Paper);
  const std::vector<char> authors = nyquistAllowedAtoms (dictionary, 0.25, 0.5, NyquistRule::AuthorsCode);
  int paper_count = 0, authors_count = 0;
  for (int k = 0; k < 144; ++k)
  {
    paper_count += paper[k];
    authors_count += authors[k];
    EXPECT_EQ (paper[k] != 0, std::max (dictionary.frequencyX (k), dictionary.frequencyY (k)) < 8);
  }
  EXPECT_EQ (paper_count, 64);
  EXPECT_EQ (authors_count, 144);
  const std::vector<char> plain = nyquistAllowedAtoms (dictionary, 10.0, 0.0, NyquistRule::Paper);
  ASSERT_EQ (plain.size (), 144u);
  for (char a : plain)
    EXPECT_TRUE (a);
  // Very coarse sampling: only the constant atom survives.
  const std::vector<char> coarse = nyquistAllowedAtoms (dictionary, 10.0, 0.5, NyquistRule::Paper);
  EXPECT_TRUE (coarse[0]);
  for (int k = 1; k < 144; ++k)
    EXPECT_FALSE (coarse[k]);
}

namespace
{
  /// The DCT-like atom (i, j) by libm.
  double
  dctAtom (int i, int j, double x, double y)
  {
    return std::cos (i * M_PI * (x + 1.0) / 2.0) * std::cos (j * M_PI * (y + 1.0) / 2.0);
  }

  std::vector<Eigen::Vector2d>
  randomPoints (int count, unsigned seed)
  {
    std::mt19937 rng (seed);
    std::uniform_real_distribution<double> u (-1.0, 1.0);
    std::vector<Eigen::Vector2d> points;
    for (int k = 0; k < count; ++k)
      points.emplace_back (u (rng), u (rng));
    return points;
  }
} // namespace

TEST (DctCosineDictionary, LayoutWavelengthsAndFactory)
{
  const DctCosineDictionary dictionary;
  EXPECT_EQ (dictionary.size (), 144);
  EXPECT_EQ (dictionary.kind (), CosineBasisKind::Dct);
  EXPECT_EQ (CosineDictionary ().kind (), CosineBasisKind::Paper);
  EXPECT_EQ (dictionary.atomIndex (3, 5), 41);
  EXPECT_TRUE (std::isinf (dictionary.wavelength (0)));
  // Half-period atoms: cos(m pi (x + 1) / 2) has period 4 / m.
  EXPECT_DOUBLE_EQ (dictionary.wavelength (dictionary.atomIndex (0, 4)), 1.0);
  EXPECT_DOUBLE_EQ (dictionary.wavelength (dictionary.atomIndex (11, 2)), 4.0 / 11.0);
  EXPECT_THROW (DctCosineDictionary (0), Error);
  EXPECT_THROW (DctCosineDictionary (65), Error);
  // Not a CosineDictionary, so paper-only fast paths (dynamic_cast) fall back to the generic calls.
  const SurfaceBasis::ConstPtr dct = makeCosineBasis (CosineBasisKind::Dct, 8);
  EXPECT_EQ (dct->size (), 64);
  EXPECT_EQ (dynamic_cast<const CosineDictionary*> (dct.get ()), nullptr);
  EXPECT_NE (dynamic_cast<const DctCosineDictionary*> (dct.get ()), nullptr);
  EXPECT_NE (dynamic_cast<const CosineDictionary*> (makeCosineBasis (CosineBasisKind::Paper, 8).get ()), nullptr);
  EXPECT_STREQ (cosineBasisKindName (CosineBasisKind::Dct), "dct");
  EXPECT_STREQ (cosineBasisKindName (CosineBasisKind::Paper), "paper");
}

// The cap reads wavelength(): mu = 0.5, f = 0.5, paper rule 4 / (2 m) > 0.25 keeps max(i, j) < 8, the same
// 64 atoms the paper's dictionary keeps at half that spacing.
TEST (DctCosineDictionary, NyquistCapUsesTheLongerWavelengths)
{
  const DctCosineDictionary dictionary (12);
  const std::vector<char> allowed = nyquistAllowedAtoms (dictionary, 0.5, 0.5, NyquistRule::Paper);
  int count = 0;
  for (int k = 0; k < 144; ++k)
  {
    count += allowed[k];
    EXPECT_EQ (allowed[k] != 0, std::max (dictionary.frequencyX (k), dictionary.frequencyY (k)) < 8);
  }
  EXPECT_EQ (count, 64);
  EXPECT_EQ (nyquistAllowedAtoms (CosineDictionary (12), 0.25, 0.5, NyquistRule::Paper), allowed);
}

TEST (DctCosineDictionary, EvaluateMatchesDirectCosines)
{
  const DctCosineDictionary dictionary (12);
  const std::vector<Eigen::Vector2d> points = randomPoints (50, 42);
  Eigen::MatrixXd values, some;
  dictionary.evaluate (points, values);
  const std::vector<int> atoms = {143, 0, 13, 7, 100};
  dictionary.evaluate (points, atoms, some);
  ASSERT_EQ (values.cols (), 144);
  ASSERT_EQ (some.cols (), 5);
  double worst = 0.0;
  for (int p = 0; p < 50; ++p)
  {
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j)
        worst = std::max (worst, std::abs (values (p, i * 12 + j) - dctAtom (i, j, points[p].x (), points[p].y ())));
    for (int k = 0; k < 5; ++k)
      worst = std::max (worst, std::abs (some (p, k) - values (p, atoms[k])));
  }
  EXPECT_LT (worst, 1e-12);
}

TEST (DctCosineDictionary, CodeDerivativesMatchFiniteDifferences)
{
  const DctCosineDictionary dictionary (12);
  std::mt19937 rng (9);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<int> atoms;
    std::vector<double> coefficients;
    randomCode (rng, atoms, coefficients);
    // Beyond the square too (footprints may reach past it).
    const double x = 1.2 * u (rng), y = 1.2 * u (rng);
    const HeightSample s = dictionary.evaluateCode (atoms, coefficients, x, y);
    double direct = 0.0;
    for (int k = 0; k < 10; ++k)
      direct += coefficients[k] * dctAtom (dictionary.frequencyX (atoms[k]), dictionary.frequencyY (atoms[k]), x, y);
    EXPECT_NEAR (s.value, direct, 1e-12);
    EXPECT_NEAR (dictionary.evaluateCodeValue (atoms, coefficients, x, y), direct, 1e-12);

    expectDerivativesMatchFiniteDifferences (dictionary, atoms, coefficients, x, y);
    // Analytic gradient of the atoms' chain rule, not just consistency: single atom (3, 0).
    const HeightSample one = dictionary.evaluateCode ({dictionary.atomIndex (3, 0)}, {1.0}, x, y);
    EXPECT_NEAR (one.gradient.x (), -1.5 * M_PI * std::sin (1.5 * M_PI * (x + 1.0)), 1e-12);
    EXPECT_NEAR (one.hessian (0, 0), -2.25 * M_PI * M_PI * std::cos (1.5 * M_PI * (x + 1.0)), 1e-11);
  }
}

// Odd heights: every paper atom is even in x and in y, so an odd height is orthogonal to all of them on
// symmetric samples; the half-period atoms include odd ones. Their series converges like that of the paper's
// atoms on even heights: fast (1 / k^4) when the slope vanishes at x = +-1 (x^3 - 3 x), slowly (1 / k^2)
// otherwise (x^3 + x y / 2: a few per cent with 12 frequencies, as the paper's atoms on x^2 + y^2).
TEST (DctCosineDictionary, RepresentsOddHeightsThePaperDictionaryCannot)
{
  std::vector<Eigen::Vector2d> points = randomPoints (200, 3);
  const std::size_t half = points.size ();
  for (std::size_t p = 0; p < half; ++p)  // mirror: symmetric sample set
    points.emplace_back (-points[p].x (), points[p].y ());
  auto relativeResidual = [&] (const SurfaceBasis& basis, int max_atoms, const std::function<double (double, double)>& height) {
    Eigen::VectorXd heights (points.size ());
    for (std::size_t p = 0; p < points.size (); ++p)
      heights[p] = height (points[p].x (), points[p].y ());
    Eigen::MatrixXd D;
    basis.evaluate (points, D);
    if (max_atoms <= 0)  // least squares over all atoms
      return (D * D.colPivHouseholderQr ().solve (heights) - heights).norm () / heights.norm ();
    return orthogonalMatchingPursuit (heights, D, {}, 1e-12, max_atoms).residual_norm / heights.norm ();
  };
  const auto flat_ends = [] (double x, double) { return x * x * x - 3.0 * x; };
  const auto cubic = [] (double x, double y) { return x * x * x + 0.5 * x * y; };
  for (const auto& height : {std::function<double (double, double)> (flat_ends), std::function<double (double, double)> (cubic)})
  {
    EXPECT_GT (relativeResidual (CosineDictionary (12), 0, height), 0.999);
    EXPECT_GT (relativeResidual (CosineDictionary (12), 12, height), 0.999);
  }
  EXPECT_LT (relativeResidual (DctCosineDictionary (12), 0, flat_ends), 1e-4);
  EXPECT_LT (relativeResidual (DctCosineDictionary (12), 6, flat_ends), 1e-3);
  EXPECT_LT (relativeResidual (DctCosineDictionary (12), 0, cubic), 0.05);
  EXPECT_LT (relativeResidual (DctCosineDictionary (12), 12, cubic), 0.06);
}

TEST (CosineBasisKindNames, RoundTripAndRefuseUnknown)
{
  for (const CosineBasisKind kind : {CosineBasisKind::Paper, CosineBasisKind::Dct, CosineBasisKind::DctQuadric})
    EXPECT_EQ (cosineBasisKindFromName (cosineBasisKindName (kind)), kind);
  EXPECT_STREQ (cosineBasisKindName (CosineBasisKind::DctQuadric), "quadric");
  EXPECT_THROW (cosineBasisKindFromName ("dst"), Error);
  EXPECT_THROW (cosineBasisKindFromName (""), Error);
}

// The quadric basis: the 144 half-period atoms unchanged, then x, y, x^2, x y, y^2 (infinite wavelength:
// the Nyquist cap never removes them), with exact values and derivatives, in a code mixed with cosines.
TEST (QuadricDctDictionary, MonomialsAfterTheCosines)
{
  const QuadricDctDictionary quadric (12);
  const DctCosineDictionary dct (12);
  EXPECT_EQ (quadric.size (), 149);
  EXPECT_EQ (quadric.kind (), CosineBasisKind::DctQuadric);
  EXPECT_EQ (quadric.monomials (), 5);
  EXPECT_NE (dynamic_cast<const QuadricDctDictionary*> (makeCosineBasis (CosineBasisKind::DctQuadric, 12).get ()), nullptr);
  for (int atom = 144; atom < 149; ++atom)
  {
    EXPECT_TRUE (quadric.isMonomial (atom));
    EXPECT_TRUE (std::isinf (quadric.wavelength (atom)));
  }
  EXPECT_FALSE (quadric.isMonomial (143));
  EXPECT_EQ (nyquistAllowedAtoms (quadric, 0.5, 0.5, NyquistRule::Paper).back (), 1);

  const std::vector<Eigen::Vector2d> points = randomPoints (50, 4);
  Eigen::MatrixXd all, cosines, some;
  quadric.evaluate (points, all);
  dct.evaluate (points, cosines);
  ASSERT_EQ (all.cols (), 149);
  EXPECT_EQ (all.leftCols (144), cosines);  // the cosines bit for bit
  const std::vector<int> atoms = {146, 3, 144, 147, 13, 148, 145};
  quadric.evaluate (points, atoms, some);
  for (std::size_t p = 0; p < points.size (); ++p)
  {
    const double x = points[p].x (), y = points[p].y ();
    const double expected[5] = {x, y, x * x, x * y, y * y};
    for (int m = 0; m < 5; ++m)
      EXPECT_EQ (all (static_cast<Eigen::Index> (p), 144 + m), expected[m]);
    for (std::size_t k = 0; k < atoms.size (); ++k)
      EXPECT_EQ (some (static_cast<Eigen::Index> (p), static_cast<Eigen::Index> (k)), all (static_cast<Eigen::Index> (p), atoms[k]));
  }

  // A code: 1 + 2 x - y + 0.5 x^2 - 3 x y + 0.25 y^2 + 0.1 cos(3 pi (x + 1) / 2) cos(pi (y + 1) / 2).
  const std::vector<int> code = {0, 144, 145, 146, 147, 148, dct.atomIndex (3, 1)};
  const std::vector<double> coefficients = {1.0, 2.0, -1.0, 0.5, -3.0, 0.25, 0.1};
  for (const Eigen::Vector2d& p : points)
  {
    const double x = p.x (), y = p.y ();
    const double a = 1.5 * M_PI * (x + 1.0), b = 0.5 * M_PI * (y + 1.0);
    const HeightSample s = quadric.evaluateCode (code, coefficients, x, y);
    EXPECT_NEAR (s.value, 1.0 + 2.0 * x - y + 0.5 * x * x - 3.0 * x * y + 0.25 * y * y + 0.1 * std::cos (a) * std::cos (b), 1e-13);
    EXPECT_NEAR (quadric.evaluateCodeValue (code, coefficients, x, y), s.value, 1e-13);
    EXPECT_NEAR (s.gradient.x (), 2.0 + x - 3.0 * y - 0.1 * 1.5 * M_PI * std::sin (a) * std::cos (b), 1e-12);
    EXPECT_NEAR (s.gradient.y (), -1.0 - 3.0 * x + 0.5 * y - 0.1 * 0.5 * M_PI * std::cos (a) * std::sin (b), 1e-12);
    EXPECT_NEAR (s.hessian (0, 0), 1.0 - 0.1 * 2.25 * M_PI * M_PI * std::cos (a) * std::cos (b), 1e-11);
    EXPECT_NEAR (s.hessian (0, 1), -3.0 + 0.1 * 0.75 * M_PI * M_PI * std::sin (a) * std::sin (b), 1e-11);
    EXPECT_EQ (s.hessian (0, 1), s.hessian (1, 0));
    EXPECT_NEAR (s.hessian (1, 1), 0.5 - 0.1 * 0.25 * M_PI * M_PI * std::cos (a) * std::cos (b), 1e-11);
  }
  // Without monomials in a code, the quadric basis gives the cosines' bits.
  const std::vector<int> cosine_code = {0, 5, 17, 140};
  const std::vector<double> cosine_coefficients = {0.3, -0.2, 0.05, 0.01};
  const HeightSample a = quadric.evaluateCode (cosine_code, cosine_coefficients, 0.3, -0.7);
  const HeightSample b = dct.evaluateCode (cosine_code, cosine_coefficients, 0.3, -0.7);
  EXPECT_EQ (a.value, b.value);
  EXPECT_EQ (a.gradient, b.gradient);
  EXPECT_EQ (a.hessian, b.hessian);
}

// Why the quadric: a sphere's cap of radius 4 (local units) over the unit disk. The cosines reach x^2 + y^2
// only slowly (their series of x^2 decays as 1 / k^2): OMP stops at L = 12 atoms 3.6 % off. The quadric's
// six atoms, preferred, code it to 0.2 % (the rest is the cap's quartic term), with half the atoms.
TEST (QuadricDctDictionary, CodesASphereCapWithTheQuadric)
{
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector2d& p : randomPoints (400, 5))
    if (p.norm () < 1.0)
      points.push_back (p);
  Eigen::VectorXd heights (static_cast<Eigen::Index> (points.size ()));
  for (std::size_t p = 0; p < points.size (); ++p)
    heights[static_cast<Eigen::Index> (p)] = std::sqrt (16.0 - points[p].squaredNorm ()) - 4.0 + 0.1 * points[p].x ();
  Eigen::MatrixXd cosines, quadric;
  DctCosineDictionary (12).evaluate (points, cosines);
  const QuadricDctDictionary basis (12);
  basis.evaluate (points, quadric);
  std::vector<char> preferred (149, 1);
  preferred[0] = 2;
  for (int atom = 144; atom < 149; ++atom)
    preferred[atom] = 2;
  const OmpResult with_cosines = orthogonalMatchingPursuit (heights, cosines, {}, 0.01, 12);
  const OmpResult with_quadric = orthogonalMatchingPursuit (heights, quadric, preferred, 0.01, 12, OmpSelection{0.3});
  const double norm = heights.norm ();
  std::cout << "sphere cap: cosines " << with_cosines.atoms.size () << " atoms, residual " << with_cosines.residual_norm / norm
            << "; quadric " << with_quadric.atoms.size () << " atoms, residual " << with_quadric.residual_norm / norm << std::endl;
  EXPECT_EQ (with_cosines.atoms.size (), 12u);
  EXPECT_GT (with_cosines.residual_norm, 0.02 * norm);
  EXPECT_LE (with_quadric.atoms.size (), 6u);
  EXPECT_LT (with_quadric.residual_norm, 0.005 * norm);
  for (int atom : with_quadric.atoms)
    EXPECT_TRUE (atom == 0 || basis.isMonomial (atom)) << atom;
  // Without the preference (1: the best atom always), OMP starts with cosines and does not get there.
  const OmpResult unpreferred = orthogonalMatchingPursuit (heights, quadric, preferred, 0.01, 12, OmpSelection{1.0});
  EXPECT_GT (unpreferred.residual_norm, 2.0 * with_quadric.residual_norm);
}
