#include <pcl_sparse/mesh/mesh_components.h>

namespace pcl_sparse
{
  std::vector<int>
  faceComponentSizes (const TriangleMesh& mesh)
  {
    const std::size_t n = mesh.vertices.size ();
    DisjointSets components (n);
    std::vector<char> in_face (n, 0);
    for (const Eigen::Vector3i& t : mesh.triangles)
    {
      components.join (t[0], t[1]);
      components.join (t[1], t[2]);
      in_face[t[0]] = in_face[t[1]] = in_face[t[2]] = 1;
    }
    std::vector<int> count (n, 0), sizes (n, 0);
    for (std::size_t v = 0; v < n; ++v)
      if (in_face[v])
        ++count[components.find (static_cast<int> (v))];
    for (std::size_t v = 0; v < n; ++v)
      if (in_face[v])
        sizes[v] = count[components.find (static_cast<int> (v))];
    return sizes;
  }
} // namespace pcl_sparse
