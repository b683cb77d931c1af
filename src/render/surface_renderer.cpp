#include <pcl_sparse/render/surface_renderer.h>

#include <pcl_sparse/common/error.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// \a color times \a shade, rounded.
    RgbColor
    shaded (const RgbColor& color, double shade)
    {
      RgbColor out;
      for (int c = 0; c < 3; ++c)
        out[c] = static_cast<std::uint8_t> (std::min (255L, std::lround (color[c] * shade)));
      return out;
    }

    /// Twice the signed area of (a, b, p) in the image plane.
    double
    edge (const Eigen::Vector3d& a, const Eigen::Vector3d& b, double px, double py)
    {
      return (b.x () - a.x ()) * (py - a.y ()) - (b.y () - a.y ()) * (px - a.x ());
    }

    /// Whether an optional per-item vector is given and not empty.
    template <typename T>
    bool
    given (const std::vector<T>* v)
    {
      return v != nullptr && !v->empty ();
    }

    /// Throws unless an optional per-item vector is absent, empty or has \a n entries.
    template <typename T>
    void
    checkLength (const std::vector<T>* v, std::size_t n, const char* what)
    {
      if (given (v) && v->size () != n)
        throw Error (std::string ("SurfaceRenderer: ") + what + " has " + std::to_string (v->size ()) +
                     " entries for " + std::to_string (n) + " items");
    }
  } // namespace

  double
  lambertShade (const RenderCamera& camera, const Eigen::Vector3d& normal, const Eigen::Vector3d& light, double ambient)
  {
    Eigen::Vector3d n (camera.right.dot (normal), camera.up.dot (normal), camera.toward.dot (normal));
    const double length = n.norm ();
    if (!(length > 0.0) || !std::isfinite (length))
      return 0.8;
    n /= length;
    if (n.z () < 0.0)
      n = -n;
    return ambient + (1.0 - ambient) * std::max (0.0, n.dot (light));
  }

  void
  SurfaceRenderer::setInputMesh (const TriangleMesh* mesh, const std::vector<RgbColor>* colors)
  {
    mesh_ = mesh;
    mesh_colors_ = colors;
  }

  void
  SurfaceRenderer::setInputPoints (const std::vector<Eigen::Vector3d>* positions, const std::vector<Eigen::Vector3d>* normals,
                                   const std::vector<RgbColor>* colors)
  {
    points_ = positions;
    normals_ = normals;
    point_colors_ = colors;
  }

  void
  SurfaceRenderer::compute (RgbImage& image)
  {
    const int w = options_.width, h = options_.height;
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
      throw Error ("SurfaceRenderer: image size " + std::to_string (w) + "x" + std::to_string (h) +
                   " is not in 1 .. 16384 per side");
    if (mesh_)
      checkLength (mesh_colors_, mesh_->vertices.size (), "the vertex colour list");
    if (points_)
    {
      checkLength (normals_, points_->size (), "the normal list");
      checkLength (point_colors_, points_->size (), "the point colour list");
    }
    image.reset (w, h, options_.background);
    std::vector<float> depth (static_cast<std::size_t> (w) * h, std::numeric_limits<float>::infinity ());
    splat_radius_used_ = 0;
    if (mesh_)
      drawMesh (image, depth);
    if (points_)
      drawPoints (image, depth);
    covered_ = static_cast<std::size_t> (
      std::count_if (depth.begin (), depth.end (), [] (float d) { return d != std::numeric_limits<float>::infinity (); }));
    if (markers_)
      drawMarkers (image, depth);
  }

  void
  SurfaceRenderer::drawMesh (RgbImage& image, std::vector<float>& depth) const
  {
    const TriangleMesh& mesh = *mesh_;
    const int w = image.width, h = image.height;
    const long nv = static_cast<long> (mesh.vertices.size ()), nf = static_cast<long> (mesh.triangles.size ());
    std::vector<Eigen::Vector3d> screen (nv);
#pragma omp parallel for schedule(static)
    for (long v = 0; v < nv; ++v)
      screen[v] = camera_.project (mesh.vertices[v]);
    std::vector<double> shade (nf);
#pragma omp parallel for schedule(static)
    for (long f = 0; f < nf; ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const Eigen::Vector3d n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross (mesh.vertices[t[2]] - mesh.vertices[t[0]]);
      shade[f] = lambertShade (camera_, n, options_.light, options_.ambient);
    }
    const bool colored = given (mesh_colors_);
    // One thread, faces in order: the image does not depend on the thread count.
    for (long f = 0; f < nf; ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      if ((t.array () < 0).any () || (t.array () >= nv).any ())
        continue;
      const Eigen::Vector3d &a = screen[t[0]], &b = screen[t[1]], &c = screen[t[2]];
      const double area = edge (a, b, c.x (), c.y ());
      if (!(std::abs (area) > 1e-12) || !a.allFinite () || !b.allFinite () || !c.allFinite ())
        continue;
      const int x0 = std::max (0, static_cast<int> (std::floor (std::min ({a.x (), b.x (), c.x ()}))));
      const int x1 = std::min (w - 1, static_cast<int> (std::floor (std::max ({a.x (), b.x (), c.x ()}))));
      const int y0 = std::max (0, static_cast<int> (std::floor (std::min ({a.y (), b.y (), c.y ()}))));
      const int y1 = std::min (h - 1, static_cast<int> (std::floor (std::max ({a.y (), b.y (), c.y ()}))));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
        {
          const double px = x + 0.5, py = y + 0.5;
          const double wa = edge (b, c, px, py) / area, wb = edge (c, a, px, py) / area, wc = 1.0 - wa - wb;
          if (wa < 0.0 || wb < 0.0 || wc < 0.0)
            continue;
          const float z = static_cast<float> (wa * a.z () + wb * b.z () + wc * c.z ());
          float& d = depth[static_cast<std::size_t> (y) * w + x];
          if (!(z < d))
            continue;
          d = z;
          RgbColor color = options_.surface;
          if (colored)
          {
            const RgbColor &ca = (*mesh_colors_)[t[0]], &cb = (*mesh_colors_)[t[1]], &cc = (*mesh_colors_)[t[2]];
            if (options_.interpolate_colors)
              for (int k = 0; k < 3; ++k)
                color[k] = static_cast<std::uint8_t> (std::lround (wa * ca[k] + wb * cb[k] + wc * cc[k]));
            else
              color = wa >= wb && wa >= wc ? ca : (wb >= wc ? cb : cc);
          }
          image.set (x, y, shaded (color, shade[f]));
        }
    }
  }

  void
  SurfaceRenderer::drawPoints (RgbImage& image, std::vector<float>& depth)
  {
    const std::vector<Eigen::Vector3d>& points = *points_;
    const int w = image.width, h = image.height;
    const long n = static_cast<long> (points.size ());
    const bool has_normals = given (normals_), colored = given (point_colors_);
    std::vector<Eigen::Vector3d> screen (n);
    std::vector<RgbColor> colors (n);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i)
    {
      screen[i] = camera_.project (points[i]);
      const double s = has_normals ? lambertShade (camera_, (*normals_)[i], options_.light, options_.ambient) : 0.8;
      colors[i] = shaded (colored ? (*point_colors_)[i] : options_.surface, s);
    }
    int r = options_.splat_radius;
    if (r <= 0)
    {
      // Splats just touch: the screen area the points span (clipped to the image) over their number.
      double x0 = w, x1 = 0, y0 = h, y1 = 0;
      std::size_t inside = 0;
      for (const Eigen::Vector3d& s : screen)
        if (s.allFinite () && s.x () >= 0 && s.y () >= 0 && s.x () < w && s.y () < h)
        {
          ++inside;
          x0 = std::min (x0, s.x ());
          x1 = std::max (x1, s.x ());
          y0 = std::min (y0, s.y ());
          y1 = std::max (y1, s.y ());
        }
      const double spacing = inside > 0 ? std::sqrt ((x1 - x0 + 1.0) * (y1 - y0 + 1.0) / inside) : 1.0;
      r = static_cast<int> (std::clamp (std::lround (0.75 * spacing), 1L, 8L));
    }
    splat_radius_used_ = r;
    const int reach = r * r + r;  // the disc of radius r + 0.5, on the pixel grid
    for (long i = 0; i < n; ++i)
    {
      const Eigen::Vector3d& s = screen[i];
      if (!s.allFinite () || s.x () < -r || s.y () < -r || s.x () >= w + r || s.y () >= h + r)
        continue;
      const int cx = static_cast<int> (std::floor (s.x ())), cy = static_cast<int> (std::floor (s.y ()));
      const float z = static_cast<float> (s.z ());
      for (int dy = -r; dy <= r; ++dy)
      {
        const int y = cy + dy;
        if (y < 0 || y >= h)
          continue;
        for (int dx = -r; dx <= r; ++dx)
        {
          const int x = cx + dx;
          if (x < 0 || x >= w || dx * dx + dy * dy > reach)
            continue;
          float& d = depth[static_cast<std::size_t> (y) * w + x];
          if (z < d)
          {
            d = z;
            image.set (x, y, colors[i]);
          }
        }
      }
    }
  }

  void
  SurfaceRenderer::drawMarkers (RgbImage& image, const std::vector<float>& depth) const
  {
    const int w = image.width, h = image.height, r = options_.marker_radius;
    // A marker on the surface has its depth; allow a few pixels' worth for the splats' flat depth.
    const double tolerance = (r + 2.0) / camera_.scale;
    for (const Eigen::Vector3d& p : *markers_)
    {
      const Eigen::Vector3d s = camera_.project (p);
      if (!s.allFinite () || s.x () < 0 || s.y () < 0 || s.x () >= w || s.y () >= h)
        continue;
      const int cx = static_cast<int> (std::floor (s.x ())), cy = static_cast<int> (std::floor (s.y ()));
      if (s.z () > depth[static_cast<std::size_t> (cy) * w + cx] + tolerance)
        continue;  // hidden behind the surface
      for (int dy = -r - 1; dy <= r + 1; ++dy)
        for (int dx = -r - 1; dx <= r + 1; ++dx)
        {
          const int q = dx * dx + dy * dy;
          if (q <= r * r + r)
            image.set (cx + dx, cy + dy, options_.marker);
          else if (q <= (r + 1) * (r + 1) + r + 1)
            image.set (cx + dx, cy + dy, {0, 0, 0});  // a dark ring keeps the dot visible on any colour
        }
    }
  }
} // namespace pcl_sparse
