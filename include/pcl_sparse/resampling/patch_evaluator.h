#pragma once
/// \file patch_evaluator.h
/// Fast evaluation of a model's patches for resampling, which evaluates codes and footprints tens of
/// millions of times: frequencies of cosine atoms decoded once per patch (no integer division per atom,
/// no virtual call), footprint centrality with a polynomial atan2 (error below 1e-9 rad). Every cosine
/// basis (CosineAtoms: the paper's, the half-period one, and with the quadric's monomials) has these
/// tables; any other SurfaceBasis goes through SparseSurfaceModel::evaluate.

#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/model/surface_basis.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pcl_sparse
{
  /// Heights, derivatives and footprint tests of a model's patches, with per-patch tables.
  class PatchEvaluator
  {
  public:
    /// Builds the tables of a model.
    /// \param[in] model  the model; kept by reference, it must outlive the evaluator and not change
    explicit PatchEvaluator (const SparseSurfaceModel& model);

    /// The model evaluated.
    const SparseSurfaceModel& model () const { return model_; }

    /// Centrality of a local point in a patch's footprint.
    /// \param[in]  p     patch index
    /// \param[in]  x, y  local position in patch \a p
    /// \param[out] turn  the angle of (x, y) as a fraction of a full turn, in [0, 1)
    /// \return |(x, y)| / extent(angle): <= 1 inside the footprint (an empty footprint is the unit disk)
    double
    centrality (std::size_t p, double x, double y, double& turn) const
    {
      const std::size_t begin = extent_begin_[p], k = extent_begin_[p + 1] - begin;
      const double r = std::sqrt (x * x + y * y);
      turn = fastAtan2 (y, x) * (0.5 / M_PI);
      if (turn < 0.0)
        turn += 1.0;
      if (turn >= 1.0)
        turn = 0.0;
      if (k == 0)
        return r;
      if (r == 0.0)
        return 0.0;
      const double t = turn * static_cast<double> (k);
      std::size_t i = static_cast<std::size_t> (t);
      const double w = t - static_cast<double> (i);
      if (i >= k)
        i -= k;
      const std::size_t j = (i + 1 == k) ? 0 : i + 1;
      const double e = (1.0 - w) * extents_[begin + i] + w * extents_[begin + j];
      return e > 0.0 ? r / e : std::numeric_limits<double>::infinity ();
    }

    /// centrality (p, x, y, turn) without the angle.
    double
    centrality (std::size_t p, double x, double y) const
    {
      double turn;
      return centrality (p, x, y, turn);
    }

    /// Largest footprint extent of patch \a p (1 for an empty footprint).
    double maxExtent (std::size_t p) const { return max_extent_[p]; }

    /// Height h(x, y) of patch \a p.
    double height (std::size_t p, double x, double y) const;
    /// Height, gradient and Hessian of a patch; equal to SparseSurfaceModel::evaluate up to round-off.
    /// \param[in] p        patch index
    /// \param[in] x, y     local position
    /// \param[in] hessian  false leaves the Hessian zero (value and gradient are the same bits either
    ///                     way): validity tests need only the gradient
    /// \return the height sample
    HeightSample sample (std::size_t p, double x, double y, bool hessian = true) const;

    /// Height samples of a block of places of one patch in structure-of-arrays form, so the atoms are
    /// evaluated for the whole block at once (vectorised); also holds the per-frequency tables, kept
    /// across blocks so that evaluation does not allocate.
    struct Block
    {
      /// Places per block: enough to fill the vector lanes, small enough to stay in L1.
      static constexpr int size = 32;
      double x[size] = {}, y[size] = {};  ///< input: local positions (unused lanes are evaluated too)
      double value[size], gx[size], gy[size], hxx[size], hxy[size], hyy[size];  ///< output
      std::vector<double> tables;  ///< cos / sin of k pi x and k pi y per frequency k, lane-minor

      /// The sample of lane \a b, equal bit for bit to PatchEvaluator::sample at (x[b], y[b]).
      /// \param[in] b  lane
      /// \return the height sample with the Hessian
      HeightSample
      sample (int b) const
      {
        HeightSample h;
        h.value = value[b];
        h.gradient = Eigen::Vector2d (gx[b], gy[b]);
        h.hessian << hxx[b], hxy[b], hxy[b], hyy[b];
        return h;
      }
    };

    /// sample (p, x, y) with the Hessian for every lane of \a block, with the same rounding.
    /// \param[in]     p      patch index
    /// \param[in,out] block  places in, samples out
    void sampleBlock (std::size_t p, Block& block) const;

    /// atan2 with absolute error below 1e-9 rad: octant reduction, atan(a) = pi/6 + atan((sqrt(3) a - 1) /
    /// (a + sqrt(3))) above tan(pi/12), then the Taylor series to z^15.
    static double
    fastAtan2 (double y, double x)
    {
      const double ax = std::abs (x), ay = std::abs (y);
      const double high = std::max (ax, ay);
      if (high == 0.0)
        return 0.0;
      double z = std::min (ax, ay) / high, offset = 0.0;
      if (z > 0.2679491924311227)
      {
        z = (z * 1.7320508075688772 - 1.0) / (z + 1.7320508075688772);
        offset = M_PI / 6.0;
      }
      const double z2 = z * z;
      double r = offset + z * (1.0 + z2 * (-1.0 / 3.0 + z2 * (1.0 / 5.0 + z2 * (-1.0 / 7.0 + z2 * (1.0 / 9.0 + z2 * (-1.0 / 11.0 +
                 z2 * (1.0 / 13.0 - z2 / 15.0)))))));
      if (ay > ax)
        r = 0.5 * M_PI - r;
      if (x < 0.0)
        r = M_PI - r;
      return y < 0.0 ? -r : r;
    }

    /// One cosine atom of a code, with the products its derivatives need.
    struct Term
    {
      int i, j;  ///< frequencies along x and y
      double coefficient;
      double ai, aj, aij, ii, jj;  ///< a i, a j, a i j, i^2, j^2 (a the coefficient), for the derivatives
    };

  private:

    const SparseSurfaceModel& model_;
    bool cosine_ = false;       ///< a cosine basis (CosineAtoms): the tables below
    bool half_period_ = false;  ///< its atoms are cos(k pi (t + 1) / 2) (Dct, DctQuadric), not cos(k pi t)
    bool monomials_ = false;    ///< it has the quadric's monomials (DctQuadric)
    std::vector<double> monomial_coefficients_;  ///< DctQuadric: 5 per patch, x y x^2 xy y^2 (0 if absent)
    std::vector<Term> terms_;
    std::vector<std::size_t> term_begin_;  ///< #patches + 1 offsets into terms_
    std::vector<int> count_x_, count_y_;   ///< highest frequency + 1 per axis, per patch
    std::vector<float> extents_;
    std::vector<std::size_t> extent_begin_;  ///< #patches + 1 offsets into extents_
    std::vector<double> max_extent_;
  };
} // namespace pcl_sparse
