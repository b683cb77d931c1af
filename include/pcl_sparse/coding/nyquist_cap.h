#pragma once
/// \file nyquist_cap.h
/// Which atoms a patch may use given its sample spacing (docs/METHOD.md step 9): atoms oscillating faster
/// than the mesh samples them only fit noise and make the surface ripple between the vertices.

#include <pcl_sparse/model/surface_basis.h>

#include <vector>

namespace pcl_sparse
{
  /// The two published forms of the cap.
  enum class NyquistRule
  {
    Paper,       ///< allowed iff lambda / 2 > f mu (the paper; default)
    AuthorsCode  ///< allowed iff lambda >= f mu (larc/gproshan src/mdict: a factor 2 looser)
  };

  /// Whether an atom passes the Nyquist cap.
  /// \param[in] wavelength  lambda, the atom's shortest wavelength in local units (SurfaceBasis::wavelength)
  /// \param[in] spacing     mu, the patch's sample spacing in local units (patchSampleSpacing)
  /// \param[in] factor      f in [0, 1]; 0 allows every atom (plain OMP)
  /// \param[in] rule        the paper's or the authors' form of the cap
  /// \return true if the atom may be selected
  inline bool
  passesNyquistCap (double wavelength, double spacing, double factor, NyquistRule rule)
  {
    if (factor <= 0.0)
      return true;
    return rule == NyquistRule::Paper ? wavelength / 2.0 > factor * spacing : wavelength >= factor * spacing;
  }

  /// The Nyquist cap for every atom of a basis.
  /// \param[in] basis    the dictionary
  /// \param[in] spacing  mu, the patch's sample spacing in local units
  /// \param[in] factor   f in [0, 1]
  /// \param[in] rule     the paper's or the authors' form of the cap
  /// \return basis.size () flags, non-zero where passesNyquistCap holds
  inline std::vector<char>
  nyquistAllowedAtoms (const SurfaceBasis& basis, double spacing, double factor, NyquistRule rule)
  {
    std::vector<char> allowed (basis.size ());
    for (int k = 0; k < basis.size (); ++k)
      allowed[k] = passesNyquistCap (basis.wavelength (k), spacing, factor, rule);
    return allowed;
  }

  /// The indices of the non-zero flags, ascending: the atoms a patch's OMP runs over.
  /// \param[in] allowed  flags, as nyquistAllowedAtoms returns them
  /// \return the indices k with allowed[k] != 0
  inline std::vector<int>
  allowedAtomIndices (const std::vector<char>& allowed)
  {
    std::vector<int> atoms;
    for (int k = 0; k < static_cast<int> (allowed.size ()); ++k)
      if (allowed[k])
        atoms.push_back (k);
    return atoms;
  }
} // namespace pcl_sparse
