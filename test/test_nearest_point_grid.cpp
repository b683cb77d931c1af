// NearestPointGrid against a linear search (the same float distance, the lowest index among equal ones) and
// against PointKdTree, whose FLANN tree it replaced in patch sampling: flat, solid, clustered and tied points,
// queries inside and far outside, and the edge cases.
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/nearest_point_grid.h>
#include <pcl_sparse/geometry/point_kd_tree.h>

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace pcl_sparse;

namespace
{
  float
  flannSquaredDistance (const Eigen::Vector3f& a, const Eigen::Vector3f& b)
  {
    const Eigen::Vector3f d = a - b;
    return (d.x () * d.x () + d.y () * d.y ()) + d.z () * d.z ();
  }

  int
  linearNearest (const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& q)
  {
    int best = -1;
    float best_squared = std::numeric_limits<float>::infinity ();
    for (std::size_t i = 0; i < points.size (); ++i)
    {
      const float squared = flannSquaredDistance (q, points[i]);
      if (squared < best_squared)
      {
        best_squared = squared;
        best = static_cast<int> (i);
      }
    }
    return best;
  }

  // Every point, a point beside each, and random queries over a box 3x the points' own: the grid's answer is
  // the linear search's, and at the same distance as the kd-tree's. Returns how many answers the kd-tree
  // gave a different index for (ties).
  int
  expectNearestAsLinear (const std::vector<Eigen::Vector3f>& points, unsigned seed)
  {
    const NearestPointGrid grid (points);
    pcl::PointCloud<pcl::PointXYZ> cloud;
    for (const Eigen::Vector3f& p : points)
      cloud.push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
    const PointKdTree tree (cloud);
    std::vector<Eigen::Vector3f> queries;
    for (const Eigen::Vector3f& p : points)
      queries.insert (queries.end (), {p, p + Eigen::Vector3f (0.013f, -0.007f, 0.002f)});
    std::mt19937 random (seed);
    std::uniform_real_distribution<float> unit (-3.0f, 3.0f);
    for (int i = 0; i < 500; ++i)
      queries.emplace_back (unit (random), unit (random), unit (random));
    int tree_differs = 0;
    std::vector<int> indices;
    std::vector<float> squared;
    for (const Eigen::Vector3f& q : queries)
    {
      const int expected = linearNearest (points, q);
      const int got = grid.nearest (q);
      EXPECT_EQ (got, expected) << "query " << q.transpose ();
      tree.nearestK (pcl::PointXYZ (q.x (), q.y (), q.z ()), 1, indices, squared);
      EXPECT_EQ (flannSquaredDistance (q, points[got]), squared[0]);
      tree_differs += indices[0] != got;
    }
    return tree_differs;
  }

  std::vector<Eigen::Vector3f>
  randomPoints (std::size_t n, const Eigen::Vector3f& scale, unsigned seed)
  {
    std::mt19937 random (seed);
    std::uniform_real_distribution<float> unit (-1.0f, 1.0f);
    std::vector<Eigen::Vector3f> points;
    for (std::size_t i = 0; i < n; ++i)
      points.push_back (Eigen::Vector3f (unit (random), unit (random), unit (random)).cwiseProduct (scale));
    return points;
  }
} // namespace

TEST (NearestPointGrid, SolidAndFlatPointsAsLinearSearch)
{
  EXPECT_EQ (expectNearestAsLinear (randomPoints (3000, Eigen::Vector3f (1.0f, 1.0f, 1.0f), 1), 11), 0);
  EXPECT_EQ (expectNearestAsLinear (randomPoints (3000, Eigen::Vector3f (1.0f, 0.5f, 0.0f), 2), 12), 0);  // a plane
  // On a line, points closer than float resolves lie at one distance from a query off it: the tree took
  // another of them 43 times (the same distance, checked), the grid the lowest index as the linear search.
  EXPECT_LT (expectNearestAsLinear (randomPoints (3000, Eigen::Vector3f (1.0f, 0.0f, 0.0f), 3), 13), 100);
}

TEST (NearestPointGrid, OutliersStretchingTheGrid)
{
  // A dense cluster and two far points: most cells are empty and a query between them crosses many rings.
  std::vector<Eigen::Vector3f> points = randomPoints (4000, Eigen::Vector3f (0.01f, 0.01f, 0.01f), 4);
  points.emplace_back (2.5f, -2.5f, 2.5f);
  points.emplace_back (-2.5f, 2.5f, -1.0f);
  EXPECT_EQ (expectNearestAsLinear (points, 14), 0);
}

TEST (NearestPointGrid, TiesGoToTheLowestIndex)
{
  // A lattice of spacing 1, filed twice (every point has a twin of a higher index): queries at cell centres
  // and on lattice points have many nearest points at exactly the same distance.
  std::vector<Eigen::Vector3f> points;
  for (int copy = 0; copy < 2; ++copy)
    for (int z = 0; z < 3; ++z)
      for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x)
          points.emplace_back (static_cast<float> (x), static_cast<float> (y), static_cast<float> (z));
  const NearestPointGrid grid (points);
  EXPECT_EQ (grid.nearest (Eigen::Vector3f (5.0f, 7.0f, 1.0f)), 1 * 144 + 7 * 12 + 5);
  EXPECT_EQ (grid.nearest (Eigen::Vector3f (5.5f, 7.5f, 1.5f)), 1 * 144 + 7 * 12 + 5);  // 8 at the same distance
  EXPECT_EQ (grid.nearest (Eigen::Vector3f (-10.0f, -10.0f, -10.0f)), 0);
  expectNearestAsLinear (points, 15);
}

TEST (NearestPointGrid, EdgeCases)
{
  const NearestPointGrid empty (std::vector<Eigen::Vector3f>{});
  EXPECT_EQ (empty.size (), 0u);
  EXPECT_EQ (empty.nearest (Eigen::Vector3f::Zero ()), -1);

  const NearestPointGrid one ({Eigen::Vector3f (1.0f, 2.0f, 3.0f)});
  EXPECT_EQ (one.nearest (Eigen::Vector3f (1e6f, -1e6f, 0.0f)), 0);

  const NearestPointGrid same (std::vector<Eigen::Vector3f> (50, Eigen::Vector3f (4.0f, 4.0f, 4.0f)));
  EXPECT_EQ (same.nearest (Eigen::Vector3f::Zero ()), 0);

  // Far from the origin with a small spread (map coordinates): still the linear search's answer.
  std::vector<Eigen::Vector3f> map = randomPoints (2000, Eigen::Vector3f (20.0f, 20.0f, 2.0f), 5);
  for (Eigen::Vector3f& p : map)
    p += Eigen::Vector3f (5.0e5f, 4.2e6f, 100.0f);
  const NearestPointGrid map_grid (map);
  for (std::size_t i = 0; i < map.size (); i += 7)
    EXPECT_EQ (map_grid.nearest (map[i] + Eigen::Vector3f (0.3f, -0.2f, 0.1f)),
               linearNearest (map, map[i] + Eigen::Vector3f (0.3f, -0.2f, 0.1f)));

  // Points near the largest float: their extent overflows a float, not the grid.
  const float huge = 0.9f * std::numeric_limits<float>::max ();
  const std::vector<Eigen::Vector3f> far = {Eigen::Vector3f (-huge, 0.0f, 0.0f), Eigen::Vector3f (huge, 1.0f, 0.0f),
                                            Eigen::Vector3f (0.0f, -huge, huge), Eigen::Vector3f (1.0f, 2.0f, 3.0f)};
  const NearestPointGrid far_grid (far);
  EXPECT_EQ (far_grid.nearest (Eigen::Vector3f::Zero ()), 3);
  EXPECT_EQ (far_grid.nearest (Eigen::Vector3f (huge, 1.0f, 0.0f)), 1);
  EXPECT_EQ (far_grid.nearest (Eigen::Vector3f (0.5f * huge, 0.0f, 0.0f)), 0);  // every distance overflows: the lowest

  EXPECT_THROW (NearestPointGrid ({Eigen::Vector3f (0.0f, std::numeric_limits<float>::quiet_NaN (), 0.0f)}), Error);
  EXPECT_THROW (NearestPointGrid ({Eigen::Vector3f::Zero (), Eigen::Vector3f (std::numeric_limits<float>::infinity (), 0.0f, 0.0f)}),
                Error);
}
