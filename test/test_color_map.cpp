/// Known colours of the colour maps in common/color_map.h at their ends, stops and edge cases.

#include <pcl_sparse/common/color_map.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

using namespace pcl_sparse;

TEST (ColorMap, ErrorColorRunsFromBlueOverGreenToRed)
{
  EXPECT_EQ (errorColor (0.0), (RgbColor{0, 0, 255}));
  EXPECT_EQ (errorColor (0.25), (RgbColor{0, 255, 255}));
  EXPECT_EQ (errorColor (0.5), (RgbColor{0, 255, 0}));
  EXPECT_EQ (errorColor (0.75), (RgbColor{255, 255, 0}));
  EXPECT_EQ (errorColor (1.0), (RgbColor{255, 0, 0}));
  // Clamped outside [0, 1]; NaN like 0.
  EXPECT_EQ (errorColor (-3.0), errorColor (0.0));
  EXPECT_EQ (errorColor (7.0), errorColor (1.0));
  EXPECT_EQ (errorColor (std::numeric_limits<double>::quiet_NaN ()), errorColor (0.0));
}

TEST (ColorMap, ViridisColorHitsItsStopsAndInterpolates)
{
  EXPECT_EQ (viridisColor (0.0), (RgbColor{68, 1, 84}));
  EXPECT_EQ (viridisColor (0.25), (RgbColor{59, 82, 139}));
  EXPECT_EQ (viridisColor (0.5), (RgbColor{33, 145, 140}));
  EXPECT_EQ (viridisColor (1.0), (RgbColor{253, 231, 37}));
  // Half way between the last two stops: (94 + 253) / 2 = 173.5 -> 174, (201 + 231) / 2 = 216, (98 + 37) / 2 = 67.5 -> 68.
  EXPECT_EQ (viridisColor (0.875), (RgbColor{174, 216, 68}));
  EXPECT_EQ (viridisColor (2.0), viridisColor (1.0));
  EXPECT_EQ (viridisColor (std::numeric_limits<double>::quiet_NaN ()), viridisColor (0.0));
  // Ordered: the green channel grows monotonically (readable in grey).
  for (int i = 1; i <= 100; ++i)
    EXPECT_GE (viridisColor (i / 100.0)[1], viridisColor ((i - 1) / 100.0)[1]);
}

TEST (ColorMap, CategoryColorsAreDistinctAndNeverBlackOrGrey)
{
  // Category 0: hue 0, saturation 0.55, value 0.95 -> (0.95, 0.4275, 0.4275) x 255, truncated.
  EXPECT_EQ (categoryColor (0), (RgbColor{242, 109, 109}));
  std::set<RgbColor> seen;
  for (std::size_t i = 0; i < 200; ++i)
  {
    const RgbColor c = categoryColor (i);
    seen.insert (c);
    EXPECT_FALSE (c[0] == c[1] && c[1] == c[2]) << "category " << i << " is grey";
  }
  EXPECT_EQ (seen.size (), 200u);
}
