#pragma once
/// \file cosine_gram.h
/// The Gram matrix D^T D of separable cosine atoms at a patch's samples, column by column, without the
/// #P-long dot products (ours). On each axis cos(a u) cos(b u) = (cos((a + b) u) + cos((a - b) u)) / 2, so
/// the inner product of atoms (i, j) and (k, l) over the samples is a quarter of four sums
///   S(u, v) = sum_p cos(u pi s(x_p)) cos(v pi s(y_p)),  u in {i + k, |i - k|}, v in {j + l, |j - l|},
/// and the (2 n - 1)^2 sums S are one #P-long matrix product. Batch OMP (batchOrthogonalMatchingPursuit)
/// then forms a Gram column in O(K) instead of O(#P K): a colour patch's channels choose about 18 atoms
/// over some 170 samples, whose Gram columns were most of colour coding's time.
#include <pcl_sparse/coding/cosine_atoms.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// \brief Columns of D^T D for D = the given cosine atoms evaluated at the given points (CosineAtoms::evaluate).
  class CosineGram
  {
  public:
    /// \param[in] basis   the atoms' basis (any kind; only its cosine atoms can be listed)
    /// \param[in] points  #P local positions (x, y), the rows of D
    /// \param[in] atoms   K cosine atom indices (< n^2), the columns of D
    /// \throws pcl_sparse::Error if an atom is a monomial or out of range
    CosineGram (const CosineAtoms& basis, const std::vector<Eigen::Vector2d>& points, const std::vector<int>& atoms);

    /// \brief Column \a k of D^T D: values[j] = sum_p d_j(p) d_k(p) for j = 0 .. K - 1.
    /// \param[in]  k       column, 0 .. K - 1
    /// \param[out] values  K entries, equal to D^T d_k up to round-off (a few ulp of the sums' size)
    void column (int k, Eigen::Ref<Eigen::VectorXd> values) const;

    /// Number of atoms K.
    int size () const { return static_cast<int> (frequency_x_.size ()); }

  private:
    std::vector<int> frequency_x_, frequency_y_;  ///< (i, j) of each listed atom
    Eigen::MatrixXd sums_;                        ///< S (u, v), u < 2 max i + 1, v < 2 max j + 1
  };
} // namespace pcl_sparse
