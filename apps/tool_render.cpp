#include "tool_render.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/render/color_bar.h>
#include <pcl_sparse/render/png_file.h>
#include <pcl_sparse/render/render_camera.h>
#include <pcl_sparse/render/surface_renderer.h>
#include <pcl_sparse/geometry/triangle_tree.h>

#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pcl_sparse
{
  namespace tools
  {
    std::vector<RgbColor>
    centralPatchColors (const std::vector<Patch>& patches, std::size_t num_vertices)
    {
      std::vector<RgbColor> colors (num_vertices, {128, 128, 128});
      std::vector<double> best (num_vertices, std::numeric_limits<double>::infinity ());
      for (std::size_t i = 0; i < patches.size (); ++i)
        for (std::size_t k = 0; k < patches[i].size (); ++k)
        {
          const int v = patches[i].vertices[k];
          const double r = patches[i].local[k].head<2> ().norm ();
          if (r < best[v])
          {
            best[v] = r;
            colors[v] = categoryColor (i);
          }
        }
      return colors;
    }

    PictureOptions
    parsePictureOptions (const CommandLine& args)
    {
      PictureOptions options;
      if (args.has ("-size"))
      {
        const std::string size = args.value ("-size");
        // Digits only, at most 5 of them: sscanf's %d wrapped 4294967297 to 1 (undefined) and took " 8x+5".
        auto pixels = [] (const std::string& digits, int& out) {
          if (digits.empty () || digits.size () > 5 || !std::all_of (digits.begin (), digits.end (), [] (char c) { return c >= '0' && c <= '9'; }))
            return false;
          out = std::stoi (digits);
          return out >= 1 && out <= 16384;
        };
        const std::size_t x = size.find ('x');
        int w = 0, h = 0;
        if (x == std::string::npos || !pixels (size.substr (0, x), w) || !pixels (size.substr (x + 1), h))
          throw Error ("option -size: '" + size + "' is not WxH with 1 .. 16384 pixels each (e.g. 800x600)");
        options.width = w;
        options.height = h;
      }
      if (args.has ("-view"))
      {
        try
        {
          options.toward = viewDirectionFromName (args.value ("-view"));
        }
        catch (const Error& e)
        {
          throw Error (std::string ("option -") + e.what ());
        }
      }
      return options;
    }

    RenderedPicture
    renderPicture (const Picture& picture, const PictureOptions& options)
    {
      pcl::console::TicToc timer;
      timer.tic ();
      std::vector<Eigen::Vector3d> all = picture.points;
      if (picture.mesh)
        all.insert (all.end (), picture.mesh->vertices.begin (), picture.mesh->vertices.end ());
      const int bar = picture.bar_max > 0.0 ? colorBarWidth (options.height) : 0;
      const int view_width = std::max (1, options.width - bar);
      RenderOptions render_options;
      render_options.width = options.width;
      render_options.height = options.height;
      render_options.interpolate_colors = !picture.crisp_colors;
      SurfaceRenderer renderer;
      renderer.setOptions (render_options);
      renderer.setCamera (fitRenderCamera (all, options.toward, 0, 0, view_width, options.height));
      renderer.setInputMesh (picture.mesh, &picture.vertex_colors);
      renderer.setInputPoints (&picture.points, &picture.normals, &picture.point_colors);
      renderer.setMarkers (&picture.markers);
      RenderedPicture out;
      renderer.compute (out.image);
      if (bar > 0)
        drawColorBar (out.image, picture.bar_max, picture.bar_title);
      out.covered = renderer.getCoveredPixels ();
      out.splat_radius = renderer.getSplatRadius ();
      out.seconds = timer.toc () / 1000.0;
      return out;
    }

    std::vector<double>
    distancesToSurface (const std::vector<Eigen::Vector3d>& points, const TriangleMesh& reference)
    {
      if (reference.empty ())
        throw Error ("the reference surface has no triangle");
      const TriangleTree tree (reference);
      std::vector<double> distances (points.size (), std::nan (""));
      for (std::size_t i = 0; i < points.size (); ++i)
        if (points[i].allFinite ())
          distances[i] = tree.nearest (points[i]).distance;
      return distances;
    }

    double
    errorMapColors (const std::vector<double>& distances, double diagonal, std::vector<RgbColor>& colors)
    {
      std::vector<double> sorted;
      for (double d : distances)
        if (std::isfinite (d))
          sorted.push_back (d);
      double scale = 0.0;
      if (!sorted.empty ())
      {
        const std::size_t k = static_cast<std::size_t> (0.99 * (sorted.size () - 1));
        std::nth_element (sorted.begin (), sorted.begin () + k, sorted.end ());
        scale = sorted[k];
      }
      if (!(scale > 0.0))
        scale = diagonal > 0.0 ? 1e-12 * diagonal : 1e-12;
      colors.resize (distances.size ());
      for (std::size_t i = 0; i < distances.size (); ++i)
        colors[i] = std::isfinite (distances[i]) ? errorColor (distances[i] / scale) : RgbColor{128, 128, 128};
      return diagonal > 0.0 ? scale / diagonal : scale;
    }

    HelpLine
    pngHelpLine ()
    {
      return {"-png OUT.png", "also draw a picture (-size WxH, -view front|side|top|iso|x,y,z as pcl_sparse_render)"};
    }

    void
    checkPngOptions (const CommandLine& args)
    {
      if (!args.has ("-png"))
      {
        // They shape the -png picture only: alone they were accepted and did nothing.
        for (const char* option : {"-size", "-view"})
          if (args.has (option))
            throw Error (std::string ("option ") + option + " shapes the -png picture: give -png OUT.png too");
        return;
      }
      const std::string path = args.value ("-png");
      if (!hasExtension (path, ".png"))
        throw Error ("option -png: '" + path + "' must end in .png");
      parsePictureOptions (args);
    }

    namespace
    {
      /// Renders and writes \a picture to the -png path, with a line on the console.
      void
      savePicture (const CommandLine& args, const Picture& picture)
      {
        checkPngOptions (args);
        const std::string path = args.value ("-png");
        const RenderedPicture rendered = renderPicture (picture, parsePictureOptions (args));
        savePng (path, rendered.image);
        removeIfRunFails (path);
        // Not with --json (stdout holds the JSON object alone) or -q.
        if (!args.has ("--json") && !args.has ("-q"))
          pcl::console::print_info ("Wrote %s: %dx%d, %zu pixels covered\n", path.c_str (), rendered.image.width,
                                    rendered.image.height, rendered.covered);
      }
    } // namespace

    void
    writeMeshPng (const CommandLine& args, const TriangleMesh& mesh, const std::vector<RgbColor>& colors, bool crisp,
                  const std::vector<Eigen::Vector3d>& markers)
    {
      if (!args.has ("-png"))
        return;
      Picture picture;
      picture.mesh = &mesh;
      picture.vertex_colors = colors;
      picture.crisp_colors = crisp;
      picture.markers = markers;
      savePicture (args, picture);
    }

    std::vector<Eigen::Vector3d>
    cloudPositions (const pcl::PointCloud<pcl::PointXYZI>& cloud)
    {
      std::vector<Eigen::Vector3d> positions;
      for (const pcl::PointXYZI& p : cloud)
        positions.push_back (p.getVector3fMap ().cast<double> ());
      return positions;
    }

    void
    writeCloudPng (const CommandLine& args, const pcl::PointCloud<pcl::PointNormal>& cloud, const Eigen::Vector3d& origin)
    {
      if (!args.has ("-png"))
        return;
      Picture picture;
      picture.points.reserve (cloud.size ());
      picture.normals.reserve (cloud.size ());
      for (const pcl::PointNormal& p : cloud)
      {
        picture.points.push_back (origin + p.getVector3fMap ().cast<double> ());
        picture.normals.push_back (p.getNormalVector3fMap ().cast<double> ());
      }
      savePicture (args, picture);
    }

    void
    writeErrorPng (const CommandLine& args, const TriangleMesh& surface, const std::vector<double>& errors, double diagonal)
    {
      if (!args.has ("-png"))
        return;
      Picture picture;
      std::vector<RgbColor> colors;
      picture.bar_max = errorMapColors (errors, diagonal, colors);
      if (picture.bar_max <= 0.0)
        picture.bar_max = 1e-12;
      if (surface.empty ())
      {
        picture.points = surface.vertices;
        picture.point_colors = colors;
      }
      else
      {
        picture.mesh = &surface;
        picture.vertex_colors = colors;
      }
      savePicture (args, picture);
    }
  } // namespace tools
} // namespace pcl_sparse
