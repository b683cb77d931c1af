// BallGrid (geometry/ball_grid.h): the balls that can hold a point, by a hash lookup.
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/ball_grid.h>

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

using namespace pcl_sparse;

TEST (BallGrid, EveryBallHoldingAPointIsACandidate)
{
  // Radii spread over 40x (a CAD part's reaches spread over 10x), some balls far apart.
  std::mt19937 random (5);
  std::uniform_real_distribution<double> unit (-1.0, 1.0), scale (0.0, 1.0);
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
  for (int i = 0; i < 300; ++i)
  {
    centres.emplace_back (unit (random), unit (random), 0.2 * unit (random));
    radii.push_back (0.02 + 0.05 * scale (random) + (i % 50 == 0 ? 0.8 : 0.0));
  }
  centres.emplace_back (30.0, -4.0, 2.0);  // a stray ball
  radii.push_back (0.05);
  const BallGrid grid (centres, radii, 0.05);
  EXPECT_GE (grid.cell (), 0.05);
  std::size_t candidates = 0, holding = 0;
  for (int k = 0; k < 20000; ++k)
  {
    const Eigen::Vector3d p = k == 0 ? Eigen::Vector3d (30.03, -4.0, 2.02) : Eigen::Vector3d (1.3 * unit (random), 1.3 * unit (random), 0.4 * unit (random));
    const auto [first, last] = grid.candidates (p);
    std::vector<char> listed (centres.size (), 0);
    for (const int* i = first; i != last; ++i)
    {
      ASSERT_GE (*i, 0);
      ASSERT_LT (*i, static_cast<int> (centres.size ()));
      if (i != first)
        EXPECT_LT (*(i - 1), *i);  // increasing: each once
      listed[*i] = 1;
      ++candidates;
    }
    for (std::size_t b = 0; b < centres.size (); ++b)
      if ((p - centres[b]).norm () <= radii[b])
      {
        ++holding;
        EXPECT_TRUE (listed[b]) << "ball " << b << " holds the point but is not listed";
      }
  }
  EXPECT_GT (holding, 20000u);              // the test sees many holding balls
  EXPECT_LT (candidates, 40u * 20000u);     // and the grid does not list every ball (301 here)
}

TEST (BallGrid, PointsOutsideEveryBoxAndEmptyGrids)
{
  const BallGrid grid ({Eigen::Vector3d (0, 0, 0)}, {1.0}, 0.5);
  EXPECT_EQ (grid.candidates (Eigen::Vector3d (0.9, 0.0, 0.0)).second - grid.candidates (Eigen::Vector3d (0.9, 0.0, 0.0)).first, 1);
  EXPECT_EQ (grid.candidates (Eigen::Vector3d (3.5, 0.0, 0.0)).first, nullptr);  // beyond every cell
  EXPECT_EQ (grid.candidates (Eigen::Vector3d (-1e300, 0.0, 0.0)).first, nullptr);
  EXPECT_EQ (grid.candidates (Eigen::Vector3d (std::numeric_limits<double>::quiet_NaN (), 0.0, 0.0)).first, nullptr);
  const BallGrid none ({}, {}, 1.0);
  EXPECT_EQ (none.candidates (Eigen::Vector3d::Zero ()).first, nullptr);
  // A huge ball among small ones: the cell grows rather than filing it in millions of cells.
  std::vector<Eigen::Vector3d> centres (100, Eigen::Vector3d::Zero ());
  std::vector<double> radii (100, 0.01);
  radii[0] = 100.0;
  const BallGrid huge (centres, radii, 0.01);
  EXPECT_GT (huge.cell (), 0.01);
  const auto [first, last] = huge.candidates (Eigen::Vector3d (60.0, 0.0, 0.0));
  ASSERT_EQ (last - first, 1);
  EXPECT_EQ (*first, 0);
}

TEST (BallGrid, BadInputIsRefused)
{
  EXPECT_THROW (BallGrid ({Eigen::Vector3d::Zero ()}, {}, 1.0), Error);
  EXPECT_THROW (BallGrid ({Eigen::Vector3d::Zero ()}, {-1.0}, 1.0), Error);
  EXPECT_THROW (BallGrid ({Eigen::Vector3d (std::numeric_limits<double>::infinity (), 0, 0)}, {1.0}, 1.0), Error);
  EXPECT_THROW (BallGrid ({Eigen::Vector3d::Zero ()}, {1.0}, 0.0), Error);
  EXPECT_THROW (BallGrid ({Eigen::Vector3d::Zero ()}, {1.0}, std::numeric_limits<double>::quiet_NaN ()), Error);
  // Finite centres and radii whose boxes are not (it looped for ever, doubling an infinite cell).
  const double big = std::numeric_limits<double>::max ();
  EXPECT_THROW (BallGrid ({Eigen::Vector3d (big, 0, 0), Eigen::Vector3d (-big, 0, 0)}, {big, big}, 1.0), Error);
}
