#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/mesh/bounding_box.h>

#include <cmath>
#include <limits>

namespace pcl_sparse
{
  std::vector<Eigen::Vector3d>
  worldPositions (const ScanCloud& scan)
  {
    std::vector<Eigen::Vector3d> world (scan.positions.size ());
    for (std::size_t i = 0; i < world.size (); ++i)
      world[i] = scan.origin + scan.positions[i];
    return world;
  }

  Eigen::Vector3d
  localFrameOrigin (const std::vector<Eigen::Vector3d>& world_positions)
  {
    return localFrameOriginOfBox (finiteBoundingBox (world_positions));
  }

  Eigen::Vector3d
  localFrameOriginOfBox (const Eigen::AlignedBox3d& box)
  {
    if (box.isEmpty ())
      return Eigen::Vector3d::Zero ();
    const Eigen::Vector3d& lo = box.min ();
    const Eigen::Vector3d& hi = box.max ();
    const double extent = (hi - lo).maxCoeff ();
    if (!std::isfinite (extent))
      return Eigen::Vector3d::Zero ();  // a box wider than DBL_MAX: no frame makes it smaller
    if (!(extent > 0.0))
      return lo;  // one position: it is the origin, every local position is exactly 0
    // Half the sum overflows for boxes near DBL_MAX; halves first.
    const Eigen::Vector3d centre = 0.5 * lo + 0.5 * hi;
    const double step = std::ldexp (1.0, std::ilogb (extent) + 1 - 8);  // a power of two in (extent/256, extent/128]
    Eigen::Vector3d origin;
    for (int k = 0; k < 3; ++k)
      origin[k] = std::abs (centre[k]) <= 2.0 * extent ? 0.0 : std::round (centre[k] / step) * step;
    return origin;
  }

  void
  centreScan (ScanCloud& scan)
  {
    std::vector<Eigen::Vector3d> world = worldPositions (scan);
    const Eigen::Vector3d origin = localFrameOrigin (world);
    for (std::size_t i = 0; i < world.size (); ++i)
      scan.positions[i] = world[i] - origin;
    scan.origin = origin;
  }
} // namespace pcl_sparse
