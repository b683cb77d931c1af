#pragma once
/// \file cosine_dictionary.h
/// The continuous cosine dictionary of docs/METHOD.md step 8: atoms phi_ij(x, y) = cos(i pi x) cos(j pi y)
/// on [-1, 1]^2, i, j = 0 .. n-1 (n = 12 gives the paper's 144 atoms). This is the default basis
/// everywhere. Every atom is even in x and in y, so the odd part of a patch's height (cubic terms,
/// off-centre features) cannot be represented; DctCosineDictionary (dct_cosine_dictionary.h) is the
/// option with both parities and the same atom count.

#include <pcl_sparse/coding/cosine_atoms.h>

namespace pcl_sparse
{
  /// Atom layout, wavelengths (2 / max(i, j)) and evaluation: see CosineAtoms.
  class CosineDictionary : public CosineAtoms
  {
  public:
    using Ptr = std::shared_ptr<CosineDictionary>;
    using ConstPtr = std::shared_ptr<const CosineDictionary>;

    /// The paper's atoms with n frequencies per axis.
    /// \param[in] frequencies  n, in 1 .. max_frequencies (12: the paper's 144 atoms)
    /// \throws pcl_sparse::Error if \a frequencies is out of range
    explicit CosineDictionary (int frequencies = 12) : CosineAtoms (frequencies, CosineBasisKind::Paper) {}
  };
} // namespace pcl_sparse
