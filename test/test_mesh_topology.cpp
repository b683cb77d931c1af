#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <algorithm>

using namespace pcl_sparse;

namespace
{
  int
  countEdges (const MeshTopology& topo, int faces_per_edge)
  {
    return static_cast<int> (std::count (topo.edge_face_count.begin (), topo.edge_face_count.end (), faces_per_edge));
  }

  int
  eulerCharacteristic (const TriangleMesh& mesh, const MeshTopology& topo)
  {
    return static_cast<int> (mesh.numVertices ()) - static_cast<int> (topo.numEdges ()) +
           static_cast<int> (mesh.numTriangles ());
  }
} // namespace

TEST (MeshTopology, TetrahedronIsClosedWithSixEdges)
{
  const TriangleMesh mesh = makeTetrahedron ();
  const MeshTopology topo = buildMeshTopology (mesh);
  EXPECT_EQ (topo.numEdges (), 6u);
  EXPECT_EQ (countEdges (topo, 2), 6);
  EXPECT_EQ (eulerCharacteristic (mesh, topo), 2);
  for (int v = 0; v < 4; ++v)
  {
    EXPECT_EQ (topo.facesOf (v).size (), 3u);
    EXPECT_EQ (topo.neighborsOf (v).size (), 3u);
  }
  for (const auto& fn : topo.face_neighbors)
    EXPECT_TRUE ((fn.array () >= 0).all ());
}

TEST (MeshTopology, CubeIsClosedGenusZero)
{
  const TriangleMesh mesh = makeCube (4);
  const MeshTopology topo = buildMeshTopology (mesh);
  EXPECT_EQ (mesh.numVertices (), 6u * 4 * 4 + 2);  // 6 n^2 + 2 for a welded cube
  EXPECT_EQ (countEdges (topo, 1), 0);
  EXPECT_EQ (countEdges (topo, 3), 0);
  EXPECT_EQ (eulerCharacteristic (mesh, topo), 2);
}

TEST (MeshTopology, DiskHasOneBoundaryLoop)
{
  const int rings = 5;
  const TriangleMesh mesh = makeDisk (rings);
  const MeshTopology topo = buildMeshTopology (mesh);
  EXPECT_EQ (countEdges (topo, 1), 6 * rings);  // the outer ring
  EXPECT_EQ (countEdges (topo, 3), 0);
  EXPECT_EQ (eulerCharacteristic (mesh, topo), 1);
  // Every face faces +z.
  for (const auto& n : computeFaceNormals (mesh))
    EXPECT_NEAR (n.z (), 1.0, 1e-12);
}

TEST (MeshTopology, TorusHasGenusOne)
{
  const TriangleMesh mesh = makeTorus (24, 12);
  const MeshTopology topo = buildMeshTopology (mesh);
  EXPECT_EQ (countEdges (topo, 1), 0);
  EXPECT_EQ (eulerCharacteristic (mesh, topo), 0);
}

TEST (MeshTopology, NonManifoldEdgeIsACut)
{
  // Three triangles sharing edge (0, 1).
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshTopology topo = buildMeshTopology (mesh);
  ASSERT_EQ (countEdges (topo, 3), 1);
  EXPECT_TRUE (topo.isNonManifoldEdge (topo.face_edges[0][0]));
  EXPECT_EQ (topo.face_neighbors[0][0], -1);
  EXPECT_EQ (topo.face_neighbors[1][0], -1);
}

TEST (MeshNormals, SphereVertexNormalsPointOutward)
{
  const TriangleMesh mesh = makeIcosphere (3, 2.0);
  const MeshTopology topo = buildMeshTopology (mesh);
  for (auto weighting : {NormalWeighting::Area, NormalWeighting::Angle})
  {
    const auto normals = computeVertexNormals (mesh, topo, weighting);
    double worst = 1.0;
    for (std::size_t v = 0; v < mesh.numVertices (); ++v)
      worst = std::min (worst, normals[v].dot (mesh.vertices[v].normalized ()));
    EXPECT_GT (worst, 0.999);
  }
}
