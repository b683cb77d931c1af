#pragma once
/// \file surface_basis.h
/// A basis of height functions h(x, y) on the patch square [-1, 1]^2 (docs/METHOD.md step 8).
/// OMP, the model and resampling talk to atoms only through this interface, so other bases
/// (polynomials, learned atoms) can be added without touching them.

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  /// Value, gradient and Hessian of a height function at one point.
  struct HeightSample
  {
    double value = 0.0;
    Eigen::Vector2d gradient = Eigen::Vector2d::Zero ();  ///< (h_x, h_y)
    Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero ();   ///< [[h_xx, h_xy], [h_xy, h_yy]]
  };

  class SurfaceBasis
  {
  public:
    using Ptr = std::shared_ptr<SurfaceBasis>;
    using ConstPtr = std::shared_ptr<const SurfaceBasis>;

    virtual ~SurfaceBasis () = default;

    /// Number of atoms.
    virtual int size () const = 0;

    /// Shortest wavelength of atom \a atom in local units (2 / max(i, j) for the paper's cosines,
    /// 4 / max(i, j) for the half-period ones), +infinity for a constant atom. The Nyquist cap of OMP compares it with the patch's sample spacing.
    virtual double wavelength (int atom) const = 0;

    /// Largest |value| of atom \a atom over the square |x|, |y| <= \a half_width (local units): what bounds
    /// a code's height (PatchCode::heightBound). A basis that knows none gives +infinity (the default).
    virtual double
    atomBound (int atom, double half_width) const
    {
      (void) atom;
      (void) half_width;
      return std::numeric_limits<double>::infinity ();
    }

    /// Values of every atom at every point: \a values is #points by size().
    virtual void evaluate (const std::vector<Eigen::Vector2d>& points, Eigen::MatrixXd& values) const = 0;

    /// Values of the atoms listed in \a atoms only: \a values is #points by atoms.size(), column k holding
    /// atom atoms[k]. Override when cheaper than the full matrix.
    virtual void evaluate (const std::vector<Eigen::Vector2d>& points, const std::vector<int>& atoms,
                           Eigen::MatrixXd& values) const
    {
      Eigen::MatrixXd all;
      evaluate (points, all);
      values.resize (all.rows (), static_cast<Eigen::Index> (atoms.size ()));
      for (std::size_t k = 0; k < atoms.size (); ++k)
        values.col (static_cast<Eigen::Index> (k)) = all.col (atoms[k]);
    }

    /// sum_k coefficients[k] * atom_{atoms[k]} at (x, y), with analytic derivatives.
    virtual HeightSample evaluateCode (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                       double x, double y) const = 0;

    /// Value only of the code at (x, y); override when it is cheaper than evaluateCode.
    virtual double evaluateCodeValue (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                      double x, double y) const
    {
      return evaluateCode (atoms, coefficients, x, y).value;
    }
  };
} // namespace pcl_sparse
