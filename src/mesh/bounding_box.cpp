#include <pcl_sparse/mesh/bounding_box.h>

#include <limits>

namespace pcl_sparse
{
  double
  boundingBoxDiagonal (const std::vector<Eigen::Vector3d>& points)
  {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant (std::numeric_limits<double>::infinity ());
    Eigen::Vector3d hi = -lo;
    bool any = false;
    for (const Eigen::Vector3d& p : points)
      if (p.allFinite ())
      {
        lo = lo.cwiseMin (p);
        hi = hi.cwiseMax (p);
        any = true;
      }
    return any ? (hi - lo).norm () : 0.0;
  }
} // namespace pcl_sparse
