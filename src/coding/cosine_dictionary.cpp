#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// cos(k pi t) and sin(k pi t) for k = 0 .. count-1 by angle addition from one sin/cos pair.
    inline void
    harmonics (double t, int count, double* c, double* s)
    {
      const double c1 = std::cos (M_PI * t);
      const double s1 = std::sin (M_PI * t);
      c[0] = 1.0;
      s[0] = 0.0;
      for (int k = 1; k < count; ++k)
      {
        c[k] = c[k - 1] * c1 - s[k - 1] * s1;
        s[k] = s[k - 1] * c1 + c[k - 1] * s1;
      }
    }

    /// cos(k pi t) for k = 0 .. count-1 by the Chebyshev recurrence T_{k+1} = 2 x T_k - T_{k-1}.
    inline void
    cosines (double t, int count, double* c)
    {
      const double c1 = std::cos (M_PI * t);
      c[0] = 1.0;
      if (count > 1)
        c[1] = c1;
      for (int k = 2; k < count; ++k)
        c[k] = 2.0 * c1 * c[k - 1] - c[k - 2];
    }
  } // namespace

  CosineDictionary::CosineDictionary (int frequencies) : n_ (frequencies)
  {
    if (frequencies < 1 || frequencies > max_frequencies)
      throw Error ("CosineDictionary: frequencies must be in [1, " + std::to_string (max_frequencies) + "], got " +
                   std::to_string (frequencies));
  }

  double
  CosineDictionary::wavelength (int atom) const
  {
    const int m = std::max (frequencyX (atom), frequencyY (atom));
    return m == 0 ? std::numeric_limits<double>::infinity () : 2.0 / m;
  }

  namespace
  {
    /// Per-axis tables: cx (p, k) = cos(k pi x_p), cy (p, k) = cos(k pi y_p), k < count.
    void
    axisTables (const std::vector<Eigen::Vector2d>& points, int count, Eigen::MatrixXd& cx, Eigen::MatrixXd& cy)
    {
      const Eigen::Index size = static_cast<Eigen::Index> (points.size ());
      cx.resize (size, count);
      cy.resize (size, count);
      double c[CosineDictionary::max_frequencies];
      for (Eigen::Index p = 0; p < size; ++p)
      {
        cosines (points[p].x (), count, c);
        for (int k = 0; k < count; ++k)
          cx (p, k) = c[k];
        cosines (points[p].y (), count, c);
        for (int k = 0; k < count; ++k)
          cy (p, k) = c[k];
      }
    }
  } // namespace

  void
  CosineDictionary::evaluate (const std::vector<Eigen::Vector2d>& points, Eigen::MatrixXd& values) const
  {
    // Per-axis tables first, then each atom column is one vectorised product of two table columns.
    Eigen::MatrixXd cx, cy;
    axisTables (points, n_, cx, cy);
    values.resize (static_cast<Eigen::Index> (points.size ()), n_ * n_);
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j)
        values.col (i * n_ + j) = cx.col (i).cwiseProduct (cy.col (j));
  }

  void
  CosineDictionary::evaluate (const std::vector<Eigen::Vector2d>& points, const std::vector<int>& atoms,
                              Eigen::MatrixXd& values) const
  {
    int count = 1;
    for (int a : atoms)
      count = std::max ({count, a / n_ + 1, a % n_ + 1});
    Eigen::MatrixXd cx, cy;
    axisTables (points, count, cx, cy);
    values.resize (static_cast<Eigen::Index> (points.size ()), static_cast<Eigen::Index> (atoms.size ()));
    for (std::size_t k = 0; k < atoms.size (); ++k)
      values.col (static_cast<Eigen::Index> (k)) = cx.col (atoms[k] / n_).cwiseProduct (cy.col (atoms[k] % n_));
  }

  HeightSample
  CosineDictionary::evaluateCode (const std::vector<int>& atoms, const std::vector<double>& coefficients, double x,
                                  double y) const
  {
    int count_x = 1, count_y = 1;
    for (int a : atoms)
    {
      count_x = std::max (count_x, a / n_ + 1);
      count_y = std::max (count_y, a % n_ + 1);
    }
    double cx[max_frequencies], sx[max_frequencies], cy[max_frequencies], sy[max_frequencies];
    harmonics (x, count_x, cx, sx);
    harmonics (y, count_y, cy, sy);

    // Derivatives: d/dx cos(i pi x) = -i pi sin(i pi x), d2/dx2 = -(i pi)^2 cos(i pi x).
    double v = 0.0, gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0;
    const std::size_t k_end = std::min (atoms.size (), coefficients.size ());
    for (std::size_t k = 0; k < k_end; ++k)
    {
      const int i = atoms[k] / n_, j = atoms[k] % n_;
      const double a = coefficients[k];
      const double ci = cx[i], si = sx[i], cj = cy[j], sj = sy[j];
      const double fi = i, fj = j;
      v += a * ci * cj;
      gx -= a * fi * si * cj;
      gy -= a * fj * ci * sj;
      hxx -= a * fi * fi * ci * cj;
      hxy += a * fi * fj * si * sj;
      hyy -= a * fj * fj * ci * cj;
    }
    HeightSample sample;
    sample.value = v;
    sample.gradient = Eigen::Vector2d (M_PI * gx, M_PI * gy);
    const double pi2 = M_PI * M_PI;
    sample.hessian << pi2 * hxx, pi2 * hxy, pi2 * hxy, pi2 * hyy;
    return sample;
  }

  double
  CosineDictionary::evaluateCodeValue (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                       double x, double y) const
  {
    int count_x = 1, count_y = 1;
    for (int a : atoms)
    {
      count_x = std::max (count_x, a / n_ + 1);
      count_y = std::max (count_y, a % n_ + 1);
    }
    double cx[max_frequencies], cy[max_frequencies];
    cosines (x, count_x, cx);
    cosines (y, count_y, cy);
    double v = 0.0;
    const std::size_t k_end = std::min (atoms.size (), coefficients.size ());
    for (std::size_t k = 0; k < k_end; ++k)
      v += coefficients[k] * cx[atoms[k] / n_] * cy[atoms[k] % n_];
    return v;
  }
} // namespace pcl_sparse
