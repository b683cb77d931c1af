/// pcl_sparse_render: draws a mesh, a scan or a model (.psm, resampled) into a PNG, headless: a software
/// rasteriser with a depth buffer and Lambert shading (src/render), no X server, no GPU.
///
///   pcl_sparse_render IN OUT.png [-size WxH] [-view front|side|top|iso|x,y,z]
///                     [-color plain|normal|patch|error|height|rgb] [-ref MESH] [-n N] [--json] [-q]

#include "tool_input.h"
#include "tool_render.h"
#include "tool_resampling.h"
#include "tool_support.h"

#include <pcl_sparse/common/color_map.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/memory_limit.h>

#include <Eigen/Geometry>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/render/png_file.h>
#include <pcl_sparse/render/render_camera.h>

#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const tools::ToolDescription kTool = {
    "pcl_sparse_render", "IN OUT.png [options]",
    {
      {"IN", "a triangle mesh (.obj .off .ply .stl), a scan (.pcd .xyz, .ply of points) or a model (.psm)"},
      {"OUT.png", "the picture (8-bit RGB; the same input gives the same bytes)"},
      {"-size WxH", "image size in pixels (default 800x600)"},
      {"-view V", "front (looking along -z, default), side (-x), top (-y), iso, or x,y,z towards the viewer"},
      {"-color C", "plain (grey, default), normal (normal direction as RGB), patch (one colour per patch),"},
      {"", "error (distance to -ref, colour bar in units of its bbox diagonal), height (along the image's"},
      {"", "up axis), rgb (the scan's or the model's colours)"},
      {"-ref MESH", "reference surface of -color error"},
      {"-n N", "points resampled from a .psm (default 4 x the model's input vertices, at least W x H)"},
      {"--json", "print one JSON object on stdout (seconds, pixels covered)"},
      {"-q", "quiet"},
    },
    2, {"-size", "-view", "-color", "-ref", "-n"}, {"--json", "-q"}};

  /// The scene before colouring: a mesh, or points with normals, in the file's frame.
  struct Scene
  {
    TriangleMesh::ConstPtr mesh;
    std::vector<Eigen::Vector3d> points, normals;
    std::vector<RgbColor> rgb;        ///< the file's colours, if any
    std::vector<int> point_patches;   ///< .psm: the patch of each point
    std::size_t patches = 0;
  };

  /// The points of \a model resampled as PointT (pcl::PointNormal, or pcl::PointXYZRGBNormal to carry the
  /// model's colours into Scene::rgb as a scan's are).
  template <typename PointT>
  Scene
  resampleModelScene (const SparseSurfaceModel::ConstPtr& model, std::size_t count)
  {
    SparseSurfaceResampling<PointT> resampling;
    resampling.setPointCount (count);
    const tools::LocalCloud<PointT> local = tools::resampleInLocalFrame (resampling, model);
    Scene scene;
    for (const PointT& p : local.cloud)
    {
      scene.points.push_back (local.origin + p.getVector3fMap ().template cast<double> ());
      scene.normals.push_back (p.getNormalVector3fMap ().template cast<double> ());
      if constexpr (pcl::traits::has_color_v<PointT>)
        scene.rgb.push_back ({p.r, p.g, p.b});
    }
    scene.point_patches = resampling.getPointPatches ();
    scene.patches = model->numPatches ();
    return scene;
  }

  /// A model's scene; \a colours: with the model's colours (-color rgb), which it must code.
  Scene
  loadModelScene (const std::string& path, std::size_t count, const tools::PictureOptions& picture, bool colours)
  {
    auto model = std::make_shared<SparseSurfaceModel> (loadModel (path));
    // Colour as pcl_sparse_decode writes it: the model codes r, g and b (resampledExtraField).
    if (colours && tools::resampledExtraField (model->attribute_channels) != CloudExtraField::Colour)
      throw Error (path + ": -color rgb: the model has no colour channel (it codes no r g b attributes)");
    if (count == 0)
      count = std::max<std::size_t> (4 * model->num_input_vertices, static_cast<std::size_t> (picture.width) * picture.height);
    count = std::min (count, SparseSurfaceResampling<pcl::PointNormal>::max_points);
    // The cloud, then its points, normals and patches again for the picture: about 170 bytes a point
    // (190 with colours: the larger point, and the colours again).
    checkFitsInMemory ((colours ? 190.0 : 170.0) * static_cast<double> (count),
                       "the " + std::to_string (count) + " points of the picture (-size, -n)");
    return colours ? resampleModelScene<pcl::PointXYZRGBNormal> (model, count)
                   : resampleModelScene<pcl::PointNormal> (model, count);
  }

  Scene
  loadScene (const std::string& path, std::size_t count, const tools::PictureOptions& picture, bool colours)
  {
    if (tools::hasExtension (path, ".psm"))
      return loadModelScene (path, count, picture, colours);
    const tools::SurfaceInput input = tools::loadSurfaceInput (path);
    Scene scene;
    if (input.mesh)
    {
      scene.mesh = input.mesh;
      return scene;
    }
    const ScanCloud& scan = *input.scan;
    scene.points = input.worldPositions ();
    if (!scan.normals.empty ())
      scene.normals = scan.normals;
    else
      scene.normals = buildCloudSurface (scan).normals;  // oriented PCA normals on the scan's neighbourhoods
    for (std::uint32_t c : scan.colors)
      scene.rgb.push_back ({static_cast<std::uint8_t> (c >> 16), static_cast<std::uint8_t> (c >> 8), static_cast<std::uint8_t> (c)});
    return scene;
  }

  /// Patch colours of a mesh or scan: the patches the encoder would grow; each vertex takes the patch where it
  /// is most central. A scan is replaced by the neighbourhood surface the patches grew on.
  void
  patchColors (const std::string& path, Scene& scene, tools::Picture& picture)
  {
    if (!scene.point_patches.empty ())
    {
      for (int p : scene.point_patches)
        picture.point_colors.push_back (p >= 0 ? categoryColor (static_cast<std::size_t> (p)) : RgbColor{128, 128, 128});
      return;
    }
    FeatureAwarePatchSampling<pcl::PointXYZ> sampling;
    tools::setSurfaceInput (sampling, tools::loadSurfaceInput (path));
    std::vector<Patch> patches;
    sampling.compute (patches);
    scene.mesh = tools::surfaceInInputFrame (sampling);
    scene.points.clear ();
    scene.normals.clear ();
    scene.patches = patches.size ();
    picture.vertex_colors = tools::centralPatchColors (patches, scene.mesh->vertices.size ());
    picture.crisp_colors = true;
  }

  /// Vertex normals of a mesh: area-weighted sums of its face normals.
  std::vector<Eigen::Vector3d>
  vertexNormals (const TriangleMesh& mesh)
  {
    std::vector<Eigen::Vector3d> normals (mesh.vertices.size (), Eigen::Vector3d::Zero ());
    for (const Eigen::Vector3i& t : mesh.triangles)
    {
      const Eigen::Vector3d n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross (mesh.vertices[t[2]] - mesh.vertices[t[0]]);
      for (int k = 0; k < 3; ++k)
        normals[t[k]] += n;
    }
    return normals;
  }

  /// Colours \a picture by \a mode; \a ref is the reference mesh of the error map.
  void
  colorScene (const std::string& mode, const std::string& path, const std::string& ref, Scene& scene, tools::Picture& picture)
  {
    if (mode == "patch")
      patchColors (path, scene, picture);
    const std::vector<Eigen::Vector3d>& positions = scene.mesh ? scene.mesh->vertices : scene.points;
    std::vector<RgbColor> colors;
    if (mode == "error")
    {
      const TriangleMesh reference = loadTriangleMesh (ref);
      picture.bar_max = tools::errorMapColors (tools::distancesToSurface (positions, reference),
                                               boundingBoxDiagonal (reference), colors);
    }
    else if (mode == "normal")
    {
      const std::vector<Eigen::Vector3d> normals = scene.mesh ? vertexNormals (*scene.mesh) : scene.normals;
      colors.assign (positions.size (), {200, 200, 200});
      for (std::size_t i = 0; i < normals.size (); ++i)
        if (normals[i].norm () > 0.0)
          for (int c = 0; c < 3; ++c)
            colors[i][c] = static_cast<std::uint8_t> (std::lround (127.5 * (1.0 + normals[i].normalized ()[c])));
    }
    else if (mode == "height")
    {
      const Eigen::Vector3d up = fitRenderCamera (positions, picture.toward_hint, 0, 0, 1, 1).up;
      double lo = std::numeric_limits<double>::infinity (), hi = -lo;
      for (const Eigen::Vector3d& p : positions)
        if (p.allFinite ())
        {
          lo = std::min (lo, up.dot (p));
          hi = std::max (hi, up.dot (p));
        }
      for (const Eigen::Vector3d& p : positions)
        colors.push_back (viridisColor (hi > lo ? (up.dot (p) - lo) / (hi - lo) : 0.0));
    }
    else if (mode == "rgb")
    {
      if (scene.rgb.size () != positions.size () || positions.empty ())
        throw Error (path + ": -color rgb: the input has no colours");
      colors = scene.rgb;
    }
    else if (mode != "plain" && mode != "patch")
      throw Error ("option -color: '" + mode + "' is not plain, normal, patch, error, height or rgb");
    if (colors.empty ())
      return;
    (scene.mesh ? picture.vertex_colors : picture.point_colors) = colors;
  }
} // namespace

int
main (int argc, char** argv)
{
  return tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    args.expectPositional (2, "IN and OUT.png");
    const std::string& input = args.positional ()[0];
    const std::string& output = args.positional ()[1];
    const bool json = args.has ("--json"), quiet = args.has ("-q");
    if (quiet || json)
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
    if (!tools::hasExtension (output, ".png"))
      throw Error (output + ": the output must be a .png file");
    tools::checkOutputPaths ({input}, {output});
    if (!tools::hasExtension (input, ".psm") && !tools::isSurfaceInputExtension (input))
      throw Error (input + ": unknown input extension (a mesh .obj .off .ply .stl, a cloud .pcd .xyz .ply or a model .psm)");
    const tools::PictureOptions options = tools::parsePictureOptions (args);
    const std::string mode = args.value ("-color", "plain");
    if (mode == "error" && !args.has ("-ref"))
      throw Error ("option -color error needs -ref MESH");
    if (args.has ("-ref") && mode != "error")
      throw Error ("option -ref is only used with -color error");
    std::size_t count = 0;
    if (args.integer ("-n", count, tools::Range::closed (1, SparseSurfaceResampling<pcl::PointNormal>::max_points)) &&
        !tools::hasExtension (input, ".psm"))  // a mesh or scan is drawn as it is: -n did nothing
      throw Error ("option -n resamples a model (.psm); " + input + " is drawn as it is");

    pcl::console::TicToc total;
    total.tic ();
    Scene scene = loadScene (input, count, options, mode == "rgb");
    tools::Picture picture;
    picture.toward_hint = options.toward;
    colorScene (mode, input, args.value ("-ref"), scene, picture);
    picture.mesh = scene.mesh.get ();
    picture.points = scene.points;
    picture.normals = scene.normals;
    const tools::RenderedPicture rendered = tools::renderPicture (picture, options);
    savePng (output, rendered.image);
    tools::removeIfRunFails (output);  // still undone if stdout cannot take the report
    const double seconds = total.toc () / 1000.0;
    const std::size_t items = scene.mesh ? scene.mesh->triangles.size () : scene.points.size ();
    if (json)
      tools::JsonObject ()
        .add ("input", input)
        .add ("output", output)
        .add ("width", rendered.image.width)
        .add ("height", rendered.image.height)
        .add (scene.mesh ? "triangles" : "points", items)
        .add ("pixels_covered", rendered.covered)
        .add ("splat_radius", rendered.splat_radius)
        .add ("error_scale", picture.bar_max)
        .addSeconds ("render_seconds", rendered.seconds)
        .addSeconds ("seconds", seconds)
        .print ();
    else if (!quiet)
      std::printf ("%s: %dx%d, %zu %s, %zu pixels covered, render %.3f s, total %.3f s\n", output.c_str (),
                   rendered.image.width, rendered.image.height, items, scene.mesh ? "triangles" : "points",
                   rendered.covered, rendered.seconds, seconds);
    return 0;
  });
}
