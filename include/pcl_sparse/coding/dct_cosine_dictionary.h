#pragma once
/// \file dct_cosine_dictionary.h
/// DCT-II-like half-period cosine atoms phi_ij(x, y) = cos(i pi (x + 1) / 2) cos(j pi (y + 1) / 2) on
/// [-1, 1]^2, i, j = 0 .. n-1: the same n^2 atoms as the paper's CosineDictionary, but odd i (j) give
/// functions odd in x (y), so tilts, cubic terms and off-centre features are representable. Not in the
/// paper (an option of ours: SparseSurfaceEncoderOptions::basis, pcl_sparse_encode -basis dct).
///
/// It is deliberately not a CosineDictionary (which is the paper's atoms only); code with tables for cosine
/// atoms takes any CosineAtoms and reads its kind (PatchEvaluator).

#include <pcl_sparse/coding/cosine_atoms.h>

namespace pcl_sparse
{
  /// Atom layout as CosineDictionary (index i * n + j); wavelength of atom (i, j) is 4 / max(i, j),
  /// which the Nyquist cap reads through wavelength().
  class DctCosineDictionary : public CosineAtoms
  {
  public:
    using Ptr = std::shared_ptr<DctCosineDictionary>;
    using ConstPtr = std::shared_ptr<const DctCosineDictionary>;

    /// Half-period atoms with n frequencies per axis.
    /// \param[in] frequencies  n, in 1 .. max_frequencies
    /// \throws pcl_sparse::Error if \a frequencies is out of range
    explicit DctCosineDictionary (int frequencies = 12) : CosineAtoms (frequencies, CosineBasisKind::Dct) {}
  };

  /// The half-period atoms and, after them, the monomials x, y, x^2, x y, y^2 (atoms n^2 .. n^2 + 4; their
  /// wavelength is infinite, so the Nyquist cap allows them everywhere). With the constant atom they span
  /// the quadrics: a curved patch's bulk in six atoms, the cosines left for what a quadric misses. The
  /// patch coder selects them first (SparseCodingOptions). Ours, the encoder's default.
  class QuadricDctDictionary : public CosineAtoms
  {
  public:
    using Ptr = std::shared_ptr<QuadricDctDictionary>;
    using ConstPtr = std::shared_ptr<const QuadricDctDictionary>;

    /// Half-period atoms with n frequencies per axis, then the five monomials.
    /// \param[in] frequencies  n, in 1 .. max_frequencies
    /// \throws pcl_sparse::Error if \a frequencies is out of range
    explicit QuadricDctDictionary (int frequencies = 12) : CosineAtoms (frequencies, CosineBasisKind::DctQuadric) {}
  };
} // namespace pcl_sparse
