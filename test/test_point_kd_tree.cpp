// PointKdTree against pcl::KdTreeFLANN: the same neighbours in the same order (the encoder's files did not
// change when it replaced PCL's tree), on random points and on a grid full of ties, and its edge cases.
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/point_kd_tree.h>

#include <pcl/kdtree/kdtree_flann.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace pcl_sparse;

namespace
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr
  randomPoints (std::size_t n, unsigned seed)
  {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    std::mt19937 random (seed);
    std::uniform_real_distribution<float> unit (-1.0f, 1.0f);
    for (std::size_t i = 0; i < n; ++i)
      cloud->push_back (pcl::PointXYZ (unit (random), unit (random), 0.1f * unit (random)));
    return cloud;
  }

  // A 20 x 20 x 3 grid of spacing 1: every point has many neighbours at exactly the same distance.
  pcl::PointCloud<pcl::PointXYZ>::Ptr
  gridPoints ()
  {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    for (int z = 0; z < 3; ++z)
      for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x)
          cloud->push_back (pcl::PointXYZ (static_cast<float> (x), static_cast<float> (y), static_cast<float> (z)));
    return cloud;
  }

  // Every query of \a cloud's own points and of points between them: k nearest and radius, sorted and not.
  void
  expectSameAsPcl (const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud, int k, double radius)
  {
    const PointKdTree ours (*cloud);
    pcl::KdTreeFLANN<pcl::PointXYZ> sorted_pcl (true), unsorted_pcl (false);
    sorted_pcl.setInputCloud (cloud);
    unsorted_pcl.setInputCloud (cloud);
    std::vector<int> our_indices, pcl_indices;
    std::vector<float> our_squared, pcl_squared;
    std::size_t neighbours = 0;
    for (std::size_t i = 0; i < cloud->size (); ++i)
    {
      const pcl::PointXYZ& p = (*cloud)[i];
      for (const pcl::PointXYZ& q : {p, pcl::PointXYZ (p.x + 0.5f, p.y + 0.25f, p.z)})
      {
        ours.nearestK (q, k, our_indices, our_squared);
        sorted_pcl.nearestKSearch (q, k, pcl_indices, pcl_squared);
        ASSERT_EQ (our_indices, pcl_indices) << "k nearest of query near point " << i;
        ASSERT_EQ (our_squared, pcl_squared);
        ours.radius (q, radius, our_indices, our_squared);
        sorted_pcl.radiusSearch (q, radius, pcl_indices, pcl_squared);
        ASSERT_EQ (our_indices, pcl_indices) << "sorted radius of query near point " << i;
        ASSERT_EQ (our_squared, pcl_squared);
        neighbours += our_indices.size ();
        ours.radius (q, radius, our_indices, our_squared, false);
        unsorted_pcl.radiusSearch (q, radius, pcl_indices, pcl_squared);
        ASSERT_EQ (our_indices, pcl_indices) << "unsorted radius of query near point " << i;
        ASSERT_EQ (our_squared, pcl_squared);
      }
    }
    // The radius holds several points per query: the comparison was not of empty lists.
    EXPECT_GT (neighbours, 4 * cloud->size ());
  }
} // namespace

TEST (PointKdTree, SameNeighboursAsPclOnRandomPoints)
{
  expectSameAsPcl (randomPoints (3000, 7), 9, 0.06);
}

TEST (PointKdTree, SameNeighboursAsPclWhereDistancesTie)
{
  expectSameAsPcl (gridPoints (), 13, 1.5);
}

// nearestWithin is nearestK's first answer wherever that lies within the bound (ties too), and nothing where
// it does not.
TEST (PointKdTree, NearestWithinABoundIsTheNearestOrNothing)
{
  for (const auto& cloud : {randomPoints (3000, 11), gridPoints ()})
  {
    const PointKdTree tree (*cloud);
    std::vector<int> indices;
    std::vector<float> squared;
    std::size_t found = 0, none = 0;
    std::mt19937 random (3);
    std::uniform_real_distribution<float> shift (-0.6f, 0.6f);
    for (std::size_t i = 0; i < cloud->size (); ++i)
    {
      const pcl::PointXYZ& p = (*cloud)[i];
      for (const pcl::PointXYZ& q : {p, pcl::PointXYZ (p.x + 0.5f, p.y + 0.25f, p.z),
                                     pcl::PointXYZ (p.x + shift (random), p.y + shift (random), p.z + shift (random))})
      {
        tree.nearestK (q, 1, indices, squared);
        ASSERT_EQ (indices.size (), 1u);
        for (const float bound : {0.5f * squared[0], squared[0], std::nextafter (squared[0], 1e30f), 4.0f * squared[0] + 1e-6f,
                                  std::numeric_limits<float>::infinity ()})
        {
          int index = -7;
          float d = -1.0f;
          const bool within = tree.nearestWithin (q, bound, index, d);
          ASSERT_EQ (within, squared[0] < bound) << "query near point " << i << ", bound " << bound;
          if (within)
          {
            ASSERT_EQ (index, indices[0]) << "query near point " << i << ", bound " << bound;
            ASSERT_EQ (d, squared[0]);
            ++found;
          }
          else
          {
            ASSERT_EQ (index, -7);  // left as it was
            ASSERT_EQ (d, -1.0f);
            ++none;
          }
        }
      }
    }
    EXPECT_GT (found, 3 * cloud->size ());
    EXPECT_GT (none, cloud->size ());
  }
  int index = -7;
  float d = -1.0f;
  EXPECT_FALSE (PointKdTree (pcl::PointCloud<pcl::PointXYZ> ()).nearestWithin (pcl::PointXYZ (0, 0, 0), 1.0f, index, d));
  EXPECT_EQ (index, -7);
}

TEST (PointKdTree, KnownNeighboursOnAGrid)
{
  const auto cloud = gridPoints ();
  const PointKdTree tree (*cloud);
  EXPECT_EQ (tree.size (), 1200u);
  std::vector<int> indices;
  std::vector<float> squared;
  // (5, 5, 1): itself, then its 6 face neighbours at distance 1, then 12 edge neighbours at sqrt 2.
  tree.nearestK (pcl::PointXYZ (5.0f, 5.0f, 1.0f), 7, indices, squared);
  ASSERT_EQ (indices.size (), 7u);
  EXPECT_EQ (indices[0], 400 + 5 * 20 + 5);
  EXPECT_EQ (squared[0], 0.0f);
  for (std::size_t m = 1; m < 7; ++m)
    EXPECT_EQ (squared[m], 1.0f) << m;
  tree.radius (pcl::PointXYZ (5.0f, 5.0f, 1.0f), std::sqrt (2.0) + 1e-6, indices, squared);
  EXPECT_EQ (indices.size (), 19u);
  // A corner: 3 neighbours at distance 1, outside a radius of exactly 1 (strictly less, as FLANN and PCL).
  tree.radius (pcl::PointXYZ (0.0f, 0.0f, 0.0f), 1.0, indices, squared);
  EXPECT_EQ (indices.size (), 1u);
  tree.radius (pcl::PointXYZ (0.0f, 0.0f, 0.0f), 1.0 + 1e-6, indices, squared);
  EXPECT_EQ (indices.size (), 4u);
}

TEST (PointKdTree, EdgeCases)
{
  std::vector<int> indices{1, 2};
  std::vector<float> squared{1.0f};
  const PointKdTree empty{pcl::PointCloud<pcl::PointXYZ> ()};
  EXPECT_EQ (empty.size (), 0u);
  empty.nearestK (pcl::PointXYZ (0, 0, 0), 3, indices, squared);
  EXPECT_TRUE (indices.empty () && squared.empty ());
  empty.radius (pcl::PointXYZ (0, 0, 0), 1.0, indices, squared);
  EXPECT_TRUE (indices.empty () && squared.empty ());

  const auto cloud = randomPoints (5, 1);
  const PointKdTree five (*cloud);
  five.nearestK ((*cloud)[2], 10, indices, squared);  // more than there are: all five
  EXPECT_EQ (indices.size (), 5u);
  EXPECT_EQ (indices[0], 2);
  five.nearestK ((*cloud)[2], 0, indices, squared);
  EXPECT_TRUE (indices.empty ());

  pcl::PointCloud<pcl::PointXYZ> bad = *cloud;
  bad[3].y = std::numeric_limits<float>::quiet_NaN ();
  EXPECT_THROW (PointKdTree tree (bad), Error);
}
