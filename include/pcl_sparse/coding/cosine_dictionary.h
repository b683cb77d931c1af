#pragma once
/// \file cosine_dictionary.h
/// The continuous cosine dictionary of METHOD.md step 8: atoms phi_ij(x, y) = cos(i pi x) cos(j pi y)
/// on [-1, 1]^2, i, j = 0 .. n-1 (n = 12 gives the paper's 144 atoms).

#include <pcl_sparse/coding/surface_basis.h>

#include <cstdint>

namespace pcl_sparse
{
  /// Atom index = i * n + j for frequencies (i, j): atom 0 is the constant, atom j varies along y only,
  /// atom i * n varies along x only. Wavelength of atom (i, j) is 2 / max(i, j) (+infinity for (0, 0)).
  ///
  /// Evaluation never calls cos per atom: cos(k pi x) and sin(k pi x) for all k come from one sin/cos
  /// pair per coordinate and the angle-addition (Chebyshev) recurrence, which is accurate to a few ulp
  /// for the small k used here.
  class CosineDictionary : public SurfaceBasis
  {
  public:
    using Ptr = std::shared_ptr<CosineDictionary>;
    using ConstPtr = std::shared_ptr<const CosineDictionary>;

    /// Largest supported \a frequencies (n); a code evaluation keeps its tables on the stack.
    static constexpr int max_frequencies = 64;

    /// \a frequencies = n, the number of frequencies per axis (1 .. max_frequencies); throws
    /// pcl_sparse::Error otherwise.
    explicit CosineDictionary (int frequencies = 12);

    /// n, the number of frequencies per axis.
    int frequencies () const { return n_; }
    /// Atom index of frequencies (i, j).
    int atomIndex (int i, int j) const { return i * n_ + j; }
    /// Frequency along x (i) of \a atom.
    int frequencyX (int atom) const { return atom / n_; }
    /// Frequency along y (j) of \a atom.
    int frequencyY (int atom) const { return atom % n_; }

    int size () const override { return n_ * n_; }
    double wavelength (int atom) const override;

    /// \a values: #points by n^2, column atomIndex (i, j) = cos(i pi x) cos(j pi y).
    void evaluate (const std::vector<Eigen::Vector2d>& points, Eigen::MatrixXd& values) const override;

    /// Only the columns of \a atoms (cost proportional to their number).
    void evaluate (const std::vector<Eigen::Vector2d>& points, const std::vector<int>& atoms,
                   Eigen::MatrixXd& values) const override;

    HeightSample evaluateCode (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                               double x, double y) const override;

    /// Value only (one cos per axis and the Chebyshev recurrence).
    double evaluateCodeValue (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                              double x, double y) const override;

  private:
    HeightSample evaluateLongCode (const std::vector<int>& atoms, const std::vector<double>& coefficients,
                                   double x, double y) const;

    int n_;
    std::vector<std::uint8_t> frequency_x_;  ///< i of each atom (avoids integer division in the hot path)
    std::vector<std::uint8_t> frequency_y_;  ///< j of each atom
  };
} // namespace pcl_sparse
