#pragma once
/// \file quadric_fit.h
/// Least-squares height quadrics and the degree-2 jet (Monge form) they define.
/// Shared by Harris 3D (docs/METHOD.md step 3) and the patch frames (step 6).

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// z = c0 + c1 x + c2 y + c3 x^2 / 2 + c4 x y + c5 y^2 / 2 in some local frame.
  /// (Harris notation of docs/METHOD.md step 3: p6 = c0, p4 = c1, p5 = c2, p1 = c3, p2 = c4, p3 = c5.)
  struct HeightQuadric
  {
    Eigen::Matrix<double, 6, 1> c = Eigen::Matrix<double, 6, 1>::Zero ();  ///< c0 .. c5

    /// Height z at (\a x, \a y).
    double value (double x, double y) const { return c[0] + c[1] * x + c[2] * y + 0.5 * c[3] * x * x + c[4] * x * y + 0.5 * c[5] * y * y; }
  };

  /// Fits a HeightQuadric to points given in the local frame (z = height) by least squares.
  /// Columns are scaled by the points' extent first, so the fit is well conditioned at any scale.
  /// \param[in]  points   #P local positions, #P >= 6
  /// \param[out] quadric  the fitted coefficients
  /// \return false (and \a quadric untouched) when there are fewer than 6 points or the xy positions do
  ///         not determine a quadric (collinear, coincident)
  bool
  fitHeightQuadric (const std::vector<Eigen::Vector3d>& points, HeightQuadric& quadric);

  /// Robust noise of heights about their least-squares height quadric: the median over points of
  /// |e_i| / sqrt (1 - h_i) / 0.6745, where e_i is a point's residual and h_i its leverage (so each term has
  /// the noise's spread, however the points are laid out). What a quadric cannot follow counts as noise:
  /// over a patch of a scan that is the sensor noise where the surface is smooth, and the depth steps
  /// where the sensor quantises depth.
  /// \param[in] points  #P local positions (z = height), #P >= 12
  /// \return the noise level in the points' units; 0 with fewer than 12 points or no determined fit
  double
  quadricNoiseLevel (const std::vector<Eigen::Vector3d>& points);

  /// Principal curvatures and directions of a surface at one point.
  /// Convention: curvature is positive where the surface bends away from its normal, so a sphere with
  /// outward normals has k1 = k2 = 1 / r.
  struct MongeJet
  {
    double k1 = 0.0;                                     ///< maximum principal curvature
    double k2 = 0.0;                                     ///< minimum principal curvature
    Eigen::Vector3d d1 = Eigen::Vector3d::UnitX ();      ///< unit direction of k1 (T1)
    Eigen::Vector3d d2 = Eigen::Vector3d::UnitY ();      ///< unit direction of k2 (T2), d1 x d2 = normal
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ ();  ///< unit surface normal

    /// The orthonormal frame R = (T1, T2, N) as columns.
    Eigen::Matrix3d frame () const
    {
      Eigen::Matrix3d R;
      R << d1, d2, normal;
      return R;
    }
  };

  /// The jet of a height quadric at (0, 0, c0).
  /// \param[in] quadric  the height quadric
  /// \return curvatures, directions and normal, expressed in the quadric's own frame
  MongeJet
  mongeJetOfQuadric (const HeightQuadric& quadric);

  /// Any orthonormal frame around a normal.
  /// \param[in] normal  unit vector
  /// \return a right-handed orthonormal frame whose third column is \a normal
  Eigen::Matrix3d
  frameAroundNormal (const Eigen::Vector3d& normal);

  /// Fits a degree-2 jet to world points: frame from a normal hint, quadric fit, curvatures and
  /// directions mapped back to world coordinates.
  /// \param[in]  points       world positions, at least 6
  /// \param[in]  origin       the point the jet is taken at (heights are measured from it)
  /// \param[in]  normal_hint  unit normal giving the fitting frame; the jet's normal is oriented like it
  /// \param[out] jet          the jet, in world coordinates
  /// \return false when the fit is underdetermined (see fitHeightQuadric)
  bool
  fitMongeJet (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
               const Eigen::Vector3d& normal_hint, MongeJet& jet);

  /// As fitMongeJet, in a given orthonormal frame: the quadric is fitted to frame^T (p - origin) and the
  /// jet is mapped back to world coordinates.
  /// \param[in]  points  world positions, at least 6
  /// \param[in]  origin  the point the jet is taken at
  /// \param[in]  frame   columns: two tangents and the normal the heights are measured along (for
  ///                     instance a seed's frame); the jet's normal is oriented like frame.col (2)
  /// \param[out] jet     the jet, in world coordinates
  /// \return false when the fit is underdetermined (see fitHeightQuadric)
  bool
  fitMongeJetInFrame (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                      const Eigen::Matrix3d& frame, MongeJet& jet);
} // namespace pcl_sparse
