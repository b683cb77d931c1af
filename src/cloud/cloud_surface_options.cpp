#include <pcl_sparse/cloud/cloud_surface_options.h>

#include <pcl_sparse/common/error.h>

#include <cmath>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    [[noreturn]] void
    refuse (const std::string& what)
    {
      throw Error ("buildCloudSurface: option " + what);
    }
  } // namespace

  void
  validateCloudSurfaceOptions (const CloudSurfaceOptions& options)
  {
    if (options.k < 3 || options.k > 64)
      refuse ("k = " + std::to_string (options.k) + " is out of range (3..64)");
    if (options.window_radius < 1 || options.window_radius > 5)
      refuse ("window_radius = " + std::to_string (options.window_radius) + " is out of range (1..5)");
    if (!(options.gap_factor > 1.0) || !std::isfinite (options.gap_factor))
      refuse ("gap_factor = " + shortestDecimal (options.gap_factor) + " must be finite and > 1");
    if (!(options.shadow_angle_degrees >= 0.0 && options.shadow_angle_degrees <= 30.0))
      refuse ("shadow_angle_degrees = " + shortestDecimal (options.shadow_angle_degrees) + " is out of range (0..30)");
    if (!(options.outlier_factor > 0.0) || !std::isfinite (options.outlier_factor))
      refuse ("outlier_factor = " + shortestDecimal (options.outlier_factor) + " must be finite and > 0");
    if (!(options.outlier_spacing > 0.0) || !std::isfinite (options.outlier_spacing))
      refuse ("outlier_spacing = " + shortestDecimal (options.outlier_spacing) + " must be finite and > 0");
    if (options.num_threads < 0)
      refuse ("num_threads = " + std::to_string (options.num_threads) + " must be >= 0");
    if (options.has_viewpoint && !options.viewpoint.allFinite ())
      refuse ("viewpoint is not finite");
    for (std::size_t i = 0; i < options.point_viewpoints.size (); ++i)
      if (!options.point_viewpoints[i].allFinite ())
        refuse ("point_viewpoints[" + std::to_string (i) + "] is not finite");
    if (options.orientation == NormalOrientation::Given && !options.use_given_normals)
      refuse ("orientation Given needs use_given_normals");
  }
} // namespace pcl_sparse
