#include <pcl_sparse/model/sparse_surface_model.h>

#include <cmath>

namespace pcl_sparse
{
  double
  PatchFootprint::extentAt (double angle) const
  {
    const int k = static_cast<int> (extent.size ());
    if (k == 0)
      return 0.0;
    double t = angle / (2.0 * M_PI);
    t -= std::floor (t);
    const double position = t * k;
    const int i = static_cast<int> (position) % k;
    const double w = position - std::floor (position);
    return (1.0 - w) * extent[i] + w * extent[(i + 1) % k];
  }

  bool
  PatchFootprint::contains (double x, double y) const
  {
    const double r = std::hypot (x, y);
    return r <= extentAt (std::atan2 (y, x));
  }

  std::size_t
  SparseSurfaceModel::numNonZeros () const
  {
    std::size_t nnz = 0;
    for (const auto& p : patches)
      nnz += p.atoms.size ();
    return nnz;
  }

  HeightSample
  SparseSurfaceModel::evaluate (std::size_t p, double x, double y) const
  {
    const PatchCode& code = patches[p];
    return basis->evaluateCode (code.atoms, code.coefficients, x, y);
  }
} // namespace pcl_sparse
