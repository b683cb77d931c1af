#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/geometry/vertex_curvature.h>

#include <cstdint>
#include <limits>

namespace pcl_sparse
{
  std::vector<MongeJet>
  computeVertexMongeJets (const TriangleMesh& mesh, const MeshTopology& topology,
                          const std::vector<Eigen::Vector3d>& normals, int rings)
  {
    const std::size_t n = mesh.numVertices ();
    if (topology.numVertices () != n || normals.size () != n)
      throw Error ("computeVertexMongeJets: mesh, topology and normals disagree on the vertex count");
    if (rings < 1)
      throw Error ("computeVertexMongeJets: rings must be >= 1");
    MongeJet failed;
    failed.k1 = failed.k2 = std::numeric_limits<double>::quiet_NaN ();
    std::vector<MongeJet> jets (n, failed);
#pragma omp parallel
    {
      VertexMarks marks (n);
      std::vector<int> hood;
      std::vector<Eigen::Vector3d> points;
#pragma omp for schedule(dynamic, 256)
      for (std::int64_t i = 0; i < static_cast<std::int64_t> (n); ++i)
      {
        const int v = static_cast<int> (i);
        if (!(normals[v].squaredNorm () > 0.0))
          continue;
        collectKRing (topology, v, rings, marks, hood);
        points.clear ();
        for (int u : hood)
          points.push_back (mesh.vertices[u]);
        MongeJet jet;
        if (fitMongeJet (points, mesh.vertices[v], normals[v], jet))
          jets[v] = jet;
      }
    }
    return jets;
  }
} // namespace pcl_sparse
