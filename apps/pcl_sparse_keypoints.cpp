/// pcl_sparse_keypoints: Harris 3D keypoints of a triangle mesh (Sipiran & Bustos; docs/METHOD.md step 3).
///
///   pcl_sparse_keypoints IN OUT.{pcd,ply} [-fraction F | -cluster C] [-rings K | -adaptive A] [-k K]
///                        [-responses RESP.ply] [--json] [-q]

#include "tool_input.h"
#include "tool_render.h"
#include "tool_support.h"

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/color_map.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/keypoints/harris_keypoint3d_mesh.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/exceptions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const tools::ToolDescription kTool = {
    "pcl_sparse_keypoints", "IN OUT.{pcd,ply} [options]",
    {
      {"IN", "a triangle mesh (.obj .off .ply .stl) or a scan (.pcd .xyz, .ply of points)"},
      {"OUT", "keypoints as PointXYZI (intensity = response), decreasing response"},
      {"-viewpoint X,Y,Z", "scans: the sensor position the normals face (points exactly there dropped)"},
      {"-fraction F", "keep F x #vertices 1-ring local maxima (default 0.01)"},
      {"-cluster C", "instead: keep local maxima at least C x bbox diagonal apart"},
      {"-rings K", "fixed K-ring neighbourhoods (the paper's option: 2)"},
      {"-adaptive A", "adaptive rings up to radius A x bbox diagonal (default 0.01)"},
      {"-k K", "Harris constant in [0, 0.25] (default 0.04)"},
      {"-responses R.ply", "also write the mesh coloured by response percentile"},
      {"", "(dark blue = low, yellow = high, grey = no response)"},
      {"-preset P", "default or paper: accepted as by every tool; both use these keypoints"},
      tools::pngHelpLine (),
      {"--json", "print one JSON object on stdout"},
      {"-q", "quiet"},
    },
    2, {"-fraction", "-cluster", "-rings", "-adaptive", "-k", "-responses", "-viewpoint", "-preset", "-png", "-size", "-view"},
    {"--json", "-q"}};

  /// Colours by percentile of the response (the raw values span many orders of magnitude).
  std::vector<RgbColor>
  responseColors (const std::vector<double>& responses)
  {
    const std::vector<int> order = orderVerticesByResponse (responses);
    std::size_t finite = 0;
    for (double r : responses)
      finite += !std::isnan (r);
    std::vector<RgbColor> colors (responses.size (), RgbColor{128, 128, 128});
    for (std::size_t rank = 0; rank < finite; ++rank)
      colors[order[rank]] = viridisColor (finite > 1 ? 1.0 - static_cast<double> (rank) / static_cast<double> (finite - 1) : 1.0);
    return colors;
  }

  /// Whether the binary PLY at \a path holds \a points records of x y z intensity (16 bytes) after its
  /// header: PCL's PLY writer returns success on a full disk, and a cut-short file was kept.
  bool
  binaryPlyHoldsItsPoints (const std::string& path, std::size_t points)
  {
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size (path, error);
    std::ifstream in (path, std::ios::binary);
    std::string header, line;
    while (!error && in && std::getline (in, line))
    {
      header += line + '\n';
      if (line == "end_header")
        return size >= header.size () + 16 * points;
    }
    return false;
  }

  void
  saveKeypoints (const std::string& path, const pcl::PointCloud<pcl::PointXYZI>& keypoints)
  {
    writeFileAtomically (path, [&] (const std::string& temporary) {
      // PCL's own messages name the temporary file or none ("[pcl::PCDWriter::writeBinary] Error during open!"),
      // and it says "Input point cloud has no data!" on an empty cloud, a run that succeeded: it is silenced,
      // and a failure is writeFileAtomically's error, which names the output.
      const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel ();
      pcl::console::setVerbosityLevel (pcl::console::L_ALWAYS);
      bool written = false;
      try
      {
        if (tools::hasExtension (path, ".pcd"))
          written = pcl::io::savePCDFileBinary (temporary, keypoints) == 0;
        else if (keypoints.empty ())
        {
          // PCL refuses to write an empty cloud; an empty keypoint set is a valid answer, written by hand.
          FILE* file = std::fopen (temporary.c_str (), "wb");
          if (file)
          {
            const int ok = std::fputs ("ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                                       "property float y\nproperty float z\nproperty float intensity\nend_header\n", file);
            written = std::fclose (file) == 0 && ok >= 0;
          }
        }
        else
          written = pcl::io::savePLYFileBinary (temporary, keypoints) == 0 &&
                    binaryPlyHoldsItsPoints (temporary, keypoints.size ());
      }
      catch (const pcl::PCLException&)  // PCDWriter throws when it cannot open the file
      {
        written = false;
      }
      pcl::console::setVerbosityLevel (level);
      return written;
    });
  }
} // namespace

int
main (int argc, char** argv)
{
  return tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    const bool json = args.has ("--json");
    const bool quiet = args.has ("-q");
    if (quiet || json)
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
    args.expectPositional (2, "IN and OUT");
    tools::checkPngOptions (args);
    encoderPresetFromName (args.value ("-preset", "default"));  // checked; Harris 3D is the same in both
    const std::string input = args.positional ()[0], output = args.positional ()[1];
    if (!tools::hasExtension (output, ".pcd") && !tools::hasExtension (output, ".ply"))
      throw Error (output + ": output must end in .pcd or .ply");
    const std::string responses_path = args.value ("-responses");
    if (args.has ("-responses") && !tools::hasExtension (responses_path, ".ply"))
      throw Error (responses_path + ": -responses output must end in .ply");
    tools::checkOutputPaths ({input}, {output, responses_path, args.value ("-png")});

    Harris3DOptions options;
    const bool has_rings = args.integer ("-rings", options.rings, tools::Range::closed (1, 1000));
    if (args.number ("-adaptive", options.adaptive_fraction, tools::Range::above (0.0)) && has_rings)
      throw Error ("options -rings and -adaptive exclude each other");
    const bool has_fraction = args.number ("-fraction", options.selection_fraction, tools::Range::aboveUpTo (0.0, 1.0));
    if (args.number ("-cluster", options.cluster_fraction, tools::Range::above (0.0)))
    {
      if (has_fraction)
        throw Error ("options -fraction and -cluster exclude each other");
      options.selection = Harris3DSelection::Clustering;
    }
    args.number ("-k", options.k, tools::Range::closed (0.0, 0.25));
    validateHarris3DOptions (options);

    pcl::console::TicToc total;
    total.tic ();
    Eigen::Vector3d viewpoint;
    const bool has_viewpoint = tools::parseViewpoint (args, viewpoint);
    const tools::SurfaceInput surface_input = tools::loadSurfaceInput (input, has_viewpoint ? &viewpoint : nullptr);
    if (!quiet && !json)
      pcl::console::print_info ("%s: %zu %s\n", input.c_str (), surface_input.points (),
                                surface_input.mesh ? "vertices" : "points");
    tools::refuseViewpointOnMesh (has_viewpoint, surface_input.mesh != nullptr, input);

    pcl::console::TicToc timer;
    timer.tic ();
    HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
    tools::setSurfaceInput (harris, surface_input);
    if (has_viewpoint)
      harris.setViewPoint (viewpoint.x (), viewpoint.y (), viewpoint.z ());
    harris.setOptions (options);
    pcl::PointCloud<pcl::PointXYZI> keypoints;
    harris.compute (keypoints);
    const double harris_seconds = timer.toc () / 1000.0;
    // The surface Harris ran on: the mesh, or a scan's neighbourhood surface (moved to the file's frame).
    const TriangleMesh::ConstPtr mesh = tools::surfaceInInputFrame (harris);
    if (harris.getResponses ().size () != mesh->numVertices ())
      throw Error (input + ": Harris 3D failed on this mesh");

    saveKeypoints (output, keypoints);
    tools::removeIfRunFails (output);
    tools::writeMeshPng (args, *mesh, {}, false, tools::cloudPositions (keypoints));
    if (!responses_path.empty ())
    {
      saveColoredMesh (responses_path, *mesh, responseColors (harris.getResponses ()));
      tools::removeIfRunFails (responses_path);
    }
    const double seconds = total.toc () / 1000.0;

    if (json)
      tools::JsonObject ()
        .add ("input", input)
        .add ("output", output)
        .add ("vertices", mesh->numVertices ())
        .add ("keypoints", keypoints.size ())
        .addSeconds ("harris_seconds", harris_seconds)
        .addSeconds ("seconds", seconds)
        .print ();
    else if (!quiet)
    {
      pcl::console::print_info ("Harris 3D: ");
      pcl::console::print_value ("%zu", keypoints.size ());
      pcl::console::print_info (" keypoints in ");
      pcl::console::print_value ("%.3f", harris_seconds);
      pcl::console::print_info (" s (total %.3f s) -> %s\n", seconds, output.c_str ());
    }
    return 0;
  });
}
