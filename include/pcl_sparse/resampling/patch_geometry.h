#pragma once
/// \file patch_geometry.h
/// World-space point, normal and curvature of a coded patch at local (x, y) (docs/METHOD.md step 12).
/// A patch P maps its local (x, y) to s + r_P R (x, y, h(x, y)); everything here follows from that map.

#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/model/surface_basis.h>

#include <Eigen/Core>

namespace pcl_sparse
{
  /// World position of a patch's surface point.
  /// \param[in] code  the patch
  /// \param[in] x, y  local position
  /// \param[in] h     height sample of the code at (x, y)
  /// \return s + r_P R (x, y, h)
  inline Eigen::Vector3d
  patchPoint (const PatchCode& code, double x, double y, const HeightSample& h)
  {
    return code.toWorld (Eigen::Vector3d (x, y, h.value));
  }

  /// World unit normal n = R normalise(-h_x, -h_y, 1): the gradient is scale free, so local and world
  /// slopes agree.
  /// \param[in] code  the patch
  /// \param[in] h     height sample with the gradient
  /// \return the normal, oriented like the frame's N (which the encoder orients like the input's faces)
  inline Eigen::Vector3d
  patchNormal (const PatchCode& code, const HeightSample& h)
  {
    return code.frame * Eigen::Vector3d (-h.gradient.x (), -h.gradient.y (), 1.0).normalized ();
  }

  /// Area element: world area per unit local area.
  /// \param[in] code  the patch
  /// \param[in] h     height sample with the gradient
  /// \return r_P^2 sqrt(1 + h_x^2 + h_y^2)
  inline double
  patchAreaElement (const PatchCode& code, const HeightSample& h)
  {
    return code.radius * code.radius * std::sqrt (1.0 + h.gradient.squaredNorm ());
  }

  /// Mean curvature (k1 + k2) / 2 in world units (1 / length), signed so that a surface bending away from
  /// its normal is positive: a sphere of radius a with outward normals gives +1/a, its inside -1/a, a plane 0.
  /// For the graph z = r h(x / r, y / r): H = -((1 + h_y^2) h_xx - 2 h_x h_y h_xy + (1 + h_x^2) h_yy) /
  /// (2 r (1 + h_x^2 + h_y^2)^(3/2)).
  /// \param[in] code  the patch
  /// \param[in] h     height sample with gradient and Hessian
  /// \return H in 1 / world length
  inline double
  patchMeanCurvature (const PatchCode& code, const HeightSample& h)
  {
    const double hx = h.gradient.x (), hy = h.gradient.y ();
    const double hxx = h.hessian (0, 0), hxy = h.hessian (0, 1), hyy = h.hessian (1, 1);
    const double w = 1.0 + hx * hx + hy * hy;
    return -((1.0 + hy * hy) * hxx - 2.0 * hx * hy * hxy + (1.0 + hx * hx) * hyy) /
           (2.0 * code.radius * w * std::sqrt (w));
  }
} // namespace pcl_sparse
