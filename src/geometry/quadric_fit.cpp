#include <pcl_sparse/geometry/quadric_fit.h>

#include <pcl_sparse/common/upper_median.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// One row of the quadric's design matrix at scaled coordinates (x, y).
    Eigen::Matrix<double, 6, 1>
    quadricRow (double x, double y)
    {
      Eigen::Matrix<double, 6, 1> row;
      row << 1.0, x, y, 0.5 * x * x, x * y, 0.5 * y * y;
      return row;
    }

    /// Least squares on coordinates scaled by 1 / extent (returned in \a scale): the factorised normal
    /// equations and the scaled coefficients. False for fewer than 6 points or an undetermined layout.
    bool
    solveScaledQuadric (const std::vector<Eigen::Vector3d>& points, double& scale,
                        Eigen::LDLT<Eigen::Matrix<double, 6, 6>>& ldlt, Eigen::Matrix<double, 6, 1>& c)
    {
      if (points.size () < 6)
        return false;
      double extent = 0.0;
      for (const auto& p : points)
        extent = std::max (extent, std::max (std::abs (p.x ()), std::abs (p.y ())));
      if (!(extent > 0.0) || !std::isfinite (extent))
        return false;
      scale = 1.0 / extent;
      // Normal equations on scaled coordinates: a 6 x 6 system, cheap for the many small fits of Harris 3D.
      // The lower triangle summed entry by entry (Eigen's rankUpdate took 3 % of a scan's encoding CPU).
      Eigen::Matrix<double, 6, 6> AtA = Eigen::Matrix<double, 6, 6>::Zero ();
      Eigen::Matrix<double, 6, 1> Atz = Eigen::Matrix<double, 6, 1>::Zero ();
      for (const auto& p : points)
      {
        const Eigen::Matrix<double, 6, 1> row = quadricRow (p.x () * scale, p.y () * scale);
        for (int j = 0; j < 6; ++j)
          for (int i = j; i < 6; ++i)
            AtA (i, j) += row[i] * row[j];
        Atz += row * p.z ();
      }
      AtA = AtA.selfadjointView<Eigen::Lower> ();
      ldlt.compute (AtA);
      if (ldlt.info () != Eigen::Success || !ldlt.isPositive ())
        return false;
      // Reject rank-deficient layouts (e.g. all points on a line): tiny pivots relative to the largest.
      const auto d = ldlt.vectorD ();
      if (d.minCoeff () <= 1e-12 * d.maxCoeff ())
        return false;
      c = ldlt.solve (Atz);
      return c.allFinite ();
    }
  } // namespace

  bool
  fitHeightQuadric (const std::vector<Eigen::Vector3d>& points, HeightQuadric& quadric)
  {
    double s = 1.0;
    Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt;
    Eigen::Matrix<double, 6, 1> c;
    if (!solveScaledQuadric (points, s, ldlt, c))
      return false;
    // Undo the scaling: coefficient of x^a y^b was multiplied by s^(a + b).
    quadric.c << c[0], c[1] * s, c[2] * s, c[3] * s * s, c[4] * s * s, c[5] * s * s;
    return true;
  }

  double
  quadricNoiseLevel (const std::vector<Eigen::Vector3d>& points)
  {
    double s = 1.0;
    Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt;
    Eigen::Matrix<double, 6, 1> c;
    if (points.size () < 12 || !solveScaledQuadric (points, s, ldlt, c))
      return 0.0;
    std::vector<double> standardized;
    standardized.reserve (points.size ());
    for (const auto& p : points)
    {
      const Eigen::Matrix<double, 6, 1> row = quadricRow (p.x () * s, p.y () * s);
      const double leverage = row.dot (ldlt.solve (row));
      standardized.push_back (std::abs (p.z () - row.dot (c)) / std::sqrt (std::max (1.0 - leverage, 1e-3)));
    }
    return upperMedian (standardized) / 0.6745;
  }

  MongeJet
  mongeJetOfQuadric (const HeightQuadric& quadric)
  {
    const auto& c = quadric.c;
    // Surface (x, y, h(x, y)); tangents Tx = (1, 0, hx), Ty = (0, 1, hy) at the origin.
    const double hx = c[1], hy = c[2];
    const double w = std::sqrt (1.0 + hx * hx + hy * hy);
    Eigen::Matrix2d first;   // first fundamental form
    first << 1.0 + hx * hx, hx * hy, hx * hy, 1.0 + hy * hy;
    Eigen::Matrix2d second;  // second fundamental form w.r.t. the upward normal
    second << c[3], c[4], c[4], c[5];
    second /= w;
    // Shape operator S = -I^{-1} II (minus: positive curvature bends away from the normal).
    // Solve the symmetric generalized problem II v = lambda I v; curvatures are -lambda.
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> solver (second, first);
    const Eigen::Vector2d lambda = solver.eigenvalues ();  // ascending: lambda0 <= lambda1
    const Eigen::Vector3d tx (1.0, 0.0, hx), ty (0.0, 1.0, hy);

    MongeJet jet;
    jet.normal = Eigen::Vector3d (-hx, -hy, 1.0) / w;
    jet.k1 = -lambda[0];
    jet.k2 = -lambda[1];
    const Eigen::Vector2d v1 = solver.eigenvectors ().col (0);
    jet.d1 = (v1[0] * tx + v1[1] * ty).normalized ();
    // d2 completes a right-handed frame; the eigenvectors are I-orthogonal, so this is the k2 direction.
    jet.d2 = jet.normal.cross (jet.d1).normalized ();
    return jet;
  }

  Eigen::Matrix3d
  frameAroundNormal (const Eigen::Vector3d& normal)
  {
    // Pick the world axis least aligned with the normal to start the tangent: stable and deterministic.
    Eigen::Vector3d axis = Eigen::Vector3d::Zero ();
    int least;
    normal.cwiseAbs ().minCoeff (&least);
    axis[least] = 1.0;
    const Eigen::Vector3d t1 = normal.cross (axis).normalized ();
    Eigen::Matrix3d R;
    R << t1, normal.cross (t1), normal;
    return R;
  }

  bool
  fitMongeJet (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
               const Eigen::Vector3d& normal_hint, MongeJet& jet)
  {
    return fitMongeJetInFrame (points, origin, frameAroundNormal (normal_hint.normalized ()), jet);
  }

  bool
  fitMongeJetInFrame (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                      const Eigen::Matrix3d& frame, MongeJet& jet)
  {
    if (!frame.allFinite ())
      return false;
    std::vector<Eigen::Vector3d> local;
    local.reserve (points.size ());
    for (const auto& p : points)
      local.push_back (frame.transpose () * (p - origin));
    HeightQuadric quadric;
    if (!fitHeightQuadric (local, quadric))
      return false;
    const MongeJet in_frame = mongeJetOfQuadric (quadric);
    jet.k1 = in_frame.k1;
    jet.k2 = in_frame.k2;
    jet.d1 = frame * in_frame.d1;
    jet.d2 = frame * in_frame.d2;
    jet.normal = frame * in_frame.normal;
    return true;
  }
} // namespace pcl_sparse
