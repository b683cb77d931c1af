#include <pcl_sparse/cloud/triangle_winding.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <utility>

namespace pcl_sparse
{
  namespace
  {
    /// > 0 when the triangle's geometric normal agrees with its corners' normals.
    double
    agreement (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
               const Eigen::Vector3i& t)
    {
      const Eigen::Vector3d& a = positions[t[0]];
      const Eigen::Vector3d area = (positions[t[1]] - a).cross (positions[t[2]] - a);
      return area.dot (normals[t[0]] + normals[t[1]] + normals[t[2]]);
    }
  } // namespace

  std::size_t
  windTrianglesLikeNormals (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
                            std::vector<Eigen::Vector3i>& triangles)
  {
    std::size_t reversed = 0;
    for (auto& t : triangles)
    {
      if (agreement (positions, normals, t) < 0.0)
      {
        std::swap (t[1], t[2]);
        ++reversed;
      }
    }
    return reversed;
  }

  double
  imageFacing (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
               const std::vector<Eigen::Vector3i>& triangles)
  {
    std::size_t against = 0;
    for (const auto& t : triangles)
      against += agreement (positions, normals, t) < 0.0 ? 1 : 0;
    return 2 * against > triangles.size () ? -1.0 : 1.0;
  }

  std::size_t
  windImageTrianglesLikeNormals (const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<Eigen::Vector3d>& normals, std::vector<Eigen::Vector3i>& triangles)
  {
    if (imageFacing (positions, normals, triangles) < 0.0)
      for (auto& t : triangles)
        std::swap (t[1], t[2]);
    const std::size_t before = triangles.size ();
    triangles.erase (std::remove_if (triangles.begin (), triangles.end (),
                                     [&] (const Eigen::Vector3i& t) { return !(agreement (positions, normals, t) > 0.0); }),
                     triangles.end ());
    return before - triangles.size ();
  }
} // namespace pcl_sparse
