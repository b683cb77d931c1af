// Exact nearest-triangle queries (geometry/triangle_tree.h), against every triangle measured one by one.
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/point_triangle_distance.h>
#include <pcl_sparse/geometry/triangle_tree.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/surface_sampling.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// The nearest triangle by measuring every one (the first of equally near ones).
  TriangleTree::Nearest
  bruteForce (const TriangleMesh& mesh, const Eigen::Vector3d& p)
  {
    TriangleTree::Nearest best;
    best.distance = std::numeric_limits<double>::infinity ();
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const double d = pointTriangleDistance (p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
      if (d < best.distance)
        best = {d, static_cast<int> (f)};
    }
    return best;
  }

  /// A fan of long slivers: a hub and many rim vertices far out on a circle (triangles 100 times longer than
  /// wide), and a small bumpy grid beside it. A k-d tree over points drawn on the triangles misses slivers like these.
  TriangleMesh
  sliversAndGrid ()
  {
    TriangleMesh mesh;
    mesh.vertices.emplace_back (0.0, 0.0, 0.0);
    const int rim = 300;
    for (int i = 0; i < rim; ++i)
    {
      const double a = 2.0 * M_PI * i / rim;
      mesh.vertices.emplace_back (10.0 * std::cos (a), 10.0 * std::sin (a), 0.3 * std::sin (3.0 * a));
    }
    for (int i = 0; i < rim; ++i)
      mesh.triangles.emplace_back (0, 1 + i, 1 + (i + 1) % rim);
    const TriangleMesh grid = makePlaneGrid (20, 0.05);
    const int offset = static_cast<int> (mesh.vertices.size ());
    for (const Eigen::Vector3d& v : grid.vertices)
      mesh.vertices.push_back (v + Eigen::Vector3d (12.0, 0.0, 0.02 * std::sin (20.0 * v.x ())));
    for (const Eigen::Vector3i& t : grid.triangles)
      mesh.triangles.push_back (t + Eigen::Vector3i::Constant (offset));
    return mesh;
  }
} // namespace

TEST (TriangleTree, NearestIsExactOnASphereAndOnSlivers)
{
  std::mt19937 random (11);
  for (const TriangleMesh& mesh : {makeIcosphere (4), sliversAndGrid ()})
  {
    const TriangleTree tree (mesh);
    ASSERT_EQ (tree.size (), mesh.triangles.size ());
    // Points near the surface, off it, inside and far away, and the corners themselves.
    std::uniform_real_distribution<double> u (-13.0, 14.0);
    std::vector<Eigen::Vector3d> probes;
    for (int i = 0; i < 600; ++i)
      probes.emplace_back (u (random), u (random) / (i % 3 ? 1.0 : 10.0), u (random) / (i % 2 ? 20.0 : 1.0));
    for (std::size_t v = 0; v < mesh.vertices.size (); v += 7)
      probes.push_back (mesh.vertices[v]);
    probes.emplace_back (1e6, -1e6, 3.0);
    for (const Eigen::Vector3d& p : probes)
    {
      const TriangleTree::Nearest expected = bruteForce (mesh, p);
      const TriangleTree::Nearest found = tree.nearest (p);
      ASSERT_EQ (found.distance, expected.distance) << p.transpose ();
      const Eigen::Vector3i& t = mesh.triangles[found.triangle];
      EXPECT_EQ (pointTriangleDistance (p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]), found.distance);
    }
  }
}

// One walk for the nearest and the triangles within a margin of it: the same triangle as nearest, the same
// set as within, at margins from none (ties at shared corners only) to past the neighbours.
TEST (TriangleTree, NearestAndTiedIsNearestThenWithin)
{
  std::mt19937 random (17);
  for (const TriangleMesh& mesh : {makeIcosphere (3), sliversAndGrid ()})
  {
    const TriangleTree tree (mesh);
    std::uniform_real_distribution<double> u (-12.0, 13.0);
    std::vector<Eigen::Vector3d> probes;
    for (int i = 0; i < 300; ++i)
      probes.emplace_back (u (random), u (random) / 5.0, u (random) / 20.0);
    for (std::size_t v = 0; v < mesh.vertices.size (); v += 5)
      probes.push_back (mesh.vertices[v] * 1.01);  // beside a corner: its faces tie
    std::vector<TriangleTree::Nearest> tied, within;
    std::size_t several = 0;
    for (const Eigen::Vector3d& p : probes)
      for (const double margin : {0.0, 1e-11, 0.05, 1.0})
      {
        const TriangleTree::Nearest expected = tree.nearest (p);
        const TriangleTree::Nearest found = tree.nearestAndTied (p, margin, tied);
        ASSERT_EQ (found.triangle, expected.triangle) << p.transpose ();
        ASSERT_EQ (found.distance, expected.distance);
        auto byTriangle = [] (std::vector<TriangleTree::Nearest> faces) {
          std::vector<std::pair<int, double>> sorted;
          for (const TriangleTree::Nearest& f : faces)
            sorted.emplace_back (f.triangle, f.distance);
          std::sort (sorted.begin (), sorted.end ());
          return sorted;
        };
        std::vector<std::pair<int, double>> expected_tied;  // every triangle measured
        for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
        {
          const Eigen::Vector3i& t = mesh.triangles[f];
          const double d = pointTriangleDistance (p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
          if (d <= expected.distance + margin)
            expected_tied.emplace_back (static_cast<int> (f), d);
        }
        // Boxes are pruned by squared distances, which rounding can put a hair past a box that touches the
        // nearest point: exact ties need a margin (NearestFaceNormal's is 1e-12 of the coordinates), as within's.
        if (margin == 0.0)
          continue;
        ASSERT_EQ (byTriangle (tied), expected_tied) << p.transpose () << " margin " << margin;
        tree.within (p, expected.distance + margin, within);
        ASSERT_EQ (byTriangle (tied), byTriangle (within)) << p.transpose () << " margin " << margin;
        several += tied.size () > 1 ? 1 : 0;
      }
    EXPECT_GT (several, probes.size ());  // ties and margins gave more than the nearest alone
  }
  std::vector<TriangleTree::Nearest> tied{{1.0, 3}};
  const TriangleMesh one = makeIcosphere (0);
  EXPECT_EQ (TriangleTree (one).nearestAndTied (Eigen::Vector3d (0.0, 0.0, std::nan ("")), 0.1, tied).triangle, -1);
  EXPECT_TRUE (tied.empty ());
}

TEST (TriangleTree, WithinFindsEveryTriangleInTheRadius)
{
  std::mt19937 random (5);
  for (const TriangleMesh& mesh : {makeIcosphere (3), sliversAndGrid ()})
  {
    const TriangleTree tree (mesh);
    std::uniform_real_distribution<double> u (-12.0, 13.0), r (0.0, 3.0);
    std::vector<TriangleTree::Nearest> found;
    std::size_t total = 0;
    for (int i = 0; i < 300; ++i)
    {
      const Eigen::Vector3d p (u (random), u (random) / 5.0, u (random) / 20.0);
      const double radius = tree.nearest (p).distance + r (random) * (i % 2 ? 1.0 : 0.01);
      tree.within (p, radius, found);
      std::vector<int> expected, got;
      for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        if (pointTriangleDistance (p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]) <= radius)
          expected.push_back (static_cast<int> (f));
      }
      for (const TriangleTree::Nearest& face : found)
      {
        got.push_back (face.triangle);
        const Eigen::Vector3i& t = mesh.triangles[face.triangle];
        EXPECT_EQ (face.distance, pointTriangleDistance (p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
      }
      std::sort (got.begin (), got.end ());
      ASSERT_EQ (got, expected) << p.transpose () << " radius " << radius;
      total += got.size ();
    }
    EXPECT_GT (total, 600u);  // the radii reach past the nearest triangle, not only to it
  }
  // The corner of a fan: every triangle sharing the corner is at distance 0, none else.
  const TriangleMesh sphere = makeIcosphere (2);
  const TriangleTree tree (sphere);
  std::vector<TriangleTree::Nearest> found;
  tree.within (sphere.vertices[0] * 1.5, tree.nearest (sphere.vertices[0] * 1.5).distance + 1e-12, found);
  std::size_t sharing = 0;
  for (const Eigen::Vector3i& t : sphere.triangles)
    sharing += (t.array () == 0).any () ? 1 : 0;
  EXPECT_EQ (found.size (), sharing);
  EXPECT_EQ (sharing, 5u);  // an icosahedron's original corner
  tree.within (Eigen::Vector3d::Zero (), 0.5, found);  // inside the unit sphere, nothing within 0.5
  EXPECT_TRUE (found.empty ());
  tree.within (Eigen::Vector3d::Zero (), -1.0, found);
  EXPECT_TRUE (found.empty ());
}

TEST (TriangleTree, KnownDistancesAndDegenerateTriangles)
{
  // A unit square at z = 0 with a zero-area triangle and a duplicated one added: heights above it, distances
  // beside it to the edge.
  TriangleMesh square = makePlaneGrid (4, 0.5);
  square.triangles.push_back (square.triangles.front ());
  square.triangles.emplace_back (0, 0, 1);
  const TriangleTree tree (square);
  EXPECT_NEAR (tree.nearest (Eigen::Vector3d (0.1, -0.2, 0.3)).distance, 0.3, 1e-15);
  EXPECT_NEAR (tree.nearest (Eigen::Vector3d (0.1, -0.2, -0.05)).distance, 0.05, 1e-15);
  EXPECT_NEAR (tree.nearest (Eigen::Vector3d (0.9, 0.0, 0.0)).distance, 0.4, 1e-15);
  EXPECT_NEAR (tree.nearest (Eigen::Vector3d (0.9, 0.9, 0.0)).distance, std::sqrt (0.32), 1e-15);
  // One triangle: a tree of one leaf.
  TriangleMesh one;
  one.vertices = {Eigen::Vector3d (0, 0, 0), Eigen::Vector3d (1, 0, 0), Eigen::Vector3d (0, 1, 0)};
  one.triangles = {Eigen::Vector3i (0, 1, 2)};
  EXPECT_EQ (TriangleTree (one).nearest (Eigen::Vector3d (0.25, 0.25, -2.0)).distance, 2.0);
  EXPECT_EQ (TriangleTree (one).nearest (Eigen::Vector3d (0.25, 0.25, -2.0)).triangle, 0);
}

TEST (TriangleTree, BadMeshesAreRefused)
{
  EXPECT_THROW (TriangleTree {TriangleMesh ()}, Error);
  TriangleMesh broken = makePlaneGrid (2, 0.5);
  broken.vertices[0].x () = std::nan ("");
  EXPECT_THROW (TriangleTree {broken}, Error);
  TriangleMesh out_of_range = makePlaneGrid (2, 0.5);
  out_of_range.triangles[1][2] = static_cast<int> (out_of_range.vertices.size ());
  EXPECT_THROW (TriangleTree {out_of_range}, Error);
  out_of_range.triangles[1][2] = -1;
  EXPECT_THROW (TriangleTree {out_of_range}, Error);
  // Coordinates whose distances overflow a double: refused, where the queries found no nearest triangle.
  TriangleMesh huge = makePlaneGrid (2, 1e80);
  EXPECT_THROW (TriangleTree {huge}, Error);
  const TriangleTree tree (makePlaneGrid (2, 1e70));
  EXPECT_GE (tree.nearest (Eigen::Vector3d (0.0, 0.0, 1e70)).triangle, 0);
  EXPECT_EQ (tree.nearest (Eigen::Vector3d (0.0, 0.0, std::nan (""))).triangle, -1);
}

// The build runs on the threads asked for (the halves of large nodes as tasks, the nodes laid out as a serial
// depth-first build would): the same tree on any count, seen through the order within lists triangles in and
// the nearest triangle of every probe.
TEST (TriangleTree, SameTreeOnAnyThreadCount)
{
  const TriangleMesh sphere = makeIcosphere (6);  // 81920 triangles: the root's halves and theirs are tasks
  ASSERT_GT (sphere.triangles.size (), 80000u);
  std::vector<Eigen::Vector3d> probes;
  sampleMeshSurface (sphere, 3000, 9, probes);
  auto answers = [&] (int threads) {
    const TriangleTree tree (sphere, threads);
    std::vector<std::pair<int, double>> found;
    std::vector<TriangleTree::Nearest> within;
    for (std::size_t i = 0; i < probes.size (); ++i)
    {
      const Eigen::Vector3d p = probes[i] * (i % 2 ? 1.01 : 0.995);
      const TriangleTree::Nearest nearest = tree.nearest (p);
      found.emplace_back (nearest.triangle, nearest.distance);
      tree.within (p, nearest.distance + 0.01, within);
      for (const TriangleTree::Nearest& w : within)
        found.emplace_back (w.triangle, w.distance);
    }
    return found;
  };
  const std::vector<std::pair<int, double>> one = answers (1);
  EXPECT_GT (one.size (), 4 * probes.size ());  // within listed several triangles a probe
  EXPECT_EQ (answers (2), one);
  EXPECT_EQ (answers (3), one);
}

// Whatever the threads, a refused mesh's error names its first bad triangle.
TEST (TriangleTree, ErrorNamesTheFirstBadTriangleOnAnyThreadCount)
{
  TriangleMesh sphere = makeIcosphere (5);
  const std::size_t last = sphere.triangles.size () - 1;
  sphere.triangles[last][1] = -1;
  sphere.triangles[17][2] = static_cast<int> (sphere.vertices.size ());
  for (const int threads : {1, 2})
  {
    try
    {
      const TriangleTree tree (sphere, threads);
      ADD_FAILURE () << "accepted a corner out of range";
    }
    catch (const Error& e)
    {
      const std::string what = e.what ();
      EXPECT_NE (what.find ("triangle 17 has a corner index out of range"), std::string::npos) << what;
    }
  }
}
