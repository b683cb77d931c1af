// The software renderer (src/render): a known scene's pixels, PNG bytes, determinism across runs and threads.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/render/bitmap_font.h>
#include <pcl_sparse/render/color_bar.h>
#include <pcl_sparse/render/png_file.h>
#include <pcl_sparse/render/render_camera.h>
#include <pcl_sparse/render/surface_renderer.h>

#include "test_file_helpers.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

using namespace pcl_sparse;

namespace
{
  const RgbColor kWhite = {255, 255, 255};

  bool
  isBackground (const RgbImage& image, int x, int y)
  {
    return image.at (x, y) == kWhite;
  }

  /// A unit sphere seen from the front at 240 x 200.
  RgbImage
  renderSphere (const TriangleMesh& sphere, RenderCamera& camera)
  {
    RenderOptions options;
    options.width = 240;
    options.height = 200;
    camera = fitRenderCamera (sphere.vertices, viewDirectionFromName ("front"), 0, 0, options.width, options.height);
    SurfaceRenderer renderer;
    renderer.setOptions (options);
    renderer.setCamera (camera);
    renderer.setInputMesh (&sphere);
    RgbImage image;
    renderer.compute (image);
    return image;
  }

  /// Random points on the unit sphere with their normals.
  void
  spherePoints (std::size_t n, std::vector<Eigen::Vector3d>& points, std::vector<Eigen::Vector3d>& normals)
  {
    std::mt19937_64 rng (7);
    std::normal_distribution<double> gauss;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Eigen::Vector3d p = Eigen::Vector3d (gauss (rng), gauss (rng), gauss (rng)).normalized ();
      points.push_back (p);
      normals.push_back (p);
    }
  }
} // namespace

TEST (RenderCamera, NamedViewsAndVectors)
{
  EXPECT_TRUE (viewDirectionFromName ("front").isApprox (Eigen::Vector3d::UnitZ ()));
  EXPECT_TRUE (viewDirectionFromName ("side").isApprox (Eigen::Vector3d::UnitX ()));
  EXPECT_TRUE (viewDirectionFromName ("0,0,-2").isApprox (-Eigen::Vector3d::UnitZ ()));
  EXPECT_THROW (viewDirectionFromName ("back"), Error);
  EXPECT_THROW (viewDirectionFromName ("0,0,0"), Error);
  EXPECT_THROW (viewDirectionFromName ("1,2"), Error);
  EXPECT_THROW (viewDirectionFromName ("1,2,3,4"), Error);
}

// The silhouette of a unit sphere is a disc of radius camera.scale pixels about the projected centre;
// outside is background; the brightest pixel lies where the sphere's normal is the light direction.
TEST (SurfaceRenderer, SphereSilhouetteAndShading)
{
  const TriangleMesh sphere = makeIcosphere (4);
  RenderCamera camera;
  const RgbImage image = renderSphere (sphere, camera);
  const Eigen::Vector3d c = camera.project (Eigen::Vector3d::Zero ());
  const double radius = camera.scale;
  EXPECT_NEAR (radius, 0.9 * 200 / 2, 1.0);  // the sphere spans 0.9 of the image height
  int inside_bad = 0, outside_bad = 0, inside = 0;
  int brightest = -1, bx = 0, by = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
    {
      const double r = std::hypot (x + 0.5 - c.x (), y + 0.5 - c.y ());
      if (r < radius - 1.5)
      {
        ++inside;
        inside_bad += isBackground (image, x, y);
        const RgbColor p = image.at (x, y);
        if (p[0] > brightest)
        {
          brightest = p[0];
          bx = x;
          by = y;
        }
      }
      else if (r > radius + 1.0)
        outside_bad += !isBackground (image, x, y);
    }
  EXPECT_GT (inside, 20000);
  EXPECT_EQ (inside_bad, 0);
  EXPECT_EQ (outside_bad, 0);
  const Eigen::Vector3d light = RenderOptions ().light;
  const double ex = c.x () + radius * light.x (), ey = c.y () - radius * light.y ();
  EXPECT_LT (std::hypot (bx + 0.5 - ex, by + 0.5 - ey), 0.1 * radius) << "brightest at " << bx << "," << by;
  // The rim, facing away from the light, is darker than the centre.
  EXPECT_LT (image.at (static_cast<int> (c.x () + 0.95 * radius), static_cast<int> (c.y ()))[0],
             image.at (static_cast<int> (c.x ()), static_cast<int> (c.y ()))[0]);
}

TEST (SurfaceRenderer, PointSplatsCoverTheDisc)
{
  std::vector<Eigen::Vector3d> points, normals;
  spherePoints (200000, points, normals);
  RenderOptions options;
  options.width = 240;
  options.height = 200;
  const RenderCamera camera = fitRenderCamera (points, Eigen::Vector3d::UnitZ (), 0, 0, options.width, options.height);
  SurfaceRenderer renderer;
  renderer.setOptions (options);
  renderer.setCamera (camera);
  renderer.setInputPoints (&points, &normals);
  RgbImage image;
  renderer.compute (image);
  const double radius = camera.scale, disc = M_PI * radius * radius;
  EXPECT_GE (renderer.getSplatRadius (), 1);
  EXPECT_NEAR (static_cast<double> (renderer.getCoveredPixels ()), disc, 0.05 * disc);
  const Eigen::Vector3d c = camera.project (Eigen::Vector3d::Zero ());
  EXPECT_FALSE (isBackground (image, static_cast<int> (c.x ()), static_cast<int> (c.y ())));
  EXPECT_TRUE (isBackground (image, 2, 2));
}

TEST (SurfaceRenderer, MarkersOnlyWhereVisible)
{
  const TriangleMesh sphere = makeIcosphere (3);
  const std::vector<Eigen::Vector3d> markers = {Eigen::Vector3d (0, 0, 1), Eigen::Vector3d (0.3, 0, -0.95)};
  RenderOptions options;
  options.width = 100;
  options.height = 100;
  const RenderCamera camera = fitRenderCamera (sphere.vertices, Eigen::Vector3d::UnitZ (), 0, 0, 100, 100);
  SurfaceRenderer renderer;
  renderer.setOptions (options);
  renderer.setCamera (camera);
  renderer.setInputMesh (&sphere);
  renderer.setMarkers (&markers);
  RgbImage image;
  renderer.compute (image);
  const Eigen::Vector3d front = camera.project (markers[0]), back = camera.project (markers[1]);
  EXPECT_EQ (image.at (static_cast<int> (front.x ()), static_cast<int> (front.y ())), options.marker);
  EXPECT_NE (image.at (static_cast<int> (back.x ()), static_cast<int> (back.y ())), options.marker);
}

TEST (SurfaceRenderer, RejectsBadSizesAndLengths)
{
  const TriangleMesh sphere = makeIcosphere (1);
  SurfaceRenderer renderer;
  RenderOptions options;
  options.width = 0;
  renderer.setOptions (options);
  RgbImage image;
  EXPECT_THROW (renderer.compute (image), Error);
  renderer.setOptions (RenderOptions ());
  const std::vector<RgbColor> colors (3);
  renderer.setInputMesh (&sphere, &colors);
  EXPECT_THROW (renderer.compute (image), Error);
}

// Same scene -> same PNG bytes, for two runs and for 1 and 2 OpenMP threads.
TEST (SurfaceRenderer, DeterministicBytesAcrossRunsAndThreads)
{
  const TriangleMesh torus = makeTorus (64, 32, 1.0, 0.3);
  std::vector<Eigen::Vector3d> points, normals;
  spherePoints (100000, points, normals);
  for (Eigen::Vector3d& p : points)
    p *= 0.5;
  auto render = [&] (int threads) {
    omp_set_num_threads (threads);
    std::vector<Eigen::Vector3d> all = points;
    all.insert (all.end (), torus.vertices.begin (), torus.vertices.end ());
    SurfaceRenderer renderer;
    renderer.setCamera (fitRenderCamera (all, viewDirectionFromName ("iso"), 0, 0, 800, 600));
    renderer.setInputMesh (&torus);
    renderer.setInputPoints (&points, &normals);
    RgbImage image;
    renderer.compute (image);
    drawColorBar (image, 1.5e-3, "dist/diag");
    return encodePng (image);
  };
  const int saved = omp_get_max_threads ();
  const std::vector<std::uint8_t> a = render (1), b = render (1), c = render (2);
  omp_set_num_threads (saved);
  ASSERT_GT (a.size (), 8u);
  EXPECT_EQ (a, b);
  EXPECT_EQ (a, c);
}

TEST (PngFile, SignatureAndAtomicWrite)
{
  RgbImage image;
  image.reset (3, 2, {10, 20, 30});
  // Every byte different (channel order, rows and columns all show), then decoded again by libpng's reader:
  // the picture the file holds is the image's, pixel for pixel.
  for (std::size_t i = 0; i < image.pixels.size (); ++i)
    image.pixels[i] = static_cast<std::uint8_t> (11 * i + 7);
  const std::vector<std::uint8_t> png = encodePng (image);
  png_image read;
  std::memset (&read, 0, sizeof (read));
  read.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE (png_image_begin_read_from_memory (&read, png.data (), png.size ())) << read.message;
  read.format = PNG_FORMAT_RGB;
  EXPECT_EQ (read.width, 3u);
  EXPECT_EQ (read.height, 2u);
  std::vector<std::uint8_t> decoded (PNG_IMAGE_SIZE (read));
  ASSERT_TRUE (png_image_finish_read (&read, nullptr, decoded.data (), 0, nullptr)) << read.message;
  EXPECT_EQ (decoded, image.pixels);
  const std::uint8_t signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  ASSERT_GE (png.size (), 8u);
  EXPECT_TRUE (std::equal (signature, signature + 8, png.begin ()));
  pcl_sparse_test::TempDir dir ("render");
  // IHDR: width 3, height 2 (big-endian), bit depth 8, colour type 2 (RGB).
  ASSERT_GE (png.size (), 26u);
  EXPECT_EQ (std::vector<std::uint8_t> (png.begin () + 12, png.begin () + 26),
             (std::vector<std::uint8_t>{'I', 'H', 'D', 'R', 0, 0, 0, 3, 0, 0, 0, 2, 8, 2}));
  savePng (dir.file ("a.png"), image);
  EXPECT_EQ (pcl_sparse_test::readBytes (dir.file ("a.png")), std::string (png.begin (), png.end ()));
  EXPECT_THROW (savePng (dir.file ("missing/a.png"), image), Error);
  EXPECT_THROW (encodePng (RgbImage ()), Error);
}

TEST (BitmapFont, DrawsDigitsInsideTheirBox)
{
  RgbImage image;
  image.reset (40, 10, kWhite);
  drawText (image, 1, 1, "1.5e-3", {0, 0, 0}, 1);
  EXPECT_EQ (textWidth ("1.5e-3", 1), 35);
  int ink = 0;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 40; ++x)
      if (!isBackground (image, x, y))
      {
        ++ink;
        EXPECT_TRUE (x >= 1 && x < 36 && y >= 1 && y < 8) << x << "," << y;
      }
  EXPECT_GT (ink, 30);
}
