/// pcl_sparse_resample: a mesh (encoded first) or a saved model (.psm) to a point cloud with analytic
/// normals and curvature, at any density (METHOD.md step 12).
///
///   pcl_sparse_resample IN OUT [-n N | -density D | -spacing S] [-rho R] [-f F] [-angles K] [-seed S]
///                       [-threads T] [-ascii] [-q] [--json]

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  void
  printHelp (const char* program)
  {
    pcl::console::print_error ("Syntax is: %s IN OUT [options]\n", program);
    pcl::console::print_info ("  IN            a triangle mesh (.obj .off .ply .stl), encoded first, or a saved model (.psm)\n");
    pcl::console::print_info ("  OUT           the cloud: .pcd (binary unless -ascii) or .ply; fields x y z nx ny nz curvature\n");
    pcl::console::print_info ("                (curvature = signed mean curvature, 1/length, positive where convex)\n");
    pcl::console::print_info ("  -n N          exactly N points (default: 4 x the input vertex count)\n");
    pcl::console::print_info ("  -density D    D points per unit of surface area instead\n");
    pcl::console::print_info ("  -spacing S    mean spacing S between neighbouring points instead (density 1 / S^2)\n");
    pcl::console::print_info ("  -rho R        encoder: patch area bound rho (default: 0.001, paper)\n");
    pcl::console::print_info ("  -f F          encoder: Nyquist factor f in [0, 1] (default: 0.5, paper)\n");
    pcl::console::print_info ("  -angles K     encoder: footprint angles (default: 64 here, 16 in the encoder: finer footprints\n");
    pcl::console::print_info ("                overshoot open borders and sharp edges less, halving the distance error)\n");
    pcl::console::print_info ("  -seed S       seed of the sampling (default: 42)\n");
    pcl::console::print_info ("  -threads T    threads (default: all; the cloud does not depend on it)\n");
    pcl::console::print_info ("  -ascii        write ascii instead of binary\n");
    pcl::console::print_info ("  -q            quiet: no progress or messages\n");
    pcl::console::print_info ("  --json        print one JSON object with counts and timings on stdout\n");
  }

  std::string
  lowerExtension (const std::string& path)
  {
    const std::size_t dot = path.find_last_of ('.');
    const std::size_t slash = path.find_last_of ('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
      return "";
    std::string extension = path.substr (dot);
    std::transform (extension.begin (), extension.end (), extension.begin (), [] (unsigned char c) { return std::tolower (c); });
    return extension;
  }

  /// Value of option \a name parsed as a number; throws naming the option when it is present but malformed.
  bool
  numberOption (int argc, char** argv, const char* name, double& value)
  {
    for (int i = 1; i < argc; ++i)
      if (std::string (argv[i]) == name)
      {
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
    return false;
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

  struct Settings
  {
    std::string input, output;
    int mode = 0;  ///< 0 default count, 1 count, 2 density, 3 spacing
    double count = 0.0, density = 0.0, spacing = 0.0;
    SparseSurfaceEncoderOptions encoder;
    SparseSurfaceResamplingOptions resampling;
    int threads = 0;
    bool binary = true, quiet = false, json = false;
  };

  Settings
  parseSettings (int argc, char** argv)
  {
    Settings s;
    // Positional arguments: the first two arguments that are not options or option values.
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "-n" || a == "-density" || a == "-spacing" || a == "-rho" || a == "-f" || a == "-seed" || a == "-threads" ||
          a == "-angles")
        ++i;
      else if (a == "-ascii" || a == "-q" || a == "--json")
        continue;
      else if (!a.empty () && a[0] == '-')
        throw Error ("unknown option " + a + " (see -h)");
      else
        positional.push_back (a);
    }
    if (positional.size () != 2)
      throw Error ("expected IN and OUT, got " + std::to_string (positional.size ()) + " file arguments (see -h)");
    s.input = positional[0];
    s.output = positional[1];
    const std::string out_extension = lowerExtension (s.output);
    if (out_extension != ".pcd" && out_extension != ".ply")
      throw Error (s.output + ": the output must be .pcd or .ply");
    const std::string in_extension = lowerExtension (s.input);
    if (in_extension != ".psm" && !isMeshFileExtension (s.input))
      throw Error (s.input + ": unknown input extension (a mesh .obj .off .ply .stl or a model .psm)");

    int given = 0;
    if (numberOption (argc, argv, "-n", s.count))
    {
      ++given;
      s.mode = 1;
      if (!(s.count >= 1.0) || s.count != std::floor (s.count))
        throw Error ("option -n: the point count must be a positive integer");
      if (s.count > static_cast<double> (SparseSurfaceResampling::max_points))
        throw Error ("option -n: " + std::to_string (static_cast<long long> (s.count)) + " points is more than the limit " +
                     std::to_string (SparseSurfaceResampling::max_points));
    }
    if (numberOption (argc, argv, "-density", s.density))
    {
      ++given;
      s.mode = 2;
      if (!(s.density > 0.0))
        throw Error ("option -density: must be a positive number of points per unit area");
    }
    if (numberOption (argc, argv, "-spacing", s.spacing))
    {
      ++given;
      s.mode = 3;
      if (!(s.spacing > 0.0))
        throw Error ("option -spacing: must be a positive length");
    }
    if (given > 1)
      throw Error ("options -n, -density and -spacing exclude each other");
    double value = 0.0;
    if (numberOption (argc, argv, "-rho", value))
    {
      if (!(value > 0.0 && value <= 1.0))
        throw Error ("option -rho: must be in (0, 1]");
      s.encoder.patches.rho = value;
    }
    if (numberOption (argc, argv, "-f", value))
    {
      if (!(value >= 0.0 && value <= 1.0))
        throw Error ("option -f: must be in [0, 1]");
      s.encoder.coding.nyquist_factor = value;
    }
    s.encoder.coding.footprint_angles = 64;
    if (numberOption (argc, argv, "-angles", value))
    {
      if (!(value >= 3.0 && value <= 4096.0) || value != std::floor (value))
        throw Error ("option -angles: must be an integer in [3, 4096]");
      s.encoder.coding.footprint_angles = static_cast<int> (value);
    }
    if (numberOption (argc, argv, "-seed", value))
    {
      if (!(value >= 0.0) || value != std::floor (value) || value > 1.8e19)
        throw Error ("option -seed: must be a non-negative integer");
      s.resampling.seed = static_cast<std::uint64_t> (value);
    }
    if (numberOption (argc, argv, "-threads", value))
    {
      if (!(value >= 1.0 && value <= 1024.0) || value != std::floor (value))
        throw Error ("option -threads: must be an integer in [1, 1024]");
      s.threads = static_cast<int> (value);
    }
    s.binary = !pcl::console::find_switch (argc, argv, "-ascii");
    s.quiet = pcl::console::find_switch (argc, argv, "-q");
    s.json = pcl::console::find_switch (argc, argv, "--json");
    return s;
  }
} // namespace

int
main (int argc, char** argv)
{
  if (argc < 2 || pcl::console::find_switch (argc, argv, "-h") || pcl::console::find_switch (argc, argv, "--help"))
  {
    printHelp (argv[0]);
    return argc < 2 ? 1 : 0;
  }
  try
  {
    const Settings s = parseSettings (argc, argv);
    if (s.quiet || s.json)
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
    const ProgressCallback progress = makeConsoleProgress (s.quiet);
    pcl::console::TicToc total;
    total.tic ();

    // Input: a saved model, or a mesh encoded here.
    auto model = std::make_shared<SparseSurfaceModel> ();
    std::size_t input_vertices = 0;
    double load_seconds = 0.0, encode_seconds = 0.0;
    pcl::console::TicToc timer;
    timer.tic ();
    if (lowerExtension (s.input) == ".psm")
    {
      *model = loadModel (s.input);
      load_seconds = timer.toc () / 1000.0;
      input_vertices = model->num_input_vertices;
    }
    else
    {
      auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (s.input));
      load_seconds = timer.toc () / 1000.0;
      input_vertices = mesh->numVertices ();
      pcl::console::print_info ("Loaded %s: %zu vertices, %zu faces in %.3f s\n", s.input.c_str (), mesh->numVertices (),
                                mesh->numTriangles (), load_seconds);
      s.encoder.validate ();
      SparseSurfaceEncoder encoder;
      encoder.setInputMesh (mesh);
      encoder.setOptions (s.encoder);
      encoder.setNumberOfThreads (s.threads);
      encoder.setProgressCallback (progress);
      timer.tic ();
      encoder.compute (*model);
      encode_seconds = timer.toc () / 1000.0;
      pcl::console::print_info ("Encoded into %zu patches, %zu coefficients in %.3f s\n", model->numPatches (),
                                model->numNonZeros (), encode_seconds);
    }

    SparseSurfaceResampling resampling;
    resampling.setInputModel (model);
    resampling.setOptions (s.resampling);
    resampling.setNumberOfThreads (s.threads);
    resampling.setProgressCallback (progress);
    if (s.mode == 0)
    {
      if (input_vertices == 0)
        throw Error (s.input + ": the model does not record its vertex count; give -n, -density or -spacing");
      resampling.setPointCount (std::min<std::size_t> (4 * input_vertices, SparseSurfaceResampling::max_points));
    }
    else if (s.mode == 1)
      resampling.setPointCount (static_cast<std::size_t> (s.count));
    else if (s.mode == 2)
      resampling.setDensity (s.density);
    else
      resampling.setSpacing (s.spacing);
    pcl::PointCloud<pcl::PointNormal> cloud;
    timer.tic ();
    resampling.compute (cloud);
    const double resample_seconds = timer.toc () / 1000.0;
    pcl::console::print_info ("Resampled %zu points (area %.6g, density %.6g) in %.3f s\n", cloud.size (),
                              resampling.getEstimatedArea (), resampling.getDensityUsed (), resample_seconds);

    timer.tic ();
    savePointNormalCloud (s.output, cloud, s.binary);
    const double save_seconds = timer.toc () / 1000.0;
    const double seconds = total.toc () / 1000.0;
    if (!s.quiet && !s.json)
    {
      pcl::console::print_highlight ("Wrote %s: ", s.output.c_str ());
      pcl::console::print_value ("%zu", cloud.size ());
      pcl::console::print_info (" points in %.3f s (save %.3f s)\n", seconds, save_seconds);
    }
    if (s.json)
      std::printf ("{\"input\": %s, \"output\": %s, \"points\": %zu, \"patches\": %zu, \"input_vertices\": %zu, "
                   "\"area\": %.9g, \"density\": %.9g, \"load_seconds\": %.6f, \"encode_seconds\": %.6f, "
                   "\"resample_seconds\": %.6f, \"save_seconds\": %.6f, \"seconds\": %.6f}\n",
                   jsonString (s.input).c_str (), jsonString (s.output).c_str (), cloud.size (), model->numPatches (),
                   input_vertices, resampling.getEstimatedArea (), resampling.getDensityUsed (), load_seconds,
                   encode_seconds, resample_seconds, save_seconds, seconds);
  }
  catch (const Error& e)
  {
    pcl::console::print_error ("%s\n", e.what ());
    return 1;
  }
  catch (const std::exception& e)
  {
    pcl::console::print_error ("error: %s\n", e.what ());
    return 1;
  }
  return 0;
}
