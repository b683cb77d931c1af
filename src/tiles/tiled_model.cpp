#include <pcl_sparse/tiles/tiled_model.h>

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
    sub.attribute_channels = model.attribute_channels;
    sub.attribute_basis = model.attribute_basis;
    sub.patches.assign (model.patches.begin () + static_cast<std::ptrdiff_t> (first),
                        model.patches.begin () + static_cast<std::ptrdiff_t> (first + count));
    return sub;
  }

  Eigen::AlignedBox3d
  patchReachBox (const PatchCode& patch)
  {
    double extent = 0.0;
    for (float e : patch.footprint.extent)
      extent = std::max (extent, static_cast<double> (e));
    double height = 0.0;
    for (double c : patch.coefficients)
      height += std::abs (c);
    // One local unit above and below the surface: the places resampling lets the patch compete for lie
    // within its height tolerance (0.1 by default) of it. A little more, for the rounding of s + r R q.
    height += 1.0;
    const double reach = patch.radius * std::sqrt (extent * extent + height * height) * (1.0 + 1e-9) + 1e-12;
    const Eigen::Vector3d r = Eigen::Vector3d::Constant (reach);
    return Eigen::AlignedBox3d (patch.origin - r, patch.origin + r);
  }
} // namespace pcl_sparse
