#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/sub_mesh.h>

namespace pcl_sparse
{
  TriangleMesh
  extractSubMesh (const TriangleMesh& mesh, const std::vector<int>& indices, const std::string& what)
  {
    std::vector<int> position (mesh.vertices.size (), -1);
    TriangleMesh sub;
    sub.vertices.reserve (indices.size ());
    for (std::size_t i = 0; i < indices.size (); ++i)
    {
      const int v = indices[i];
      if (v < 0 || static_cast<std::size_t> (v) >= mesh.vertices.size ())
        throw Error (what + ": index " + std::to_string (v) + " out of range (" + std::to_string (mesh.vertices.size ()) +
                     " points)");
      if (position[v] >= 0)
        throw Error (what + ": index " + std::to_string (v) + " is listed twice");
      position[v] = static_cast<int> (i);
      sub.vertices.push_back (mesh.vertices[v]);
    }
    for (const Eigen::Vector3i& t : mesh.triangles)
    {
      const Eigen::Vector3i s (position[t[0]], position[t[1]], position[t[2]]);
      if (s.minCoeff () >= 0)
        sub.triangles.push_back (s);
    }
    return sub;
  }
} // namespace pcl_sparse
