#pragma once
/// \file cosine_atoms.h
/// Separable cosine atoms phi_ij(x, y) = cos(i pi s(x)) cos(j pi s(y)) on [-1, 1]^2, i, j = 0 .. n-1, with
/// s(t) = t (the paper's dictionary, docs/METHOD.md step 8) or s(t) = (t + 1) / 2 (DCT-II-like half-period
/// atoms, both parities). Shared evaluation of CosineDictionary and DctCosineDictionary; use those.

#include <pcl_sparse/model/surface_basis.h>

#include <cstdint>
#include <string>

namespace pcl_sparse
{
  /// Which cosine atoms a basis uses.
  enum class CosineBasisKind
  {
    Paper,  ///< cos(i pi x) cos(j pi y): even in x and y only (the paper's dictionary, the default)
    Dct,    ///< cos(i pi (x + 1) / 2) cos(j pi (y + 1) / 2): even and odd parts (our option)
    /// The Dct atoms and the five monomials x, y, x^2, x y, y^2 after them (ours, the default): with the
    /// constant atom they span every quadric, which cosines reach only slowly (a paraboloid needs about 12
    /// cosines for 2 % of its height; the quadric codes a sphere's cap to 0.05 % with 6 atoms).
    DctQuadric
  };

  /// Atom index = i * n + j for frequencies (i, j): atom 0 is the constant, atom j varies along y only,
  /// atom i * n varies along x only. DctQuadric adds atoms n^2 .. n^2 + 4: x, y, x^2, x y, y^2. Wavelength of atom (i, j) is 2 / max(i, j) for Paper and
  /// 4 / max(i, j) for Dct (+infinity for (0, 0)).
  ///
  /// Evaluation never calls cos per atom: cos(k pi s) and sin(k pi s) for all k come from one sin/cos
  /// pair per coordinate and the angle-addition (Chebyshev) recurrence, which is accurate to a few ulp
  /// for the small k used here. Derivatives carry the chain-rule factor ds/dt (1 or 1/2).
  class CosineAtoms : public SurfaceBasis
  {
  public:
    using Ptr = std::shared_ptr<CosineAtoms>;
    using ConstPtr = std::shared_ptr<const CosineAtoms>;

    /// Largest supported \a frequencies (n); a code evaluation keeps its tables on the stack.
    static constexpr int max_frequencies = 64;

    /// The atoms' kind (Paper or Dct).
    CosineBasisKind kind () const { return kind_; }
    /// n, the number of frequencies per axis.
    int frequencies () const { return n_; }
    /// Atom index i n + j of the frequencies (\a i, \a j).
    int atomIndex (int i, int j) const { return i * n_ + j; }
    /// Frequency along x (i) of \a atom.
    int frequencyX (int atom) const { return atom / n_; }
    /// Frequency along y (j) of \a atom.
    int frequencyY (int atom) const { return atom % n_; }

    /// DctQuadric's monomials: x, y, x^2, x y, y^2.
    static constexpr int quadric_monomials = 5;
    /// Number of monomial atoms after the cosines: quadric_monomials for DctQuadric, else 0.
    int monomials () const { return monomials_; }
    /// Whether \a atom is a monomial (DctQuadric's atoms from n^2 on).
    bool isMonomial (int atom) const { return atom >= n_ * n_; }
    /// Whether atoms 0 .. n^2 - 1 are \a other's, function for function (DctQuadric's cosines are Dct's).
    bool
    sameCosines (const CosineAtoms& other) const
    {
      return n_ == other.n_ && scale_ == other.scale_ && shift_ == other.shift_;
    }
    /// Exponents (p, q), x^p y^q, of monomial \a monomial (0 .. 4: atom n^2 + monomial).
    static void monomialExponents (int monomial, int& p, int& q);

    /// The quadric's five coefficients m (of x, y, x^2, x y, y^2) in a code: each monomial atom's coefficient
    /// added to its slot, the others 0.
    /// \return whether the code has a monomial atom
    bool quadricCoefficients (const std::vector<int>& atoms, const std::vector<double>& coefficients, double* m) const;

    /// m[0] x + m[1] y + m[2] x^2 + m[3] x y + m[4] y^2.
    static double
    quadricValue (const double* m, double x, double y)
    {
      return m[0] * x + m[1] * y + m[2] * x * x + m[3] * x * y + m[4] * y * y;
    }

    /// Adds quadricValue and its gradient and Hessian (h_xy once) to a sample's parts.
    static void
    addQuadric (const double* m, double x, double y, double& value, double& gx, double& gy, double& hxx, double& hxy,
                double& hyy)
    {
      value += quadricValue (m, x, y);
      gx += m[0] + 2.0 * m[2] * x + m[3] * y;
      gy += m[1] + m[3] * x + 2.0 * m[4] * y;
      hxx += 2.0 * m[2];
      hxy += m[3];
      hyy += 2.0 * m[4];
    }

    /// n^2 cosine atoms, then the monomials.
    int size () const override { return n_ * n_ + monomials_; }
    /// 2 / max(i, j) (Paper) or 4 / max(i, j) (Dct) for atom (i, j); +infinity for the constant atom and
    /// the monomials.
    double wavelength (int atom) const override;
    /// 1 for a cosine (bounded everywhere); half_width^(p + q) for the monomial x^p y^q.
    double atomBound (int atom, double half_width) const override;

    /// Values of every atom at every point.
    /// \param[in]  points  #points local positions (x, y)
    /// \param[out] values  #points by n^2; column atomIndex (i, j) holds phi_ij
    void evaluate (const std::vector<Eigen::Vector2d>& points, Eigen::MatrixXd& values) const override;

    /// Values of some atoms only (cost proportional to their number).
    /// \param[in]  points  #points local positions (x, y)
    /// \param[in]  atoms   atom indices
    /// \param[out] values  #points by atoms.size (); column k holds atom atoms[k]
    void evaluate (const std::vector<Eigen::Vector2d>& points, const std::vector<int>& atoms,
                   Eigen::MatrixXd& values) const override;

    /// Value, gradient and Hessian of a code, with analytic derivatives.
    /// \param[in] atoms         atom indices
    /// \param[in] coefficients  one per atom
    /// \param[in] x, y          local position
    /// \return sum_k coefficients[k] phi_{atoms[k]} (x, y) and its derivatives
    HeightSample evaluateCode (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                               double x, double y) const override;

    /// Value only of a code (one cos per axis and the Chebyshev recurrence).
    /// \param[in] atoms         atom indices
    /// \param[in] coefficients  one per atom
    /// \param[in] x, y          local position
    /// \return sum_k coefficients[k] phi_{atoms[k]} (x, y)
    double evaluateCodeValue (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                              double x, double y) const override;

    /// The atoms' factors along each axis at \a points: cx (p, k) = cos(k pi s(x_p)) and cy (p, k) =
    /// cos(k pi s(y_p)) for k = 0 .. count - 1 (CosineGram needs the sums of two frequencies too).
    /// \param[in]  points  #points local positions (x, y)
    /// \param[in]  count   factors per axis, in 1 .. 2 max_frequencies
    /// \param[out] cx, cy  #points by count
    /// \throws pcl_sparse::Error if \a count is out of range
    void axisCosines (const std::vector<Eigen::Vector2d>& points, int count, Eigen::MatrixXd& cx,
                      Eigen::MatrixXd& cy) const;

  protected:
    /// Tables for n frequencies per axis of the given kind.
    /// \param[in] frequencies  n, in 1 .. max_frequencies
    /// \param[in] kind         Paper or Dct atoms
    /// \throws pcl_sparse::Error if \a frequencies is out of range
    CosineAtoms (int frequencies, CosineBasisKind kind);

  private:
    HeightSample evaluateLongCode (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                   double x, double y) const;

    /// s(t) = scale_ * t + shift_; exactly t for Paper, so the paper's atoms stay bit for bit the same.
    double argument (double t) const { return scale_ * t + shift_; }

    int n_;
    CosineBasisKind kind_;
    int monomials_;
    double scale_;  ///< ds/dt: 1 (Paper) or 1/2 (Dct)
    double shift_;  ///< 0 (Paper) or 1/2 (Dct)
    std::vector<std::uint8_t> frequency_x_;  ///< i of each atom (avoids integer division in the hot path)
    std::vector<std::uint8_t> frequency_y_;  ///< j of each atom
  };

  /// A cosine basis of the given kind.
  /// \param[in] kind         Paper (CosineDictionary) or Dct (DctCosineDictionary)
  /// \param[in] frequencies  n, frequencies per axis (n^2 atoms)
  /// \return the basis
  /// \throws pcl_sparse::Error if \a frequencies is out of range
  CosineAtoms::ConstPtr
  makeCosineBasis (CosineBasisKind kind, int frequencies = 12);

  /// Name of a basis kind, as the tools' -basis option takes it.
  /// \param[in] kind  the kind
  /// \return "paper" or "dct"
  const char*
  cosineBasisKindName (CosineBasisKind kind);

  /// The basis kind of a name, as the tools' -basis option takes it.
  /// \param[in] name  "paper" or "dct"
  /// \return the kind
  /// \throws pcl_sparse::Error naming \a name if it is neither
  CosineBasisKind
  cosineBasisKindFromName (const std::string& name);
} // namespace pcl_sparse
