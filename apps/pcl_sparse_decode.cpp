/// pcl_sparse_decode: reads a .psm model file and resamples it into a point cloud with normals and
/// curvature (METHOD.md step 12); optionally reconstructs the input vertices of a mesh.
///
///   pcl_sparse_decode MODEL.psm OUT.{pcd,ply} [-n N | -density D] [-seed S] [-threads T]
///                     [-recon MESH RECON.{ply,obj,off,stl}] [--json] [-q]

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  void
  printHelp (const char* program)
  {
    pcl::console::print_error ("Syntax is: %s MODEL.psm OUT.{pcd,ply} [options]\n", program);
    pcl::console::print_info ("  MODEL.psm          a model file written by pcl_sparse_encode -o\n");
    pcl::console::print_info ("  OUT               the resampled cloud: x y z, normal, curvature (.pcd or .ply)\n");
    pcl::console::print_info ("  -n N              exactly N points (default: the model's number of input vertices)\n");
    pcl::console::print_info ("  -density D        D points per unit area instead of -n\n");
    pcl::console::print_info ("  -seed S           seed of the sampling (default 42)\n");
    pcl::console::print_info ("  -threads T        OpenMP threads (default: all; the output does not depend on it)\n");
    pcl::console::print_info ("  -recon MESH RECON reconstruct MESH's vertices from the model (needs a model written with\n");
    pcl::console::print_info ("                    --store-vertices) and write MESH with them to RECON\n");
    pcl::console::print_info ("  --json            print one JSON object on stdout\n");
    pcl::console::print_info ("  -q                quiet\n");
  }

  const std::vector<std::string> value_options = {"-n", "-density", "-seed", "-threads"};
  const std::vector<std::string> switches = {"--json", "-q", "-h", "--help"};

  double
  numberOption (int argc, char** argv, const std::string& name, double fallback, bool* found = nullptr)
  {
    for (int i = 1; i < argc; ++i)
      if (name == argv[i])
      {
        if (i + 1 >= argc)
          throw Error ("option " + name + " needs a value");
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod (argv[i + 1], &end);
        if (end == argv[i + 1] || *end != '\0' || errno != 0 || !std::isfinite (value))
          throw Error ("option " + name + ": '" + argv[i + 1] + "' is not a number");
        if (found)
          *found = true;
        return value;
      }
    return fallback;
  }

  bool
  hasExtension (const std::string& path, const std::string& extension)
  {
    if (path.size () < extension.size ())
      return false;
    std::string tail = path.substr (path.size () - extension.size ());
    std::transform (tail.begin (), tail.end (), tail.begin (), [] (unsigned char c) { return std::tolower (c); });
    return tail == extension;
  }
} // namespace

int
main (int argc, char** argv)
{
  if (argc < 3 || pcl::console::find_switch (argc, argv, "-h") || pcl::console::find_switch (argc, argv, "--help"))
  {
    printHelp (argv[0]);
    return argc < 3 ? 1 : 0;
  }
  const bool json = pcl::console::find_switch (argc, argv, "--json");
  const bool quiet = pcl::console::find_switch (argc, argv, "-q");
  try
  {
    std::vector<std::string> files;
    std::string recon_mesh, recon_out;
    for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
      if (arg == "-recon")
      {
        if (i + 2 >= argc)
          throw Error ("option -recon needs MESH and RECON");
        recon_mesh = argv[i + 1];
        recon_out = argv[i + 2];
        i += 2;
        continue;
      }
      if (std::find (value_options.begin (), value_options.end (), arg) != value_options.end ())
      {
        ++i;
        continue;
      }
      if (std::find (switches.begin (), switches.end (), arg) != switches.end ())
        continue;
      if (arg.size () > 1 && arg[0] == '-')
        throw Error ("unknown option '" + arg + "' (see --help)");
      files.push_back (arg);
    }
    if (files.size () != 2)
      throw Error ("expected MODEL.psm and OUT.{pcd,ply}, got " + std::to_string (files.size ()) + " file names");
    const std::string& model_path = files[0];
    const std::string& out_path = files[1];
    if (!hasExtension (out_path, ".pcd") && !hasExtension (out_path, ".ply"))
      throw Error ("output '" + out_path + "' must end in .pcd or .ply");
    if (!recon_out.empty () && !isMeshFileExtension (recon_out))
      throw Error ("option -recon: '" + recon_out + "' has no mesh extension (.obj .off .ply .stl)");
    bool has_n = false, has_density = false;
    const double n = numberOption (argc, argv, "-n", 0.0, &has_n);
    const double density = numberOption (argc, argv, "-density", 0.0, &has_density);
    if (has_n && has_density)
      throw Error ("options -n and -density exclude each other");
    if (has_n && (n < 1 || n != std::floor (n) || n > SparseSurfaceResampling::max_points))
      throw Error ("option -n: expected an integer in [1, 1e9]");
    if (has_density && !(density > 0.0))
      throw Error ("option -density: expected a positive number");
    const double seed = numberOption (argc, argv, "-seed", 42.0);
    if (seed < 0 || seed != std::floor (seed))
      throw Error ("option -seed: expected a non-negative integer");
    const double threads = numberOption (argc, argv, "-threads", 0.0);
    if (threads < 0 || threads != std::floor (threads))
      throw Error ("option -threads: expected a non-negative integer");

    pcl::console::TicToc timer;
    timer.tic ();
    const auto model = std::make_shared<const SparseSurfaceModel> (loadModel (model_path));
    const double load_seconds = timer.toc () / 1000.0;

    // Check -recon before writing anything, so that a bad request leaves no output behind.
    TriangleMesh recon;
    if (!recon_mesh.empty ())
    {
      recon = loadTriangleMesh (recon_mesh);
      if (recon.vertices.size () != model->num_input_vertices)
        throw Error ("option -recon: '" + recon_mesh + "' has " + std::to_string (recon.vertices.size ()) +
                     " vertices, the model was encoded from " + std::to_string (model->num_input_vertices));
      bool any = false;
      for (const PatchCode& patch : model->patches)
        any = any || !patch.vertices.empty ();
      if (!any && !model->patches.empty ())
        throw Error ("option -recon: '" + model_path + "' stores no patch vertices (encode with --store-vertices)");
    }

    timer.tic ();
    SparseSurfaceResampling resampling;
    resampling.setInputModel (model);
    SparseSurfaceResamplingOptions options;
    options.seed = static_cast<std::uint64_t> (seed);
    resampling.setOptions (options);
    if (has_density)
      resampling.setDensity (density);
    else
      resampling.setPointCount (has_n ? static_cast<std::size_t> (n)
                                      : std::max<std::size_t> (model->num_input_vertices, 1));
    resampling.setNumberOfThreads (static_cast<int> (threads));
    resampling.setProgressCallback (makeConsoleProgress (quiet || json));
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    const double resample_seconds = timer.toc () / 1000.0;

    timer.tic ();
    savePointNormalCloud (out_path, cloud);
    if (!recon_mesh.empty ())
    {
      const std::vector<Eigen::Vector3d> vertices = model->reconstructVertices (recon.vertices.size ());
      for (std::size_t v = 0; v < vertices.size (); ++v)
        if (vertices[v].allFinite ())
          recon.vertices[v] = vertices[v];
      saveTriangleMesh (recon_out, recon);
    }
    const double write_seconds = timer.toc () / 1000.0;

    if (json)
      std::printf ("{\"model\": \"%s\", \"patches\": %zu, \"nnz\": %zu, \"points\": %zu, \"area\": %.17g, "
                   "\"seconds\": {\"load\": %.6f, \"resample\": %.6f, \"write\": %.6f}}\n",
                   model_path.c_str (), model->numPatches (), model->numNonZeros (), cloud.size (),
                   resampling.getEstimatedArea (), load_seconds, resample_seconds, write_seconds);
    else if (!quiet)
      std::printf ("%zu patches, %zu atoms -> %zu points; seconds: load %.3f, resample %.3f, write %.3f\n",
                   model->numPatches (), model->numNonZeros (), cloud.size (), load_seconds, resample_seconds,
                   write_seconds);
  }
  catch (const Error& e)
  {
    pcl::console::print_error ("pcl_sparse_decode: %s\n", e.what ());
    return 1;
  }
  catch (const std::exception& e)
  {
    pcl::console::print_error ("pcl_sparse_decode: unexpected failure: %s\n", e.what ());
    return 1;
  }
  return 0;
}
