#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

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
  // No face across the shared edge, for any of the three (its edge 0 is (0, 1) in each).
  for (int f = 0; f < 3; ++f)
    EXPECT_EQ (topo.face_neighbors[f][0], -1) << f;
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

TEST (MeshTopology, AdjacencyIsConsistentOnClosedAndOpenMeshes)
{
  TriangleMesh two_spheres = makeIcosphere (2);
  appendMesh (two_spheres, makeIcosphere (1, 1.0, Eigen::Vector3d (3, 0, 0)));
  // The large torus has enough vertices for buildMeshTopology to run in parallel.
  for (const TriangleMesh& mesh :
       {makeTetrahedron (), makeCube (3), makeDisk (4), makeTorus (16, 8), makeTorus (160, 64), two_spheres})
  {
    const MeshTopology topo = buildMeshTopology (mesh);
    const int num_faces = static_cast<int> (mesh.numTriangles ());
    for (int f = 0; f < num_faces; ++f)
      for (int k = 0; k < 3; ++k)
      {
        const int a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
        const int e = topo.face_edges[f][k];
        ASSERT_GE (e, 0);
        EXPECT_EQ (topo.edges[e], Eigen::Vector2i (std::min (a, b), std::max (a, b)));
        // Each corner's vertex lists the face; each edge end lists the other end.
        const auto faces = topo.facesOf (a);
        EXPECT_TRUE (std::binary_search (faces.begin (), faces.end (), f));
        const auto ring = topo.neighborsOf (a);
        EXPECT_TRUE (std::binary_search (ring.begin (), ring.end (), b));
        // Neighbours are symmetric, share the edge, and walk it the other way (consistent orientation).
        const int g = topo.face_neighbors[f][k];
        if (topo.edge_face_count[e] == 1)
        {
          EXPECT_EQ (g, -1);
          continue;
        }
        ASSERT_GE (g, 0);
        int j = 0;
        while (j < 3 && topo.face_edges[g][j] != e)
          ++j;
        ASSERT_LT (j, 3);
        EXPECT_EQ (topo.face_neighbors[g][j], f);
        EXPECT_EQ (mesh.triangles[g][j], b);
      }
    // Sum of valences = 2 #E; sum of vertex-face incidences = 3 #F.
    EXPECT_EQ (topo.vertex_neighbors.size (), 2 * topo.numEdges ());
    EXPECT_EQ (topo.vertex_faces.size (), 3 * mesh.numTriangles ());
  }
}

TEST (MeshTopology, DiskValencesAndBoundaryVertices)
{
  const int rings = 3;
  const TriangleMesh mesh = makeDisk (rings);
  const MeshTopology topo = buildMeshTopology (mesh);
  EXPECT_EQ (topo.neighborsOf (0).size (), 6u);  // the centre
  EXPECT_EQ (topo.facesOf (0).size (), 6u);
  // Outer-ring vertices: on exactly two boundary edges each; inner vertices on none.
  std::vector<int> boundary_degree (mesh.numVertices (), 0);
  for (std::size_t e = 0; e < topo.numEdges (); ++e)
    if (topo.isBoundaryEdge (static_cast<int> (e)))
    {
      ++boundary_degree[topo.edges[e][0]];
      ++boundary_degree[topo.edges[e][1]];
    }
  const int first_outer = 1 + 6 * (rings - 1) * rings / 2;  // 1 + 6 (1 + ... + (rings - 1))
  for (int v = 0; v < static_cast<int> (mesh.numVertices ()); ++v)
    EXPECT_EQ (boundary_degree[v], v >= first_outer ? 2 : 0) << "vertex " << v;
}

TEST (MeshTopology, RepeatedIndexFaceHasNoSelfEdge)
{
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {1, 1, 2}};
  const MeshTopology topo = buildMeshTopology (mesh);
  EXPECT_EQ (topo.numEdges (), 3u);
  EXPECT_EQ (topo.face_edges[1][0], -1);  // corners 0 and 1 are both vertex 1
  EXPECT_EQ (topo.facesOf (1).size (), 2u);  // counted once per face
}

TEST (MeshTopology, SameForAnyThreadCount)
{
  // Enough vertices to run in parallel, with faces across the mesh: non-manifold fins, a repeated index, a
  // face using one edge twice.
  TriangleMesh mesh = makeTorus (160, 64);
  const int n = static_cast<int> (mesh.numVertices ());
  mesh.vertices.emplace_back (0.0, 0.0, 2.0);
  for (int v = 0; v + 1 < n; v += 997)
    mesh.triangles.emplace_back (v, v + 1, n);
  mesh.triangles.emplace_back (5, 5, n - 3);
  mesh.triangles.emplace_back (7, n - 7, 7);
  const auto lists = [] (const MeshTopology& t) {
    return std::tie (t.vertex_face_offsets, t.vertex_faces, t.vertex_neighbor_offsets, t.vertex_neighbors, t.edges,
                     t.edge_face_count, t.face_edges, t.face_neighbors);
  };
  const MeshTopology one = buildMeshTopology (mesh, 1);
  for (const int threads : {2, 3})
  {
    const MeshTopology topo = buildMeshTopology (mesh, threads);
    EXPECT_TRUE (lists (topo) == lists (one)) << threads << " threads";
  }
  EXPECT_GT (countEdges (one, 3), 0);
  const int twice = static_cast<int> (mesh.numTriangles ()) - 1;  // (7, n - 7, 7): edge (7, n - 7) twice
  EXPECT_EQ (one.face_edges[twice][0], one.face_edges[twice][1]);
  EXPECT_EQ (one.face_neighbors[twice][0], twice);
  EXPECT_EQ (one.face_edges[twice][2], -1);
  EXPECT_EQ (one.face_edges[twice - 1][0], -1);
}
