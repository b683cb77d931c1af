#include <pcl_sparse/render/render_camera.h>

#include <pcl_sparse/common/error.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace pcl_sparse
{
  Eigen::Vector3d
  viewDirectionFromName (const std::string& name)
  {
    if (name == "front")
      return Eigen::Vector3d::UnitZ ();
    if (name == "side")
      return Eigen::Vector3d::UnitX ();
    if (name == "top")
      return Eigen::Vector3d::UnitY ();
    if (name == "iso")
      return Eigen::Vector3d (1.0, 1.0, 1.0).normalized ();
    Eigen::Vector3d v = Eigen::Vector3d::Zero ();  // "1,2" sets two: the norm below must not read an unset third
    std::stringstream in (name);
    std::string item;
    int n = 0;
    while (std::getline (in, item, ','))
    {
      char* end = nullptr;
      const double x = std::strtod (item.c_str (), &end);
      if (n >= 3 || item.empty () || *end != '\0' || !std::isfinite (x))
        throw Error ("view '" + name + "': expected front, side, top, iso or x,y,z");
      v[n++] = x;
    }
    // stableNorm: norm () overflowed at 1e200 (a blank picture) and underflowed at 1e-200 (refused as zero).
    const double length = v.stableNorm ();
    if (n != 3 || length == 0.0 || name.back () == ',')  // getline drops an empty last part: "1,2,3,"
      throw Error ("view '" + name + "': expected front, side, top, iso or a non-zero x,y,z");
    return v / length;
  }

  RenderCamera
  fitRenderCamera (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& toward, int x0, int y0, int width,
                   int height, double fill)
  {
    RenderCamera camera;
    camera.toward = toward.normalized ();
    // Up is world y unless we look (almost) along it; then -z, so that +z (the front) is at the bottom.
    Eigen::Vector3d up_hint = Eigen::Vector3d::UnitY ();
    if (std::abs (camera.toward.y ()) > 0.99)
      up_hint = Eigen::Vector3d (0.0, 0.0, camera.toward.y () > 0.0 ? -1.0 : 1.0);
    camera.right = up_hint.cross (camera.toward).normalized ();
    camera.up = camera.toward.cross (camera.right);
    camera.cx = x0 + 0.5 * width;
    camera.cy = y0 + 0.5 * height;

    const double inf = std::numeric_limits<double>::infinity ();
    double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf};
    for (const Eigen::Vector3d& p : points)
    {
      if (!p.allFinite ())
        continue;
      const double c[3] = {camera.right.dot (p), camera.up.dot (p), camera.toward.dot (p)};
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min (lo[k], c[k]);
        hi[k] = std::max (hi[k], c[k]);
      }
    }
    if (!(lo[0] <= hi[0]))
      return camera;
    camera.center = 0.5 * ((lo[0] + hi[0]) * camera.right + (lo[1] + hi[1]) * camera.up + (lo[2] + hi[2]) * camera.toward);
    const double ex = hi[0] - lo[0], ey = hi[1] - lo[1];
    const double sx = ex > 0.0 ? width / ex : inf, sy = ey > 0.0 ? height / ey : inf;
    const double s = std::min (sx, sy);
    camera.scale = std::isfinite (s) ? fill * s : 1.0;
    return camera;
  }
} // namespace pcl_sparse
