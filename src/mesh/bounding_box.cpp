#include <pcl_sparse/mesh/bounding_box.h>

#include <algorithm>
#include <limits>

namespace pcl_sparse
{
  Eigen::AlignedBox3d
  finiteBoundingBox (const std::vector<Eigen::Vector3d>& points)
  {
    Eigen::AlignedBox3d box;  // empty
    for (const Eigen::Vector3d& p : points)
      if (p.allFinite ())
        box.extend (p);
    return box;
  }

  double
  boundingBoxDiagonal (const std::vector<Eigen::Vector3d>& points)
  {
    const Eigen::AlignedBox3d box = finiteBoundingBox (points);
    return box.isEmpty () ? 0.0 : (box.max () - box.min ()).norm ();
  }

  double
  largestCoordinate (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin)
  {
    const Eigen::AlignedBox3d box = finiteBoundingBox (points);
    if (box.isEmpty ())
      return 0.0;
    return std::max ((box.min () + origin).cwiseAbs ().maxCoeff (), (box.max () + origin).cwiseAbs ().maxCoeff ());
  }

  double
  surfaceBoundingBoxDiagonal (const TriangleMesh& mesh)
  {
    Eigen::AlignedBox3d box;  // empty
    const long n = static_cast<long> (mesh.vertices.size ());
    for (const Eigen::Vector3i& t : mesh.triangles)
      if (t.minCoeff () >= 0 && t.maxCoeff () < n)
        for (int k = 0; k < 3; ++k)
          if (mesh.vertices[t[k]].allFinite ())
            box.extend (mesh.vertices[t[k]]);
    return box.isEmpty () ? 0.0 : (box.max () - box.min ()).norm ();
  }
} // namespace pcl_sparse
