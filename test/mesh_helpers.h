#pragma once
// Small queries on test meshes.

#include <pcl_sparse/mesh/triangle_mesh.h>

namespace pcl_sparse_test
{
  /// The vertex whose direction from the origin is most opposite to vertex \a v's (its antipode on a sphere
  /// about the origin).
  inline int
  antipodeOf (const pcl_sparse::TriangleMesh& mesh, int v)
  {
    int antipode = 0;
    for (int u = 0; u < static_cast<int> (mesh.vertices.size ()); ++u)
      if (mesh.vertices[u].dot (mesh.vertices[v]) < mesh.vertices[antipode].dot (mesh.vertices[v]))
        antipode = u;
    return antipode;
  }
} // namespace pcl_sparse_test
