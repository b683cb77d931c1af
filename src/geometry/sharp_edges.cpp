#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/geometry/sharp_edges.h>
#include <pcl_sparse/mesh/mesh_normals.h>

#include <cmath>

namespace pcl_sparse
{
  std::vector<int>
  findSharpEdges (const TriangleMesh& mesh, const MeshTopology& topology, double min_degrees)
  {
    const std::vector<Eigen::Vector3d> normals = computeFaceNormals (mesh);
    // The two faces of each manifold edge (face_neighbors only links across manifold edges).
    std::vector<int> first_face (topology.numEdges (), -1), second_face (topology.numEdges (), -1);
    for (int f = 0; f < static_cast<int> (mesh.numTriangles ()); ++f)
      for (int k = 0; k < 3; ++k)
      {
        const int e = topology.face_edges[f][k];
        if (e < 0 || topology.edge_face_count[e] != 2)
          continue;
        (first_face[e] < 0 ? first_face[e] : second_face[e]) = f;
      }
    const double cos_limit = std::cos (min_degrees * M_PI / 180.0);
    std::vector<int> sharp;
    for (int e = 0; e < static_cast<int> (topology.numEdges ()); ++e)
    {
      if (second_face[e] < 0)
        continue;
      const Eigen::Vector3d& a = normals[first_face[e]];
      const Eigen::Vector3d& b = normals[second_face[e]];
      if (a.squaredNorm () > 0.0 && b.squaredNorm () > 0.0 && a.dot (b) < cos_limit)
        sharp.push_back (e);
    }
    return sharp;
  }

  std::vector<bool>
  verticesNearSharpEdges (const TriangleMesh& mesh, const MeshTopology& topology, double min_degrees, int rings)
  {
    std::vector<bool> near (mesh.numVertices (), false);
    VertexMarks marks (mesh.numVertices ());
    std::vector<int> hood;
    for (int e : findSharpEdges (mesh, topology, min_degrees))
      for (int end : {topology.edges[e][0], topology.edges[e][1]})
      {
        collectKRing (topology, end, rings, marks, hood);
        for (int u : hood)
          near[u] = true;
      }
    return near;
  }
} // namespace pcl_sparse
