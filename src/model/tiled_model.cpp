#include <pcl_sparse/model/tiled_model.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  std::vector<std::size_t>
  TiledModel::patchNumbers () const
  {
    std::vector<std::size_t> numbers;
    numbers.reserve (model.patches.size ());
    for (const TileRange& range : tiles)
      for (std::size_t i = 0; i < range.num_patches; ++i)
        numbers.push_back (range.first_patch + i);
    return numbers;
  }

  SparseSurfaceModel
  subModel (const SparseSurfaceModel& model, std::size_t first, std::size_t count)
  {
    SparseSurfaceModel sub;
    sub.basis = model.basis;
    sub.num_input_vertices = model.num_input_vertices;
    sub.bbox_diagonal = model.bbox_diagonal;
    sub.footprint_step = model.footprint_step;
    sub.attribute_channels = model.attribute_channels;
    sub.attribute_basis = model.attribute_basis;
    sub.patches.assign (model.patches.begin () + static_cast<std::ptrdiff_t> (first),
                        model.patches.begin () + static_cast<std::ptrdiff_t> (first + count));
    return sub;
  }

  Eigen::AlignedBox3d
  patchReachBox (const PatchCode& patch, const SurfaceBasis& basis)
  {
    const double extent = patch.footprint.largestExtent ();
    const double height = patch.heightBound (basis);
    // Surface points have |h| <= max_height (1 by default, PatchOwnershipOptions) where resampling keeps
    // them, and a place competed for lies within the height tolerance (0.1) of one: 0.25 covers it.
    const double z = std::min (height, 1.0) + 0.25;
    // The footprint's disk (radius extent in the tangent plane) plus a segment of +-z along the normal,
    // projected on each axis; a little more for the rounding of s + r R q.
    const Eigen::Vector3d n = patch.frame.col (2);
    Eigen::Vector3d half;
    for (int a = 0; a < 3; ++a)
      half[a] = patch.radius * (extent * std::sqrt (std::max (0.0, 1.0 - n[a] * n[a])) + z * std::abs (n[a]));
    half = half * (1.0 + 1e-9) + Eigen::Vector3d::Constant (1e-12 + 1e-9 * patch.origin.cwiseAbs ().maxCoeff ());
    return Eigen::AlignedBox3d (patch.origin - half, patch.origin + half);
  }
} // namespace pcl_sparse
