#include <pcl_sparse/mesh/bounding_box.h>

#include <algorithm>
#include <cstdint>
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
    // Each vertex once, not once per face using it (a scan's surface: 6 faces a vertex, random accesses).
    const long n = static_cast<long> (mesh.vertices.size ());
    std::vector<std::uint8_t> used (mesh.vertices.size (), 0);
    for (const Eigen::Vector3i& t : mesh.triangles)
      if (t.minCoeff () >= 0 && t.maxCoeff () < n)
        used[t[0]] = used[t[1]] = used[t[2]] = 1;
    Eigen::AlignedBox3d box;  // empty
    for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
      if (used[v] && mesh.vertices[v].allFinite ())
        box.extend (mesh.vertices[v]);
    return box.isEmpty () ? 0.0 : (box.max () - box.min ()).norm ();
  }
} // namespace pcl_sparse
