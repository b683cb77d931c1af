#pragma once
/// \file tool_render.h
/// Pictures for the tools: what pcl_sparse_render draws (a mesh, points, marker dots, an error colour
/// bar), the options -size and -view, and one-call -png writers for the other tools. Not library API.

#include "tool_support.h"

#include <pcl_sparse/common/color_map.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/render/rgb_image.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_sparse
{
  namespace tools
  {
    /// Patch map colours: each vertex takes the colour of the patch where it is most central (smallest local
    /// |(x', y')|); vertices in no patch are grey.
    std::vector<RgbColor>
    centralPatchColors (const std::vector<Patch>& patches, std::size_t num_vertices);

    /// Image size and view of a picture (-size WxH, -view NAME|x,y,z).
    struct PictureOptions
    {
      int width = 800;                                       ///< pixels
      int height = 600;                                      ///< pixels
      Eigen::Vector3d toward = Eigen::Vector3d::UnitZ ();    ///< from the scene towards the viewer
    };

    /// Reads -size WxH (1 .. 16384 each) and -view (front side top iso or x,y,z); absent ones keep the
    /// defaults. Throws Error naming the option for a malformed value.
    PictureOptions
    parsePictureOptions (const CommandLine& args);

    /// What a picture shows: any of a mesh, points and marker dots, and optionally an error colour bar.
    struct Picture
    {
      const TriangleMesh* mesh = nullptr;           ///< drawn flat-shaded
      std::vector<RgbColor> vertex_colors;          ///< empty: grey
      bool crisp_colors = false;                    ///< nearest-corner colours (patch maps) instead of blending
      std::vector<Eigen::Vector3d> points;          ///< drawn as splats
      std::vector<Eigen::Vector3d> normals;         ///< empty: unshaded
      std::vector<RgbColor> point_colors;           ///< empty: grey
      std::vector<Eigen::Vector3d> markers;         ///< red dots on top
      double bar_max = 0.0;                         ///< > 0: draw the error bar, top value bar_max
      std::string bar_title = "dist/diag";          ///< title of the error bar
      Eigen::Vector3d toward_hint = Eigen::Vector3d::UnitZ ();  ///< the view, for colours that depend on it
    };

    /// A rendered picture and its figures.
    struct RenderedPicture
    {
      RgbImage image;            ///< the image
      std::size_t covered = 0;   ///< pixels covered by the surface
      int splat_radius = 0;      ///< splat radius used for points (0: no points)
      double seconds = 0.0;      ///< time to render (camera fit, raster, bar), not to load or save
    };

    /// Renders \a picture (camera fitted to everything drawn; the bar's strip left free when drawn).
    RenderedPicture
    renderPicture (const Picture& picture, const PictureOptions& options);

    /// Distance of each point to a triangle mesh (its exact nearest triangle, TriangleTree); NaN for a non-finite point.
    std::vector<double>
    distancesToSurface (const std::vector<Eigen::Vector3d>& points, const TriangleMesh& reference);

    /// Error-map colours of \a distances on a scale from 0 to their 99th percentile (the largest errors
    /// saturate rather than darken the rest); returns that scale divided by \a diagonal, the bar's top.
    double
    errorMapColors (const std::vector<double>& distances, double diagonal, std::vector<RgbColor>& colors);

    /// The help line of -png for the other tools.
    HelpLine
    pngHelpLine ();

    /// Checks -png, -size and -view before a tool does its work, so that a bad one is refused before any
    /// output is written. Does nothing without -png.
    /// \param[in] args the command line
    /// \throws Error naming the option
    void
    checkPngOptions (const CommandLine& args);

    /// -png OUT.png (with -size, -view) of the other tools: the mesh with \a colors (crisp: patch maps) and
    /// \a markers. Does nothing without -png.
    void
    writeMeshPng (const CommandLine& args, const TriangleMesh& mesh, const std::vector<RgbColor>& colors,
                  bool crisp, const std::vector<Eigen::Vector3d>& markers = {});

    /// Positions of a keypoint cloud, as markers for writeMeshPng.
    std::vector<Eigen::Vector3d>
    cloudPositions (const pcl::PointCloud<pcl::PointXYZI>& cloud);

    /// -png of a cloud with normals, shaded, at \a origin + each point. Does nothing without -png.
    void
    writeCloudPng (const CommandLine& args, const pcl::PointCloud<pcl::PointNormal>& cloud,
                   const Eigen::Vector3d& origin = Eigen::Vector3d::Zero ());

    /// -png of an error map: \a surface (a mesh, or points when it has no triangle) coloured by the
    /// per-vertex \a errors, with its colour bar in units of \a diagonal. Does nothing without -png.
    void
    writeErrorPng (const CommandLine& args, const TriangleMesh& surface, const std::vector<double>& errors,
                   double diagonal);
  } // namespace tools
} // namespace pcl_sparse
