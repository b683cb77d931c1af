#pragma once
/// \file render_camera.h
/// An orthographic camera for the software renderer: a view direction, and the scale and centre that fit
/// the scene into a viewport. Orthographic because the pictures are for judging shape and error, where
/// perspective would only make sizes depend on depth.

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Orthographic projection: pixel x = cx + scale * right.(p - center), pixel y = cy - scale * up.(p -
  /// center); depth = -toward.(p - center), smaller is nearer the viewer.
  struct RenderCamera
  {
    Eigen::Vector3d right = Eigen::Vector3d::UnitX ();   ///< image x axis in the world
    Eigen::Vector3d up = Eigen::Vector3d::UnitY ();      ///< image up axis in the world
    Eigen::Vector3d toward = Eigen::Vector3d::UnitZ ();  ///< from the scene towards the viewer
    Eigen::Vector3d center = Eigen::Vector3d::Zero ();   ///< world point drawn at pixel (cx, cy)
    double scale = 1.0;                                  ///< pixels per world unit
    double cx = 0.0;                                     ///< image x of center (pixel edges at integers)
    double cy = 0.0;                                     ///< image y of center

    /// Projects a world point.
    /// \param[in] p  the point
    /// \return image x, image y (continuous, pixel i covers [i, i+1)) and depth
    Eigen::Vector3d
    project (const Eigen::Vector3d& p) const
    {
      const Eigen::Vector3d d = p - center;
      return {cx + scale * right.dot (d), cy - scale * up.dot (d), -toward.dot (d)};
    }
  };

  /// The direction towards the viewer for a named view: front (+z), side (+x), top (+y), iso (1, 1, 1).
  /// \param[in] name  front, side, top or iso; or three numbers "x,y,z" (any length, not zero)
  /// \return the unit direction from the scene towards the viewer
  /// \throws pcl_sparse::Error for an unknown name or a malformed or zero vector
  Eigen::Vector3d
  viewDirectionFromName (const std::string& name);

  /// A camera looking along -\a toward whose view of \a points fills \a fill of the viewport (the larger
  /// relative extent), centred in it. Up is world +y, or -z when looking along y.
  /// \param[in] points    the scene's points (non-finite ones ignored)
  /// \param[in] toward    direction from the scene towards the viewer (need not be unit)
  /// \param[in] x0        viewport left edge, pixels
  /// \param[in] y0        viewport top edge, pixels
  /// \param[in] width     viewport width, pixels
  /// \param[in] height    viewport height, pixels
  /// \param[in] fill      fraction of the viewport the scene spans (0, 1]
  /// \return the camera; scale 1 and centre 0 when no point is finite
  RenderCamera
  fitRenderCamera (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& toward, int x0, int y0, int width,
                   int height, double fill = 0.9);
} // namespace pcl_sparse
