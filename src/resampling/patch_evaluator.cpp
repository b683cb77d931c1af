#include <pcl_sparse/resampling/patch_evaluator.h>

#include <pcl_sparse/coding/cosine_dictionary.h>

#include <algorithm>
#include <cmath>

// GCC / Clang on x86-64 with ifunc (glibc): an AVX2 copy chosen at load time; elsewhere the plain one.
#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__)
#define PCL_SPARSE_AVX2_CLONE __attribute__ ((target_clones ("avx2", "default")))
#else
#define PCL_SPARSE_AVX2_CLONE
#endif

namespace pcl_sparse
{
  namespace
  {
    /// sin(r) on [-pi/4, pi/4] (Taylor, truncation below 1e-16); r2 = r * r.
    inline double
    sinPoly (double r, double r2)
    {
      return r * (1.0 + r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362880.0 + r2 * (-1.0 / 39916800.0 +
             r2 * (1.0 / 6227020800.0 + r2 * (-1.0 / 1307674368000.0))))))));
    }

    /// cos(r) on [-pi/4, pi/4] from r2 = r * r.
    inline double
    cosPoly (double r2)
    {
      return 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0 + r2 * (-1.0 / 3628800.0 +
             r2 * (1.0 / 479001600.0 + r2 * (-1.0 / 87178291200.0 + r2 * (1.0 / 20922789888000.0))))))));
    }

    /// sin(pi t) and cos(pi t): reduction to the nearest quarter turn, then Taylor polynomials on
    /// [-pi/4, pi/4] (truncation below 1e-16), a few times faster than std::sin and std::cos.
    inline void
    sinCosPi (double t, double& s, double& c)
    {
      const double k = std::nearbyint (2.0 * t);
      const double r = (t - 0.5 * k) * M_PI, r2 = r * r;
      const double sr = sinPoly (r, r2), cr = cosPoly (r2);
      switch (static_cast<long long> (k) & 3)
      {
        case 0: s = sr; c = cr; break;
        case 1: s = cr; c = -sr; break;
        case 2: s = -sr; c = -cr; break;
        default: s = -cr; c = sr; break;
      }
    }

    constexpr int lanes = PatchEvaluator::Block::size;

    /// sinCosPi of every lane, branch free so that it vectorises; the same rounding (the quarter turn
    /// k mod 4 is exact in doubles).
    inline void
    sinCosPiLanes (const double* t, double* s, double* c)
    {
      for (int b = 0; b < lanes; ++b)
      {
        const double k = std::nearbyint (2.0 * t[b]);
        const double r = (t[b] - 0.5 * k) * M_PI, r2 = r * r;
        const double sr = sinPoly (r, r2), cr = cosPoly (r2);
        const double q = k - 4.0 * std::floor (0.25 * k);
        s[b] = q == 0.0 ? sr : q == 1.0 ? cr : q == 2.0 ? -sr : -cr;
        c[b] = q == 0.0 ? cr : q == 1.0 ? -sr : q == 2.0 ? -cr : sr;
      }
    }

    /// cos and sin of k pi t for k < n by angle addition, row k at table[k * lanes], as in sample.
    inline void
    harmonicLanes (const double* s1, const double* c1, int n, double* cos_table, double* sin_table)
    {
      for (int b = 0; b < lanes; ++b)
      {
        cos_table[b] = 1.0;
        sin_table[b] = 0.0;
      }
      for (int k = 1; k < n; ++k)
      {
        const double* cp = cos_table + (k - 1) * lanes;
        const double* sp = sin_table + (k - 1) * lanes;
        double* ck = cos_table + k * lanes;
        double* sk = sin_table + k * lanes;
        for (int b = 0; b < lanes; ++b)
        {
          ck[b] = cp[b] * c1[b] - sp[b] * s1[b];
          sk[b] = sp[b] * c1[b] + cp[b] * s1[b];
        }
      }
    }

    /// The half-period atoms' argument s = (t + 1) / 2 (CosineAtoms: scale 1/2, shift 1/2).
    inline double
    halfPeriodArgument (double t)
    {
      return 0.5 * t + 0.5;
    }

    /// PatchEvaluator::sample with the Hessian for a block of places: the same operations in the same
    /// order per lane, so the same bits; the lanes are independent, so the loops vectorise. Compiled for
    /// AVX2 too (no FMA: a fused multiply-add would round differently) and chosen at load time.
    PCL_SPARSE_AVX2_CLONE void
    cosineBlock (const PatchEvaluator::Term* begin, const PatchEvaluator::Term* end, int nx, int ny, bool half_period,
                 const double* monomials, PatchEvaluator::Block& block)
    {
      block.tables.resize (static_cast<std::size_t> (2 * (nx + ny) * lanes));
      double* const cx = block.tables.data ();
      double* const sx = cx + nx * lanes;
      double* const cy = sx + nx * lanes;
      double* const sy = cy + ny * lanes;
      double s1x[lanes], c1x[lanes], s1y[lanes], c1y[lanes];
      if (half_period)
      {
        double tx[lanes], ty[lanes];
        for (int b = 0; b < lanes; ++b)
        {
          tx[b] = halfPeriodArgument (block.x[b]);
          ty[b] = halfPeriodArgument (block.y[b]);
        }
        sinCosPiLanes (tx, s1x, c1x);
        sinCosPiLanes (ty, s1y, c1y);
      }
      else
      {
        sinCosPiLanes (block.x, s1x, c1x);
        sinCosPiLanes (block.y, s1y, c1y);
      }
      harmonicLanes (s1x, c1x, nx, cx, sx);
      harmonicLanes (s1y, c1y, ny, cy, sy);
      double v[lanes] = {}, gx[lanes] = {}, gy[lanes] = {}, hxx[lanes] = {}, hxy[lanes] = {}, hyy[lanes] = {};
      for (const PatchEvaluator::Term* term = begin; term != end; ++term)
      {
        const double *ci = cx + term->i * lanes, *si = sx + term->i * lanes;
        const double *cj = cy + term->j * lanes, *sj = sy + term->j * lanes;
        const double a = term->coefficient, ai = term->ai, aj = term->aj, aij = term->aij, ii = term->ii, jj = term->jj;
        for (int b = 0; b < lanes; ++b)
        {
          const double cc = a * ci[b] * cj[b];
          v[b] += cc;
          gx[b] -= ai * si[b] * cj[b];
          gy[b] -= aj * ci[b] * sj[b];
          hxx[b] -= ii * cc;
          hxy[b] += aij * si[b] * sj[b];
          hyy[b] -= jj * cc;
        }
      }
      const double pi = half_period ? 0.5 * M_PI : M_PI, pi2 = pi * pi;
      for (int b = 0; b < lanes; ++b)
      {
        block.value[b] = v[b];
        block.gx[b] = pi * gx[b];
        block.gy[b] = pi * gy[b];
        block.hxx[b] = pi2 * hxx[b];
        block.hxy[b] = pi2 * hxy[b];
        block.hyy[b] = pi2 * hyy[b];
      }
      if (monomials)
        for (int b = 0; b < lanes; ++b)
          CosineAtoms::addQuadric (monomials, block.x[b], block.y[b], block.value[b], block.gx[b], block.gy[b], block.hxx[b],
                        block.hxy[b], block.hyy[b]);
    }
  } // namespace

  PatchEvaluator::PatchEvaluator (const SparseSurfaceModel& model) : model_ (model)
  {
    const std::size_t m = model.numPatches ();
    const auto* cosine = dynamic_cast<const CosineAtoms*> (model.basis.get ());
    cosine_ = cosine != nullptr;
    half_period_ = cosine_ && cosine->kind () != CosineBasisKind::Paper;
    monomials_ = cosine_ && cosine->monomials () > 0;
    if (monomials_)
      monomial_coefficients_.assign (CosineAtoms::quadric_monomials * m, 0.0);
    term_begin_.assign (1, 0);
    extent_begin_.assign (1, 0);
    count_x_.assign (m, 1);
    count_y_.assign (m, 1);
    max_extent_.assign (m, 1.0);
    for (std::size_t p = 0; p < m; ++p)
    {
      const PatchCode& code = model.patches[p];
      if (monomials_)
        cosine->quadricCoefficients (code.atoms, code.coefficients,
                                     &monomial_coefficients_[CosineAtoms::quadric_monomials * p]);
      if (cosine_)
      {
        const std::size_t count = std::min (code.atoms.size (), code.coefficients.size ());
        for (std::size_t k = 0; k < count; ++k)
        {
          if (cosine->isMonomial (code.atoms[k]))
            continue;  // in monomial_coefficients_
          Term term;
          term.i = cosine->frequencyX (code.atoms[k]);
          term.j = cosine->frequencyY (code.atoms[k]);
          term.coefficient = code.coefficients[k];
          const double a = term.coefficient, fi = term.i, fj = term.j;
          term.ai = a * fi;
          term.aj = a * fj;
          term.aij = a * fi * fj;
          term.ii = fi * fi;
          term.jj = fj * fj;
          count_x_[p] = std::max (count_x_[p], term.i + 1);
          count_y_[p] = std::max (count_y_[p], term.j + 1);
          terms_.push_back (term);
        }
        term_begin_.push_back (terms_.size ());
      }
      extents_.insert (extents_.end (), code.footprint.extent.begin (), code.footprint.extent.end ());
      extent_begin_.push_back (extents_.size ());
      if (!code.footprint.extent.empty ())
        max_extent_[p] = *std::max_element (code.footprint.extent.begin (), code.footprint.extent.end ());
    }
  }

  double
  PatchEvaluator::height (std::size_t p, double x, double y) const
  {
    if (!cosine_)
      return model_.evaluate (p, x, y).value;
    // cos(k pi t) by the Chebyshev recurrence from one cosine per axis.
    double cx[CosineDictionary::max_frequencies], cy[CosineDictionary::max_frequencies];
    const int nx = count_x_[p], ny = count_y_[p];
    double s1x, c1x, s1y, c1y;
    sinCosPi (half_period_ ? halfPeriodArgument (x) : x, s1x, c1x);
    sinCosPi (half_period_ ? halfPeriodArgument (y) : y, s1y, c1y);
    cx[0] = cy[0] = 1.0;
    if (nx > 1)
      cx[1] = c1x;
    if (ny > 1)
      cy[1] = c1y;
    for (int k = 2; k < nx; ++k)
      cx[k] = 2.0 * c1x * cx[k - 1] - cx[k - 2];
    for (int k = 2; k < ny; ++k)
      cy[k] = 2.0 * c1y * cy[k - 1] - cy[k - 2];
    double v = 0.0;
    for (std::size_t t = term_begin_[p]; t < term_begin_[p + 1]; ++t)
      v += terms_[t].coefficient * cx[terms_[t].i] * cy[terms_[t].j];
    if (monomials_)
      v += CosineAtoms::quadricValue (&monomial_coefficients_[CosineAtoms::quadric_monomials * p], x, y);
    return v;
  }

  HeightSample
  PatchEvaluator::sample (std::size_t p, double x, double y, bool hessian) const
  {
    if (!cosine_)
      return model_.evaluate (p, x, y);
    // cos and sin of k pi t by angle addition from one sin/cos pair per axis.
    double cx[CosineDictionary::max_frequencies], sx[CosineDictionary::max_frequencies];
    double cy[CosineDictionary::max_frequencies], sy[CosineDictionary::max_frequencies];
    const int nx = count_x_[p], ny = count_y_[p];
    double s1x, c1x, s1y, c1y;
    sinCosPi (half_period_ ? halfPeriodArgument (x) : x, s1x, c1x);
    sinCosPi (half_period_ ? halfPeriodArgument (y) : y, s1y, c1y);
    cx[0] = cy[0] = 1.0;
    sx[0] = sy[0] = 0.0;
    for (int k = 1; k < nx; ++k)
    {
      cx[k] = cx[k - 1] * c1x - sx[k - 1] * s1x;
      sx[k] = sx[k - 1] * c1x + cx[k - 1] * s1x;
    }
    for (int k = 1; k < ny; ++k)
    {
      cy[k] = cy[k - 1] * c1y - sy[k - 1] * s1y;
      sy[k] = sy[k - 1] * c1y + cy[k - 1] * s1y;
    }
    // d/dx cos(i pi x) = -i pi sin(i pi x), d2/dx2 = -(i pi)^2 cos(i pi x). Products of a, i, j are per term.
    double v = 0.0, gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0;
    const Term* const begin = terms_.data () + term_begin_[p];
    const Term* const end = terms_.data () + term_begin_[p + 1];
    if (hessian)
      for (const Term* term = begin; term != end; ++term)
      {
        const double cc = term->coefficient * cx[term->i] * cy[term->j];
        v += cc;
        gx -= term->ai * sx[term->i] * cy[term->j];
        gy -= term->aj * cx[term->i] * sy[term->j];
        hxx -= term->ii * cc;
        hxy += term->aij * sx[term->i] * sy[term->j];
        hyy -= term->jj * cc;
      }
    else
      for (const Term* term = begin; term != end; ++term)
      {
        v += term->coefficient * cx[term->i] * cy[term->j];
        gx -= term->ai * sx[term->i] * cy[term->j];
        gy -= term->aj * cx[term->i] * sy[term->j];
      }
    // Chain rule of the half-period argument (t + 1) / 2: a factor 1/2 per derivative.
    const double pi = half_period_ ? 0.5 * M_PI : M_PI, pi2 = pi * pi;
    double value = v, gx_out = pi * gx, gy_out = pi * gy, hxx_out = pi2 * hxx, hxy_out = pi2 * hxy, hyy_out = pi2 * hyy;
    if (monomials_)
      CosineAtoms::addQuadric (&monomial_coefficients_[CosineAtoms::quadric_monomials * p], x, y, value, gx_out, gy_out, hxx_out,
                    hxy_out, hyy_out);
    HeightSample sample;
    sample.value = value;
    sample.gradient = Eigen::Vector2d (gx_out, gy_out);
    if (hessian)
      sample.hessian << hxx_out, hxy_out, hxy_out, hyy_out;
    return sample;
  }

  void
  PatchEvaluator::sampleBlock (std::size_t p, Block& block) const
  {
    if (cosine_)
    {
      cosineBlock (terms_.data () + term_begin_[p], terms_.data () + term_begin_[p + 1], count_x_[p], count_y_[p], half_period_,
                   monomials_ ? &monomial_coefficients_[CosineAtoms::quadric_monomials * p] : nullptr, block);
      return;
    }
    for (int b = 0; b < Block::size; ++b)
    {
      const HeightSample h = model_.evaluate (p, block.x[b], block.y[b]);
      block.value[b] = h.value;
      block.gx[b] = h.gradient.x ();
      block.gy[b] = h.gradient.y ();
      block.hxx[b] = h.hessian (0, 0);
      block.hxy[b] = h.hessian (0, 1);
      block.hyy[b] = h.hessian (1, 1);
    }
  }
} // namespace pcl_sparse
