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
