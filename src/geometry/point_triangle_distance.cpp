#include <pcl_sparse/geometry/point_triangle_distance.h>

namespace pcl_sparse
{
  double
  pointTriangleDistance (const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
  {
    // Voronoi regions of the triangle's features (Ericson, Real-Time Collision Detection 5.1.5).
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot (ap), d2 = ac.dot (ap);
    if (d1 <= 0.0 && d2 <= 0.0)
      return ap.norm ();
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot (bp), d4 = ac.dot (bp);
    if (d3 >= 0.0 && d4 <= d3)
      return bp.norm ();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
      return (p - (a + ab * (d1 / (d1 - d3)))).norm ();
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot (cp), d6 = ac.dot (cp);
    if (d6 >= 0.0 && d5 <= d6)
      return cp.norm ();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
      return (p - (a + ac * (d2 / (d2 - d6)))).norm ();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
      return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm ();
    const double denominator = 1.0 / (va + vb + vc);
    return (p - (a + ab * (vb * denominator) + ac * (vc * denominator))).norm ();
  }
} // namespace pcl_sparse
