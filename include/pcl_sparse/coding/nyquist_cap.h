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

  /// Whether an atom of wavelength \a wavelength passes the cap for sample spacing \a spacing (mu) and
  /// factor \a factor (f). f = 0 allows every atom (plain OMP).
  inline bool
  passesNyquistCap (double wavelength, double spacing, double factor, NyquistRule rule)
  {
    if (factor <= 0.0)
      return true;
    return rule == NyquistRule::Paper ? wavelength / 2.0 > factor * spacing : wavelength >= factor * spacing;
  }

  /// One flag per atom of \a basis: passesNyquistCap for its wavelength.
  inline std::vector<char>
  nyquistAllowedAtoms (const SurfaceBasis& basis, double spacing, double factor, NyquistRule rule)
  {
    std::vector<char> allowed (basis.size ());
    for (int k = 0; k < basis.size (); ++k)
      allowed[k] = passesNyquistCap (basis.wavelength (k), spacing, factor, rule);
    return allowed;
  }
} // namespace pcl_sparse
