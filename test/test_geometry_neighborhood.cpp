#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace pcl_sparse;

namespace
{
  // makePlaneGrid (n) has (n + 1)^2 vertices, vertex (i, j) at index j (n + 1) + i. Its diagonals
  // alternate ("union jack"): vertices with i + j even have 8 neighbours, the others 4.
  int
  gridIndex (int n, int i, int j)
  {
    return j * (n + 1) + i;
  }
} // namespace

TEST (MeshNeighborhood, KRingSizesOnRegularGrid)
{
  const int n = 20;
  const TriangleMesh mesh = makePlaneGrid (n);
  const MeshTopology topo = buildMeshTopology (mesh);
  VertexMarks marks (mesh.numVertices ());
  std::vector<int> ring;

  // Even vertex: the k-ring is the (2k + 1)^2 square.
  const int even = gridIndex (n, 10, 10);
  for (int k = 0; k <= 4; ++k)
  {
    EXPECT_EQ (collectKRing (topo, even, k, marks, ring), k);
    EXPECT_EQ (ring.size (), static_cast<std::size_t> ((2 * k + 1) * (2 * k + 1))) << "k = " << k;
    EXPECT_EQ (ring.front (), even);
    for (int u : ring)
    {
      const int di = std::abs (u % (n + 1) - 10), dj = std::abs (u / (n + 1) - 10);
      EXPECT_LE (std::max (di, dj), k);
    }
  }
  // Odd vertex: 1, 5 (a plus), 21 (two crossed 5 x 3 bars).
  const int odd = gridIndex (n, 11, 10);
  collectKRing (topo, odd, 1, marks, ring);
  EXPECT_EQ (ring.size (), 5u);
  collectKRing (topo, odd, 2, marks, ring);
  EXPECT_EQ (ring.size (), 21u);
  // Corner vertex (0, 0) is even: a 3 x 3 quarter square after 2 rings.
  collectKRing (topo, gridIndex (n, 0, 0), 2, marks, ring);
  EXPECT_EQ (ring.size (), 9u);
}

TEST (MeshNeighborhood, RingsComeOutInBreadthFirstOrderWithoutDuplicates)
{
  const TriangleMesh mesh = makeIcosphere (3);
  const MeshTopology topo = buildMeshTopology (mesh);
  VertexMarks marks (mesh.numVertices ());
  std::vector<int> ring;
  collectKRing (topo, 17, 3, marks, ring);
  std::vector<int> sorted = ring;
  std::sort (sorted.begin (), sorted.end ());
  EXPECT_TRUE (std::adjacent_find (sorted.begin (), sorted.end ()) == sorted.end ());
  // The marks hold exactly the output.
  int marked = 0;
  for (int v = 0; v < static_cast<int> (mesh.numVertices ()); ++v)
    marked += marks.isMarked (v);
  EXPECT_EQ (marked, static_cast<int> (ring.size ()));
  // 1-ring entries come right after the centre, in the topology's order.
  const auto first = topo.neighborsOf (17);
  EXPECT_TRUE (std::equal (first.begin (), first.end (), ring.begin () + 1));
  // Same answer as the allocating overload.
  EXPECT_EQ (kRing (topo, 17, 3), ring);
}

TEST (MeshNeighborhood, KRingStopsWhenTheComponentIsExhausted)
{
  TriangleMesh mesh = makeTetrahedron ();
  appendMesh (mesh, makeTetrahedron ());
  const MeshTopology topo = buildMeshTopology (mesh);
  VertexMarks marks (mesh.numVertices ());
  std::vector<int> ring;
  EXPECT_EQ (collectKRing (topo, 5, 6, marks, ring), 1);
  ASSERT_EQ (ring.size (), 4u);
  for (int u : ring)
    EXPECT_GE (u, 4);  // never leaves the second tetrahedron
}

TEST (MeshNeighborhood, AdaptiveRingGrowsUntilRadiusAndEnoughNeighbours)
{
  const int n = 20;  // spacing 0.1
  const TriangleMesh mesh = makePlaneGrid (n, 1.0);
  const MeshTopology topo = buildMeshTopology (mesh);
  VertexMarks marks (mesh.numVertices ());
  std::vector<int> ring;
  const int even = gridIndex (n, 10, 10), odd = gridIndex (n, 11, 10);

  AdaptiveRingOptions options;
  options.radius = 0.15;  // 1-ring radius is 0.1 sqrt 2 = 0.141 < 0.15: a second ring is needed
  EXPECT_EQ (collectAdaptiveRing (mesh, topo, even, options, marks, ring), 2);
  EXPECT_EQ (ring.size (), 25u);
  options.radius = 0.1;
  EXPECT_EQ (collectAdaptiveRing (mesh, topo, even, options, marks, ring), 1);
  EXPECT_EQ (ring.size (), 9u);

  // The odd vertex's 1-ring reaches the radius but has only 4 neighbours: grow to 2 rings (20).
  options.radius = 0.05;
  EXPECT_EQ (collectAdaptiveRing (mesh, topo, odd, options, marks, ring), 2);
  EXPECT_EQ (ring.size (), 21u);
  options.min_neighbors = 0;
  EXPECT_EQ (collectAdaptiveRing (mesh, topo, odd, options, marks, ring), 1);
  EXPECT_EQ (ring.size (), 5u);

  // The ring cap wins over a huge radius.
  options.radius = 100.0;
  options.max_rings = 3;
  EXPECT_EQ (collectAdaptiveRing (mesh, topo, even, options, marks, ring), 3);
  EXPECT_EQ (ring.size (), 49u);
}

TEST (MeshNeighborhood, AHubVertexDoesNotPutEveryVertexInEveryNeighbourhood)
{
  // A fan-triangulated 5000-gon: vertex 0 neighbours every other vertex, so each rim vertex's 2-ring was
  // the whole polygon and Harris 3D took quadratic time (a 200000-gon did not finish in a minute).
  const int n = 5000;
  TriangleMesh fan;
  for (int i = 0; i < n; ++i)
    fan.vertices.emplace_back (std::cos (2.0 * M_PI * i / n), std::sin (2.0 * M_PI * i / n), 0.0);
  for (int i = 1; i + 1 < n; ++i)
    fan.triangles.emplace_back (0, i, i + 1);
  const MeshTopology topo = buildMeshTopology (fan);
  VertexMarks marks (fan.numVertices ());
  std::vector<int> ring;
  EXPECT_EQ (collectKRing (topo, 2500, 1, marks, ring), 1);
  EXPECT_EQ (ring.size (), 4u);  // 2500, the hub, 2499, 2501: below the limit nothing changes
  collectKRing (topo, 2500, 2, marks, ring);
  EXPECT_EQ (ring.size (), static_cast<std::size_t> (1 + default_max_ring_neighbors));
  collectKRing (topo, 2500, 2, marks, ring, 10);
  ASSERT_EQ (ring.size (), 11u);
  EXPECT_EQ (ring[1], 0);  // the 1-ring first, in the topology's order, then the hub's ring cut
  for (int u : ring)
    EXPECT_EQ (std::count (ring.begin (), ring.end (), u), 1);

  AdaptiveRingOptions options;
  options.radius = 10.0;  // everything: only the limit stops it
  options.max_neighbors = 100;
  collectAdaptiveRing (fan, topo, 2500, options, marks, ring);
  EXPECT_EQ (ring.size (), 101u);
  // The marks hold exactly the neighbourhood (the next caller clears them).
  int marked = 0;
  for (int v = 0; v < n; ++v)
    marked += marks.isMarked (v) ? 1 : 0;
  EXPECT_EQ (marked, 101);
}

TEST (MeshNeighborhood, VertexMarksClearInConstantTime)
{
  VertexMarks marks (10);
  EXPECT_TRUE (marks.mark (3));
  EXPECT_FALSE (marks.mark (3));
  EXPECT_TRUE (marks.isMarked (3));
  marks.clear ();
  EXPECT_FALSE (marks.isMarked (3));
  EXPECT_TRUE (marks.mark (3));
}

TEST (MeshNeighborhood, BoundingBoxDiagonal)
{
  EXPECT_NEAR (boundingBoxDiagonal (makeCube (4, 1.0)), 2.0 * std::sqrt (3.0), 1e-12);
  EXPECT_NEAR (boundingBoxDiagonal (makePlaneGrid (3, 0.5)), std::sqrt (2.0), 1e-12);
  EXPECT_EQ (boundingBoxDiagonal (TriangleMesh ()), 0.0);
  // Non-finite points are ignored; none finite gives 0.
  const double nan = std::numeric_limits<double>::quiet_NaN (), inf = std::numeric_limits<double>::infinity ();
  EXPECT_EQ (boundingBoxDiagonal ({Eigen::Vector3d (nan, 0, 0), Eigen::Vector3d (0, inf, 0)}), 0.0);
  EXPECT_EQ (boundingBoxDiagonal ({Eigen::Vector3d (1, 2, 3), Eigen::Vector3d (nan, 0, 0), Eigen::Vector3d (4, 6, 3)}),
             5.0);
}
