/// Implementation of CosineAtoms (cosine_atoms.h) for both kinds; kept under this name, which
/// test/sanitized/CMakeLists.txt lists.
#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/dct_cosine_dictionary.h>
#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// sin(pi x) and cos(pi x) without libm: x = q / 2 + r with |r| <= 1/4, Taylor series of sin and cos
    /// of pi r to degree 17 / 18 (truncation below 1e-16 for |pi r| <= pi / 4), then the quadrant q.
    /// About twice as fast as sincos, which dominates evaluateCode.
    inline void
    sinCosPi (double x, double& sine, double& cosine)
    {
      const double q = std::floor (2.0 * x + 0.5);
      const double t = M_PI * (x - 0.5 * q);
      const double t2 = t * t;
      // Horner form of the series with the reciprocals 1 / ((2k)(2k + 1)) and 1 / ((2k - 1)(2k)) folded in.
      constexpr double s3 = 1.0 / 6.0, s5 = 1.0 / 20.0, s7 = 1.0 / 42.0, s9 = 1.0 / 72.0, s11 = 1.0 / 110.0,
                       s13 = 1.0 / 156.0, s15 = 1.0 / 210.0, s17 = 1.0 / 272.0;
      constexpr double c2 = 1.0 / 2.0, c4 = 1.0 / 12.0, c6 = 1.0 / 30.0, c8 = 1.0 / 56.0, c10 = 1.0 / 90.0,
                       c12 = 1.0 / 132.0, c14 = 1.0 / 182.0, c16 = 1.0 / 240.0, c18 = 1.0 / 306.0;
      const double s = t * (1.0 - s3 * t2 * (1.0 - s5 * t2 * (1.0 - s7 * t2 * (1.0 - s9 * t2 * (1.0 - s11 * t2 *
                                  (1.0 - s13 * t2 * (1.0 - s15 * t2 * (1.0 - s17 * t2))))))));
      const double c = 1.0 - c2 * t2 * (1.0 - c4 * t2 * (1.0 - c6 * t2 * (1.0 - c8 * t2 * (1.0 - c10 * t2 *
                             (1.0 - c12 * t2 * (1.0 - c14 * t2 * (1.0 - c16 * t2 * (1.0 - c18 * t2))))))));
      switch (static_cast<long> (q) & 3)
      {
        case 0: sine = s; cosine = c; break;
        case 1: sine = c; cosine = -s; break;
        case 2: sine = -s; cosine = -c; break;
        default: sine = -c; cosine = s; break;
      }
    }

    /// cos(k pi t) and sin(k pi t) for k = 0 .. count-1 by angle addition from one sin/cos pair. Steps of
    /// 4 (from k - 4) make four independent recurrence chains: the CPU runs them in parallel, where a
    /// single chain k -> k + 1 would be one long dependency path (the hot spot of evaluateCode).
    inline void
    harmonics (double t, int count, double* c, double* s)
    {
      double s1, c1;
      sinCosPi (t, s1, c1);
      c[0] = 1.0;
      s[0] = 0.0;
      c[1] = c1;
      s[1] = s1;
      const double c2 = c1 * c1 - s1 * s1, s2 = 2.0 * s1 * c1;
      c[2] = c2;
      s[2] = s2;
      c[3] = c2 * c1 - s2 * s1;
      s[3] = s2 * c1 + c2 * s1;
      const double c4 = c2 * c2 - s2 * s2, s4 = 2.0 * s2 * c2;
      for (int k = 4; k < count; ++k)
      {
        c[k] = c[k - 4] * c4 - s[k - 4] * s4;
        s[k] = s[k - 4] * c4 + c[k - 4] * s4;
      }
    }

    /// cos(k pi t) for k = 0 .. count-1 by the Chebyshev recurrence, in two independent chains:
    /// cos((k + 2) a) = 2 cos(2 a) cos(k a) - cos((k - 2) a).
    inline void
    cosines (double t, int count, double* c)
    {
      double s1, c1;
      sinCosPi (t, s1, c1);
      const double c2 = 2.0 * c1 * c1 - 1.0;
      c[0] = 1.0;
      c[1] = c1;
      c[2] = c2;
      c[3] = 2.0 * c2 * c1 - c1;
      const double twice_c2 = 2.0 * c2;
      for (int k = 4; k < count; ++k)
        c[k] = twice_c2 * c[k - 2] - c[k - 4];
    }
  } // namespace

  CosineAtoms::CosineAtoms (int frequencies, CosineBasisKind kind)
    : n_ (frequencies), kind_ (kind), monomials_ (kind == CosineBasisKind::DctQuadric ? quadric_monomials : 0),
      scale_ (kind == CosineBasisKind::Paper ? 1.0 : 0.5), shift_ (kind == CosineBasisKind::Paper ? 0.0 : 0.5)
  {
    if (frequencies < 1 || frequencies > max_frequencies)
      throw Error (std::string (kind == CosineBasisKind::Paper ? "CosineDictionary" : "DctCosineDictionary") +
                   ": frequencies must be in [1, " + std::to_string (max_frequencies) + "], got " +
                   std::to_string (frequencies));
    // Monomials get frequency 0 here (their own terms are added by addQuadric).
    frequency_x_.assign (static_cast<std::size_t> (size ()), 0);
    frequency_y_.assign (static_cast<std::size_t> (size ()), 0);
    for (int a = 0; a < n_ * n_; ++a)
    {
      frequency_x_[a] = static_cast<std::uint8_t> (a / n_);
      frequency_y_[a] = static_cast<std::uint8_t> (a % n_);
    }
  }

  void
  CosineAtoms::monomialExponents (int monomial, int& p, int& q)
  {
    static constexpr int px[quadric_monomials] = {1, 0, 2, 1, 0}, py[quadric_monomials] = {0, 1, 0, 1, 2};
    p = px[monomial];
    q = py[monomial];
  }

  bool
  CosineAtoms::quadricCoefficients (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                    double* m) const
  {
    std::fill (m, m + quadric_monomials, 0.0);
    bool any = false;
    const std::size_t k_end = std::min (atoms.size (), coefficients.size ());
    for (std::size_t k = 0; k < k_end; ++k)
      if (isMonomial (atoms[k]))
      {
        m[atoms[k] - n_ * n_] += coefficients[k];
        any = true;
      }
    return any;
  }

  double
  CosineAtoms::wavelength (int atom) const
  {
    // cos(m pi s) has period 2 / m in s, i.e. 2 / (m ds/dt) in the patch coordinate t.
    if (isMonomial (atom))
      return std::numeric_limits<double>::infinity ();
    const int m = std::max (frequencyX (atom), frequencyY (atom));
    return m == 0 ? std::numeric_limits<double>::infinity () : 2.0 / (scale_ * m);
  }

  double
  CosineAtoms::atomBound (int atom, double half_width) const
  {
    if (!isMonomial (atom))
      return 1.0;
    int p, q;
    monomialExponents (atom - n_ * n_, p, q);
    return std::pow (std::abs (half_width), p + q);
  }

  namespace
  {
    /// Per-axis tables: cx (p, k) = cos(k pi s(x_p)), cy (p, k) = cos(k pi s(y_p)), k < count, with
    /// s(t) = scale * t + shift.
    void
    axisTables (const std::vector<Eigen::Vector2d>& points, int count, double scale, double shift,
                Eigen::MatrixXd& cx, Eigen::MatrixXd& cy)
    {
      const Eigen::Index size = static_cast<Eigen::Index> (points.size ());
      cx.resize (size, count);
      cy.resize (size, count);
      double c[2 * CosineAtoms::max_frequencies + 4];
      for (Eigen::Index p = 0; p < size; ++p)
      {
        cosines (scale * points[p].x () + shift, count, c);
        for (int k = 0; k < count; ++k)
          cx (p, k) = c[k];
        cosines (scale * points[p].y () + shift, count, c);
        for (int k = 0; k < count; ++k)
          cy (p, k) = c[k];
      }
    }

    /// Values x^p y^q of monomial \a monomial (CosineAtoms::monomialExponents) at every point.
    template <typename Column>
    void
    monomialColumn (const std::vector<Eigen::Vector2d>& points, int monomial, Column&& column)
    {
      int p, q;
      CosineAtoms::monomialExponents (monomial, p, q);
      for (std::size_t k = 0; k < points.size (); ++k)
      {
        const double x = points[k].x (), y = points[k].y ();
        column[static_cast<Eigen::Index> (k)] = (p == 0 ? 1.0 : p == 1 ? x : x * x) * (q == 0 ? 1.0 : q == 1 ? y : y * y);
      }
    }
  } // namespace

  void
  CosineAtoms::evaluate (const std::vector<Eigen::Vector2d>& points, Eigen::MatrixXd& values) const
  {
    // Per-axis tables first, then each atom column is one vectorised product of two table columns.
    Eigen::MatrixXd cx, cy;
    axisTables (points, n_, scale_, shift_, cx, cy);
    values.resize (static_cast<Eigen::Index> (points.size ()), size ());
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j)
        values.col (i * n_ + j) = cx.col (i).cwiseProduct (cy.col (j));
    for (int m = 0; m < monomials_; ++m)
      monomialColumn (points, m, values.col (n_ * n_ + m));
  }

  void
  CosineAtoms::evaluate (const std::vector<Eigen::Vector2d>& points, const std::vector<int>& atoms,
                              Eigen::MatrixXd& values) const
  {
    int count = 1;
    for (int a : atoms)
      if (!isMonomial (a))
        count = std::max ({count, a / n_ + 1, a % n_ + 1});
    Eigen::MatrixXd cx, cy;
    axisTables (points, count, scale_, shift_, cx, cy);
    values.resize (static_cast<Eigen::Index> (points.size ()), static_cast<Eigen::Index> (atoms.size ()));
    for (std::size_t k = 0; k < atoms.size (); ++k)
      if (isMonomial (atoms[k]))
        monomialColumn (points, atoms[k] - n_ * n_, values.col (static_cast<Eigen::Index> (k)));
      else
        values.col (static_cast<Eigen::Index> (k)) = cx.col (atoms[k] / n_).cwiseProduct (cy.col (atoms[k] % n_));
  }

  void
  CosineAtoms::axisCosines (const std::vector<Eigen::Vector2d>& points, int count, Eigen::MatrixXd& cx,
                            Eigen::MatrixXd& cy) const
  {
    if (count < 1 || count > 2 * max_frequencies)
      throw Error ("CosineAtoms::axisCosines: count must be in [1, " + std::to_string (2 * max_frequencies) +
                   "], got " + std::to_string (count));
    axisTables (points, count, scale_, shift_, cx, cy);
  }

  HeightSample
  CosineAtoms::evaluateCode (const std::vector<int>& atoms, const std::vector<double>& coefficients, double x,
                                  double y) const
  {
    // Frequencies of the code's atoms once (table lookups), then tables only as long as needed.
    constexpr int stack_atoms = 64;
    const std::size_t k_end = std::min (atoms.size (), coefficients.size ());
    if (k_end > static_cast<std::size_t> (stack_atoms))
      return evaluateLongCode (atoms, coefficients, x, y);
    int fi[stack_atoms], fj[stack_atoms];
    double coefficient[stack_atoms];
    int count_x = 1, count_y = 1;
    std::size_t terms = 0;
    bool has_monomials = false;
    for (std::size_t k = 0; k < k_end; ++k)
    {
      if (isMonomial (atoms[k]))
      {
        has_monomials = true;
        continue;
      }
      fi[terms] = frequency_x_[atoms[k]];
      fj[terms] = frequency_y_[atoms[k]];
      coefficient[terms] = coefficients[k];
      count_x = std::max (count_x, fi[terms] + 1);
      count_y = std::max (count_y, fj[terms] + 1);
      ++terms;
    }
    double cx[max_frequencies + 4], sx[max_frequencies + 4], cy[max_frequencies + 4], sy[max_frequencies + 4];
    harmonics (argument (x), count_x, cx, sx);
    harmonics (argument (y), count_y, cy, sy);

    // Derivatives: d/dx cos(i pi s) = -i pi s' sin(i pi s), d2/dx2 = -(i pi s')^2 cos(i pi s), s' = scale_.
    double v = 0.0, gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0;
    for (std::size_t k = 0; k < terms; ++k)
    {
      const int i = fi[k], j = fj[k];
      const double a = coefficient[k];
      const double ci = cx[i], si = sx[i], cj = cy[j], sj = sy[j];
      const double di = i, dj = j;
      const double acc = a * ci * cj;
      v += acc;
      gx -= a * di * si * cj;
      gy -= a * dj * ci * sj;
      hxx -= di * di * acc;
      hxy += a * di * dj * si * sj;
      hyy -= dj * dj * acc;
    }
    HeightSample sample;
    sample.value = v;
    const double pi = M_PI * scale_;
    sample.gradient = Eigen::Vector2d (pi * gx, pi * gy);
    const double pi2 = pi * pi;
    sample.hessian << pi2 * hxx, pi2 * hxy, pi2 * hxy, pi2 * hyy;
    double m[quadric_monomials];
    if (has_monomials && quadricCoefficients (atoms, coefficients, m))
    {
      double hxy_total = sample.hessian (0, 1);
      addQuadric (m, x, y, sample.value, sample.gradient.x (), sample.gradient.y (), sample.hessian (0, 0), hxy_total,
                  sample.hessian (1, 1));
      sample.hessian (0, 1) = sample.hessian (1, 0) = hxy_total;
    }
    return sample;
  }

  HeightSample
  CosineAtoms::evaluateLongCode (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                      double x, double y) const
  {
    // Rare (more than 64 atoms): split into chunks and add up.
    HeightSample total;
    const std::size_t k_end = std::min (atoms.size (), coefficients.size ());
    for (std::size_t first = 0; first < k_end; first += 64)
    {
      const std::size_t last = std::min (k_end, first + 64);
      const std::vector<int> a (atoms.begin () + first, atoms.begin () + last);
      const std::vector<double> c (coefficients.begin () + first, coefficients.begin () + last);
      const HeightSample part = evaluateCode (a, c, x, y);
      total.value += part.value;
      total.gradient += part.gradient;
      total.hessian += part.hessian;
    }
    return total;
  }

  double
  CosineAtoms::evaluateCodeValue (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                       double x, double y) const
  {
    const std::size_t k_end = std::min (atoms.size (), coefficients.size ());
    int count_x = 1, count_y = 1;
    for (std::size_t k = 0; k < k_end; ++k)
    {
      count_x = std::max (count_x, frequency_x_[atoms[k]] + 1);
      count_y = std::max (count_y, frequency_y_[atoms[k]] + 1);
    }
    double cx[max_frequencies + 4], cy[max_frequencies + 4];
    cosines (argument (x), count_x, cx);
    cosines (argument (y), count_y, cy);
    double v = 0.0;
    if (monomials_ == 0)
    {
      for (std::size_t k = 0; k < k_end; ++k)
        v += coefficients[k] * cx[frequency_x_[atoms[k]]] * cy[frequency_y_[atoms[k]]];
      return v;
    }
    for (std::size_t k = 0; k < k_end; ++k)
      if (!isMonomial (atoms[k]))
        v += coefficients[k] * cx[frequency_x_[atoms[k]]] * cy[frequency_y_[atoms[k]]];
    double m[quadric_monomials];
    if (quadricCoefficients (atoms, coefficients, m))
      v += quadricValue (m, x, y);
    return v;
  }

  CosineAtoms::ConstPtr
  makeCosineBasis (CosineBasisKind kind, int frequencies)
  {
    if (kind == CosineBasisKind::Dct)
      return std::make_shared<DctCosineDictionary> (frequencies);
    if (kind == CosineBasisKind::DctQuadric)
      return std::make_shared<QuadricDctDictionary> (frequencies);
    return std::make_shared<CosineDictionary> (frequencies);
  }

  const char*
  cosineBasisKindName (CosineBasisKind kind)
  {
    return kind == CosineBasisKind::Dct ? "dct" : kind == CosineBasisKind::DctQuadric ? "quadric" : "paper";
  }

  CosineBasisKind
  cosineBasisKindFromName (const std::string& name)
  {
    for (const CosineBasisKind kind : {CosineBasisKind::Paper, CosineBasisKind::Dct, CosineBasisKind::DctQuadric})
      if (name == cosineBasisKindName (kind))
        return kind;
    throw Error ("unknown basis '" + name + "': expected paper, dct or quadric");
  }
} // namespace pcl_sparse
