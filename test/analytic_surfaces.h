#pragma once
// Height fields with known shape for the tests (makeHeightFieldGrid's z = f (x, y)).

namespace pcl_sparse_test
{
  /// A tilted elliptic paraboloid: curved everywhere, a quadric but no cosine series of few terms.
  inline double
  paraboloid (double x, double y)
  {
    return 0.5 * (x * x + y * y) + 0.2 * x * y;
  }
} // namespace pcl_sparse_test
