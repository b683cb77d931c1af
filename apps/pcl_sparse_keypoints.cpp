/// pcl_sparse_keypoints: Harris 3D keypoints of a triangle mesh (Sipiran & Bustos; METHOD.md step 3).
///
///   pcl_sparse_keypoints MESH OUT.{pcd,ply} [-fraction F | -cluster C] [-rings K | -adaptive A] [-k K]
///                        [-responses RESP.ply] [--json] [-q]

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/keypoints/harris_keypoint3d_mesh.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const char* kProgram = "pcl_sparse_keypoints";

  void
  printHelp (const char* program)
  {
    pcl::console::print_error ("Syntax is: %s MESH OUT.{pcd,ply} [options]\n", program);
    pcl::console::print_info ("  MESH                a triangle mesh: .obj .off .ply .stl\n");
    pcl::console::print_info ("  OUT                 keypoints as PointXYZI (intensity = response), decreasing response\n");
    pcl::console::print_info ("  -fraction F         keep F x #vertices 1-ring local maxima (default 0.01)\n");
    pcl::console::print_info ("  -cluster C          instead: keep local maxima at least C x bbox diagonal apart\n");
    pcl::console::print_info ("  -rings K            fixed K-ring neighbourhoods (the paper's option: 2)\n");
    pcl::console::print_info ("  -adaptive A         adaptive rings up to radius A x bbox diagonal (default 0.01)\n");
    pcl::console::print_info ("  -k K                Harris constant (default 0.04)\n");
    pcl::console::print_info ("  -responses R.ply    also write the mesh coloured by response percentile\n");
    pcl::console::print_info ("                      (dark blue = low, yellow = high, grey = no response)\n");
    pcl::console::print_info ("  --json              print one JSON object on stdout\n");
    pcl::console::print_info ("  -q                  quiet\n");
  }

  bool
  hasExtension (const std::string& path, const std::string& extension)
  {
    if (path.size () <= extension.size ())
      return false;
    std::string tail = path.substr (path.size () - extension.size ());
    std::transform (tail.begin (), tail.end (), tail.begin (), [] (unsigned char c) { return std::tolower (c); });
    return tail == extension;
  }

  std::string
  jsonString (const std::string& text)
  {
    std::string out = "\"";
    for (const unsigned char c : text)
    {
      if (c == '"' || c == '\\')
        out += std::string ("\\") + static_cast<char> (c);
      else if (c < 0x20)
      {
        char buffer[8];
        std::snprintf (buffer, sizeof (buffer), "\\u%04x", c);
        out += buffer;
      }
      else
        out += static_cast<char> (c);
    }
    return out + "\"";
  }

  /// Value of option \a name as a number; throws Error naming the option when it is missing or malformed.
  /// Returns false when the option is absent.
  bool
  parseNumber (int argc, char** argv, const char* name, double& value)
  {
    const int i = pcl::console::find_argument (argc, argv, name);
    if (i < 0)
      return false;
    if (i + 1 >= argc)
      throw Error (std::string ("option ") + name + " needs a value");
    const std::string text = argv[i + 1];
    std::size_t used = 0;
    try
    {
      value = std::stod (text, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used == 0 || used != text.size () || !std::isfinite (value))
      throw Error (std::string ("option ") + name + ": '" + text + "' is not a number");
    return true;
  }

  /// Viridis-like map of t in [0, 1] (perceptually ordered, readable in grey too).
  std::array<std::uint8_t, 3>
  colormap (double t)
  {
    static const double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
    t = std::clamp (t, 0.0, 1.0) * 4.0;
    const int i = std::min (3, static_cast<int> (t));
    const double f = t - i;
    std::array<std::uint8_t, 3> rgb;
    for (int c = 0; c < 3; ++c)
      rgb[c] = static_cast<std::uint8_t> (std::lround (stops[i][c] + f * (stops[i + 1][c] - stops[i][c])));
    return rgb;
  }

  /// Colours by percentile of the response (the raw values span many orders of magnitude).
  std::vector<std::array<std::uint8_t, 3>>
  responseColors (const std::vector<double>& responses)
  {
    const std::vector<int> order = orderVerticesByResponse (responses);
    std::size_t finite = 0;
    for (double r : responses)
      finite += !std::isnan (r);
    std::vector<std::array<std::uint8_t, 3>> colors (responses.size (), std::array<std::uint8_t, 3>{128, 128, 128});
    for (std::size_t rank = 0; rank < finite; ++rank)
      colors[order[rank]] = colormap (finite > 1 ? 1.0 - static_cast<double> (rank) / static_cast<double> (finite - 1) : 1.0);
    return colors;
  }

  void
  saveKeypoints (const std::string& path, const pcl::PointCloud<pcl::PointXYZI>& keypoints)
  {
    writeFileAtomically (path, [&] (const std::string& temporary) {
      if (hasExtension (path, ".pcd"))
        return pcl::io::savePCDFileBinary (temporary, keypoints) == 0;
      // PCL refuses to write an empty cloud; an empty keypoint set is a valid answer, written by hand.
      if (keypoints.empty ())
      {
        FILE* file = std::fopen (temporary.c_str (), "wb");
        if (!file)
          return false;
        const int ok = std::fputs ("ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                                   "property float y\nproperty float z\nproperty float intensity\nend_header\n", file);
        return std::fclose (file) == 0 && ok >= 0;
      }
      return pcl::io::savePLYFileBinary (temporary, keypoints) == 0;
    });
  }
} // namespace

int
main (int argc, char** argv)
{
  if (argc < 3 || pcl::console::find_switch (argc, argv, "-h") || pcl::console::find_switch (argc, argv, "--help"))
  {
    printHelp (argv[0]);
    return argc < 3 && !(argc == 2 && (std::string (argv[1]) == "-h" || std::string (argv[1]) == "--help")) ? 1 : 0;
  }
  const bool json = pcl::console::find_switch (argc, argv, "--json");
  const bool quiet = pcl::console::find_switch (argc, argv, "-q");
  if (quiet || json)
    pcl::console::setVerbosityLevel (pcl::console::L_ERROR);

  try
  {
    // Positional arguments and unknown options.
    const std::set<std::string> valued = {"-fraction", "-cluster", "-rings", "-adaptive", "-k", "-responses"};
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
      if (arg == "--json" || arg == "-q")
        continue;
      if (valued.count (arg))
      {
        ++i;
        continue;
      }
      if (arg.size () > 1 && arg[0] == '-' && !std::isdigit (static_cast<unsigned char> (arg[1])))
        throw Error ("unknown option '" + arg + "' (see --help)");
      files.push_back (arg);
    }
    if (files.size () != 2)
      throw Error ("expected MESH and OUT, got " + std::to_string (files.size ()) + " file arguments (see --help)");
    const std::string input = files[0], output = files[1];
    if (!hasExtension (output, ".pcd") && !hasExtension (output, ".ply"))
      throw Error (output + ": output must end in .pcd or .ply");
    std::string responses_path;
    if (pcl::console::find_argument (argc, argv, "-responses") >= 0)
    {
      const int i = pcl::console::find_argument (argc, argv, "-responses");
      if (i + 1 >= argc)
        throw Error ("option -responses needs a file name");
      responses_path = argv[i + 1];
      if (!hasExtension (responses_path, ".ply"))
        throw Error (responses_path + ": -responses output must end in .ply");
    }

    Harris3DOptions options;
    double value = 0.0;
    const bool has_rings = parseNumber (argc, argv, "-rings", value);
    if (has_rings)
    {
      if (value < 1 || value != std::floor (value) || value > 1000)
        throw Error ("option -rings must be a whole number >= 1");
      options.rings = static_cast<int> (value);
    }
    if (parseNumber (argc, argv, "-adaptive", value))
    {
      if (has_rings)
        throw Error ("options -rings and -adaptive exclude each other");
      if (!(value > 0.0))
        throw Error ("option -adaptive must be > 0");
      options.adaptive_fraction = value;
    }
    const bool has_fraction = parseNumber (argc, argv, "-fraction", value);
    if (has_fraction)
    {
      if (!(value > 0.0 && value <= 1.0))
        throw Error ("option -fraction must be in (0, 1]");
      options.selection_fraction = value;
    }
    if (parseNumber (argc, argv, "-cluster", value))
    {
      if (has_fraction)
        throw Error ("options -fraction and -cluster exclude each other");
      if (!(value > 0.0))
        throw Error ("option -cluster must be > 0");
      options.selection = Harris3DSelection::Clustering;
      options.cluster_fraction = value;
    }
    if (parseNumber (argc, argv, "-k", value))
      options.k = value;
    validateHarris3DOptions (options);

    pcl::console::TicToc total;
    total.tic ();
    const auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (input));
    if (!quiet && !json)
      pcl::console::print_info ("%s: %zu vertices, %zu faces\n", input.c_str (), mesh->numVertices (), mesh->numTriangles ());

    pcl::console::TicToc timer;
    timer.tic ();
    HarrisKeypoint3DMesh harris;
    harris.setInputMesh (mesh);
    harris.setOptions (options);
    pcl::PointCloud<pcl::PointXYZI> keypoints;
    harris.compute (keypoints);
    const double harris_seconds = timer.toc () / 1000.0;
    if (harris.getResponses ().size () != mesh->numVertices ())
      throw Error (input + ": Harris 3D failed on this mesh");

    saveKeypoints (output, keypoints);
    if (!responses_path.empty ())
      saveColoredMesh (responses_path, *mesh, responseColors (harris.getResponses ()));
    const double seconds = total.toc () / 1000.0;

    if (json)
      std::printf ("{\"input\": %s, \"output\": %s, \"vertices\": %zu, \"keypoints\": %zu, \"harris_seconds\": %.6f, "
                   "\"seconds\": %.6f}\n",
                   jsonString (input).c_str (), jsonString (output).c_str (), mesh->numVertices (), keypoints.size (),
                   harris_seconds, seconds);
    else if (!quiet)
    {
      pcl::console::print_info ("Harris 3D: ");
      pcl::console::print_value ("%zu", keypoints.size ());
      pcl::console::print_info (" keypoints in ");
      pcl::console::print_value ("%.3f", harris_seconds);
      pcl::console::print_info (" s (total %.3f s) -> %s\n", seconds, output.c_str ());
    }
  }
  catch (const Error& e)
  {
    pcl::console::print_error ("%s: %s\n", kProgram, e.what ());
    return 1;
  }
  catch (const std::exception& e)
  {
    pcl::console::print_error ("%s: %s\n", kProgram, e.what ());
    return 1;
  }
  return 0;
}
