#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/dct_cosine_dictionary.h>
#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>
#include <pcl_sparse/coding/nyquist_cap.h>
#include <pcl_sparse/common/error.h>

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <functional>
#include <random>

using namespace pcl_sparse;

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
  std::uniform_int_distribution<int> atom (0, 143);
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<int> atoms;
    std::vector<double> coefficients;
    for (int k = 0; k < 10; ++k)
    {
      atoms.push_back (atom (rng));
      coefficients.push_back (u (rng));
    }
    const double x = 0.9 * u (rng), y = 0.9 * u (rng);
    const HeightSample s = dictionary.evaluateCode (atoms, coefficients, x, y);
    double direct = 0.0;
    for (int k = 0; k < 10; ++k)
      direct += coefficients[k] * std::cos (M_PI * dictionary.frequencyX (atoms[k]) * x) *
                std::cos (M_PI * dictionary.frequencyY (atoms[k]) * y);
    EXPECT_NEAR (s.value, direct, 1e-12);
    EXPECT_NEAR (dictionary.evaluateCodeValue (atoms, coefficients, x, y), direct, 1e-12);

    // Central differences err by about h^2 (11 pi)^2 / 6 = 2e-8 relative to the derivative they estimate
    // (atoms up to frequency 11), rounding by about 1e-11: 1e-6 of the magnitude leaves a margin of 50.
    const double h = 1e-5;
    auto f = [&] (double a, double b) { return dictionary.evaluateCode (atoms, coefficients, a, b); };
    const double scale = 1.0 + s.gradient.norm ();
    EXPECT_NEAR (s.gradient.x (), (f (x + h, y).value - f (x - h, y).value) / (2 * h), 1e-6 * scale);
    EXPECT_NEAR (s.gradient.y (), (f (x, y + h).value - f (x, y - h).value) / (2 * h), 1e-6 * scale);
    const double hscale = 1.0 + s.hessian.norm ();
    EXPECT_NEAR (s.hessian (0, 0), (f (x + h, y).gradient.x () - f (x - h, y).gradient.x ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (0, 1), (f (x, y + h).gradient.x () - f (x, y - h).gradient.x ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (1, 0), (f (x + h, y).gradient.y () - f (x - h, y).gradient.y ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (1, 1), (f (x, y + h).gradient.y () - f (x, y - h).gradient.y ()) / (2 * h), 1e-6 * hscale);
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
  std::uniform_int_distribution<int> atom (0, 143);
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<int> atoms;
    std::vector<double> coefficients;
    for (int k = 0; k < 10; ++k)
    {
      atoms.push_back (atom (rng));
      coefficients.push_back (u (rng));
    }
    // Beyond the square too (footprints may reach past it).
    const double x = 1.2 * u (rng), y = 1.2 * u (rng);
    const HeightSample s = dictionary.evaluateCode (atoms, coefficients, x, y);
    double direct = 0.0;
    for (int k = 0; k < 10; ++k)
      direct += coefficients[k] * dctAtom (dictionary.frequencyX (atoms[k]), dictionary.frequencyY (atoms[k]), x, y);
    EXPECT_NEAR (s.value, direct, 1e-12);
    EXPECT_NEAR (dictionary.evaluateCodeValue (atoms, coefficients, x, y), direct, 1e-12);

    // Central differences err by about h^2 (11 pi)^2 / 6 = 2e-8 relative to the derivative they estimate
    // (atoms up to frequency 11), rounding by about 1e-11: 1e-6 of the magnitude leaves a margin of 50.
    const double h = 1e-5;
    auto f = [&] (double a, double b) { return dictionary.evaluateCode (atoms, coefficients, a, b); };
    const double scale = 1.0 + s.gradient.norm ();
    EXPECT_NEAR (s.gradient.x (), (f (x + h, y).value - f (x - h, y).value) / (2 * h), 1e-6 * scale);
    EXPECT_NEAR (s.gradient.y (), (f (x, y + h).value - f (x, y - h).value) / (2 * h), 1e-6 * scale);
    const double hscale = 1.0 + s.hessian.norm ();
    EXPECT_NEAR (s.hessian (0, 0), (f (x + h, y).gradient.x () - f (x - h, y).gradient.x ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (0, 1), (f (x, y + h).gradient.x () - f (x, y - h).gradient.x ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (1, 0), (f (x + h, y).gradient.y () - f (x - h, y).gradient.y ()) / (2 * h), 1e-6 * hscale);
    EXPECT_NEAR (s.hessian (1, 1), (f (x, y + h).gradient.y () - f (x, y - h).gradient.y ()) / (2 * h), 1e-6 * hscale);
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
  for (const CosineBasisKind kind : {CosineBasisKind::Paper, CosineBasisKind::Dct})
    EXPECT_EQ (cosineBasisKindFromName (cosineBasisKindName (kind)), kind);
  EXPECT_THROW (cosineBasisKindFromName ("dst"), Error);
  EXPECT_THROW (cosineBasisKindFromName (""), Error);
}
