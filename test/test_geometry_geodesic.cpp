#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/geodesic.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace pcl_sparse;

namespace
{
  constexpr int kN = 40;             // grid cells per side
  constexpr double kSpacing = 0.05;  // on [-1, 1]^2

  int
  gridIndex (int i, int j)
  {
    return j * (kN + 1) + i;
  }

  struct PlaneFixture : public ::testing::Test
  {
    TriangleMesh mesh = makePlaneGrid (kN, 1.0);
    MeshTopology topo = buildMeshTopology (mesh);
    int center = gridIndex (20, 20);
  };
} // namespace

// On the union-jack grid every edge path is a mix of axis and diagonal steps, so the edge distance is
// the octile distance: between |d| and (sqrt(4 - 2 sqrt 2)) |d| = 1.0824 |d|.
TEST_F (PlaneFixture, DistancesBoundEuclideanWithinOctileFactor)
{
  DijkstraGeodesic geodesic (mesh, topo);
  const double max_distance = 0.6;
  const std::size_t accepted = geodesic.compute (center, max_distance);
  EXPECT_EQ (accepted, geodesic.acceptedVertices ().size ());
  EXPECT_GT (accepted, 300u);
  const double factor = std::sqrt (4.0 - 2.0 * std::sqrt (2.0));
  double worst = 1.0;
  for (int v : geodesic.acceptedVertices ())
  {
    const double euclid = (mesh.vertices[v] - mesh.vertices[center]).norm ();
    const double d = geodesic.distance (v);
    EXPECT_LE (d, max_distance);
    EXPECT_GE (d, euclid - 1e-12);
    EXPECT_LE (d, factor * euclid + 1e-12);
    if (euclid > 0)
      worst = std::max (worst, d / euclid);
  }
  EXPECT_GT (worst, 1.05);  // the bound is nearly reached (direction ~22.5 degrees)
  // Axis and diagonal directions are exact.
  EXPECT_NEAR (geodesic.distance (gridIndex (28, 20)), 8 * kSpacing, 1e-12);
  EXPECT_NEAR (geodesic.distance (gridIndex (26, 26)), 6 * std::sqrt (2.0) * kSpacing, 1e-12);
  // Every vertex within the radius in Euclidean distance / factor is reached; none beyond the radius.
  for (int v = 0; v < static_cast<int> (mesh.numVertices ()); ++v)
  {
    const double euclid = (mesh.vertices[v] - mesh.vertices[center]).norm ();
    if (euclid * factor < max_distance - 1e-9)
      EXPECT_TRUE (geodesic.isAccepted (v));
    if (euclid > max_distance + 1e-9)
      EXPECT_FALSE (geodesic.isAccepted (v));
  }
}

TEST_F (PlaneFixture, VisitOrderIsIncreasingDistanceWithValidParents)
{
  DijkstraGeodesic geodesic (mesh, topo);
  std::vector<double> offered;
  geodesic.compute (center, 0.4, [&] (int v, double d, int parent) {
    offered.push_back (d);
    if (v == center)
      EXPECT_EQ (parent, -1);
    else
      EXPECT_NEAR (d, geodesic.distance (parent) + (mesh.vertices[v] - mesh.vertices[parent]).norm (), 1e-12);
    return GeodesicVisit::Accept;
  });
  ASSERT_FALSE (offered.empty ());
  EXPECT_EQ (offered.front (), 0.0);
  EXPECT_TRUE (std::is_sorted (offered.begin (), offered.end ()));
  EXPECT_EQ (geodesic.acceptedVertices ().front (), center);
}

TEST_F (PlaneFixture, RefusedVerticesAreNotExpanded)
{
  // A wall of refused vertices at column i = 24 (x = 0.2), across the whole grid: nothing beyond it is
  // reachable although it is within the radius.
  DijkstraGeodesic geodesic (mesh, topo);
  int refused = 0;
  geodesic.compute (center, 1.0, [&] (int v, double, int) {
    if (v % (kN + 1) == 24)
    {
      ++refused;
      return GeodesicVisit::Refuse;
    }
    return GeodesicVisit::Accept;
  });
  EXPECT_GT (refused, 10);
  for (int v : geodesic.acceptedVertices ())
    EXPECT_LT (v % (kN + 1), 24);
  EXPECT_TRUE (std::isfinite (geodesic.distance (gridIndex (24, 20))));  // refused, but its distance is known
  EXPECT_FALSE (geodesic.isAccepted (gridIndex (24, 20)));
  EXPECT_FALSE (geodesic.isAccepted (gridIndex (25, 20)));
  EXPECT_TRUE (std::isinf (geodesic.distance (gridIndex (25, 20))));
  EXPECT_TRUE (geodesic.isAccepted (gridIndex (23, 20)));
}

TEST_F (PlaneFixture, StopEndsTheWalk)
{
  DijkstraGeodesic geodesic (mesh, topo);
  int offered = 0;
  geodesic.compute (center, 1.0, [&] (int, double, int) { return ++offered <= 10 ? GeodesicVisit::Accept : GeodesicVisit::Stop; });
  EXPECT_EQ (offered, 11);
  EXPECT_EQ (geodesic.acceptedVertices ().size (), 10u);
}

TEST_F (PlaneFixture, ReusedObjectGivesTheSameAnswerAsAFreshOne)
{
  DijkstraGeodesic reused (mesh, topo);
  reused.compute (gridIndex (3, 3), 0.5);
  reused.compute (gridIndex (35, 30), 0.3);
  reused.compute (center, 0.25);
  DijkstraGeodesic fresh (mesh, topo);
  fresh.compute (center, 0.25);
  EXPECT_EQ (reused.acceptedVertices (), fresh.acceptedVertices ());
  for (int v = 0; v < static_cast<int> (mesh.numVertices ()); ++v)
  {
    EXPECT_EQ (reused.isAccepted (v), fresh.isAccepted (v));
    if (fresh.isAccepted (v))
    {
      EXPECT_EQ (reused.distance (v), fresh.distance (v));
      EXPECT_EQ (reused.parent (v), fresh.parent (v));
    }
  }
  // A vertex accepted in an earlier walk but outside this one reports no distance.
  EXPECT_TRUE (std::isinf (reused.distance (gridIndex (3, 3))));
}

TEST (DijkstraGeodesic, ZeroRadiusAcceptsOnlyTheSourceAndBadSourceThrows)
{
  const TriangleMesh mesh = makeIcosphere (2);
  const MeshTopology topo = buildMeshTopology (mesh);
  DijkstraGeodesic geodesic (mesh, topo);
  EXPECT_EQ (geodesic.compute (5, 0.0), 1u);
  EXPECT_THROW (geodesic.compute (-1, 1.0), Error);
  EXPECT_THROW (geodesic.compute (static_cast<int> (mesh.numVertices ()), 1.0), Error);
}

TEST (DijkstraGeodesic, SphereDistancesBoundTheGreatCircle)
{
  // Edge paths on a fine icosphere: never shorter than the chord; on a triangular lattice the worst
  // direction costs 2 / sqrt 3 = 1.155 x the straight line, plus up to two edges of discretisation.
  const double r = 1.0;
  const TriangleMesh mesh = makeIcosphere (4, r);
  const MeshTopology topo = buildMeshTopology (mesh);
  double max_edge = 0.0;
  for (const auto& e : topo.edges)
    max_edge = std::max (max_edge, (mesh.vertices[e[0]] - mesh.vertices[e[1]]).norm ());
  DijkstraGeodesic geodesic (mesh, topo);
  geodesic.compute (0, 10.0);
  EXPECT_EQ (geodesic.acceptedVertices ().size (), mesh.numVertices ());
  for (int v = 1; v < static_cast<int> (mesh.numVertices ()); ++v)
  {
    const double arc = r * std::acos (std::clamp (mesh.vertices[v].dot (mesh.vertices[0]) / (r * r), -1.0, 1.0));
    EXPECT_GE (geodesic.distance (v), (1.0 - 1e-9) * 2.0 * r * std::sin (arc / (2.0 * r)));  // >= chord
    EXPECT_LE (geodesic.distance (v), 1.16 * arc + 2.0 * max_edge);
  }
}

TEST_F (PlaneFixture, DeferredVertexIsOfferedAgainWhenANeighbourJoins)
{
  const int target = gridIndex (21, 20);  // a neighbour of the centre, at distance one spacing
  DijkstraGeodesic geodesic (mesh, topo);
  // Deferred once, accepted at its second offer: at its former distance (no shorter path exists).
  int offers = 0;
  geodesic.compute (center, 0.3, [&] (int v, double, int) {
    if (v != target)
      return GeodesicVisit::Accept;
    return ++offers == 1 ? GeodesicVisit::Defer : GeodesicVisit::Accept;
  });
  EXPECT_EQ (offers, 2);
  EXPECT_TRUE (geodesic.isAccepted (target));
  EXPECT_NEAR (geodesic.distance (target), kSpacing, 1e-15);

  // Deferred every time: offered once, then once more for each neighbour accepted after that offer.
  offers = 0;
  std::size_t accepted_before = 0;
  geodesic.compute (center, 0.3, [&] (int v, double, int) {
    if (v != target)
      return GeodesicVisit::Accept;
    if (++offers == 1)
      accepted_before = geodesic.acceptedVertices ().size ();
    return GeodesicVisit::Defer;
  });
  const auto& order = geodesic.acceptedVertices ();
  int later_neighbours = 0;
  for (int u : topo.neighborsOf (target))
    later_neighbours += std::find (order.begin () + accepted_before, order.end (), u) != order.end () ? 1 : 0;
  EXPECT_GE (later_neighbours, 2);  // several re-offers, not one
  EXPECT_EQ (offers, 1 + later_neighbours);
  EXPECT_FALSE (geodesic.isAccepted (target));
  EXPECT_NEAR (geodesic.distance (target), kSpacing, 1e-15);

  // Refused instead: offered once, never accepted.
  offers = 0;
  geodesic.compute (center, 0.3, [&] (int v, double, int) {
    if (v != target)
      return GeodesicVisit::Accept;
    ++offers;
    return GeodesicVisit::Refuse;
  });
  EXPECT_EQ (offers, 1);
  EXPECT_FALSE (geodesic.isAccepted (target));
}

TEST (DijkstraGeodesic, CachedEdgeLengthsGiveTheSameWalkBitForBit)
{
  const TriangleMesh mesh = makeTorus (48, 16);
  const MeshTopology topo = buildMeshTopology (mesh);
  const std::vector<double> lengths = computeEdgeLengths (mesh, topo);
  ASSERT_EQ (lengths.size (), topo.vertex_neighbors.size ());
  for (int v = 0; v < static_cast<int> (mesh.numVertices ()); ++v)
    for (int i = topo.vertex_neighbor_offsets[v]; i < topo.vertex_neighbor_offsets[v + 1]; ++i)
      EXPECT_EQ (lengths[i], (mesh.vertices[topo.vertex_neighbors[i]] - mesh.vertices[v]).norm ());
  DijkstraGeodesic computed (mesh, topo), cached (mesh, topo);
  cached.setEdgeLengths (lengths);
  computed.compute (7, 2.5);
  cached.compute (7, 2.5);
  EXPECT_GT (computed.acceptedVertices ().size (), 100u);
  EXPECT_EQ (computed.acceptedVertices (), cached.acceptedVertices ());
  for (int v : computed.acceptedVertices ())
  {
    EXPECT_EQ (computed.distance (v), cached.distance (v));
    EXPECT_EQ (computed.parent (v), cached.parent (v));
  }
  EXPECT_THROW (cached.setEdgeLengths (std::vector<double> (3, 1.0)), Error);
}
