/// pcl_sparse_encode: encodes a triangle mesh as a sparse surface model and reports the paper's figures
/// (N_V, M, rho, nnz, RMSE, RMSE / diag, CR) and the seconds per stage.
///
///   pcl_sparse_encode MESH [-rho R] [-f F] [-L N] [-eps E] [-min-samples N] [-recon RECON.ply]
///                     [-error ERR.ply] [-o MODEL.psm [-tolerance T] [--store-vertices]] [--json] [-q]

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  void
  printHelp (const char* program)
  {
    pcl::console::print_error ("Syntax is: %s MESH [options]\n", program);
    pcl::console::print_info ("  MESH              a triangle mesh: .obj .off .ply .stl\n");
    pcl::console::print_info ("  -rho R            patch size bound A_p / A (default 0.001; paper: 0.005, 0.001, 0.0002)\n");
    pcl::console::print_info ("  -f F              Nyquist factor in [0, 1] (default 0.5; 0 = plain OMP)\n");
    pcl::console::print_info ("  --authors-nyquist the authors' cap lambda >= f mu instead of the paper's lambda / 2 > f mu\n");
    pcl::console::print_info ("  -L N              atoms per patch at most (default 12)\n");
    pcl::console::print_info ("  -eps E            relative residual to stop at, in (0, 1) (default 0.01)\n");
    pcl::console::print_info ("  -min-samples N    patches with fewer points get extra samples (default 64; authors 128)\n");
    pcl::console::print_info ("  -basis paper|dct  cosine atoms: paper cos(i pi x) cos(j pi y) (default);\n"
                              "                    dct cos(i pi (x+1)/2) cos(j pi (y+1)/2), odd parts too (ours)\n");
    pcl::console::print_info ("  -seed S           seed of the extra samples (default 42)\n");
    pcl::console::print_info ("  -threads N        OpenMP threads (default: all; the model does not depend on it)\n");
    pcl::console::print_info ("  -recon RECON      write the reconstructed mesh (input vertex order and faces)\n");
    pcl::console::print_info ("  -error ERR.ply    write the reconstruction coloured by vertex error, blue (0) to red (max)\n");
    pcl::console::print_info ("  -o MODEL.psm      write the model file (docs/FORMAT.md)\n");
    pcl::console::print_info ("  -tolerance T      model file: largest surface displacement / bbox diagonal (default 0 = lossless)\n");
    pcl::console::print_info ("  --store-vertices  model file: also store the patch vertices (for -recon from the file)\n");
    pcl::console::print_info ("  --json            print one JSON object on stdout instead of the table row\n");
    pcl::console::print_info ("  -q                quiet (no progress, only the result and errors)\n");
  }

  /// Options taking a value, and switches; anything else starting with '-' is refused.
  const std::vector<std::string> value_options = {"-rho", "-f", "-L", "-eps", "-min-samples", "-seed", "-threads",
                                                  "-basis", "-recon", "-error", "-o", "-tolerance"};
  const std::vector<std::string> switches = {"--json", "-q", "--authors-nyquist", "-h", "--help", "--store-vertices"};

  /// The value of option \a name as a double, \a fallback when absent; throws Error when it does not parse.
  double
  numberOption (int argc, char** argv, const std::string& name, double fallback)
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
        return value;
      }
    return fallback;
  }

  int
  integerOption (int argc, char** argv, const std::string& name, int fallback)
  {
    const double value = numberOption (argc, argv, name, fallback);
    if (value != std::floor (value) || std::abs (value) > 1e9)
      throw Error ("option " + name + ": expected an integer, got " + std::to_string (value));
    return static_cast<int> (value);
  }

  std::string
  stringOption (int argc, char** argv, const std::string& name)
  {
    for (int i = 1; i < argc; ++i)
      if (name == argv[i])
      {
        if (i + 1 >= argc)
          throw Error ("option " + name + " needs a value");
        return argv[i + 1];
      }
    return std::string ();
  }

  /// Blue (0) -> cyan -> green -> yellow -> red (1).
  std::array<std::uint8_t, 3>
  errorColor (double t)
  {
    t = std::min (1.0, std::max (0.0, t));
    const double r = std::min (1.0, std::max (0.0, 2.0 * t - 1.0) * 2.0);
    const double g = t < 0.25 ? 4.0 * t : (t > 0.75 ? 4.0 * (1.0 - t) : 1.0);
    const double b = std::min (1.0, std::max (0.0, 1.0 - 2.0 * t) * 2.0);
    return {static_cast<std::uint8_t> (std::lround (255 * r)), static_cast<std::uint8_t> (std::lround (255 * g)),
            static_cast<std::uint8_t> (std::lround (255 * b))};
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
} // namespace

int
main (int argc, char** argv)
{
  if (argc < 2 || pcl::console::find_switch (argc, argv, "-h") || pcl::console::find_switch (argc, argv, "--help"))
  {
    printHelp (argv[0]);
    return argc < 2 ? 1 : 0;
  }
  const bool json = pcl::console::find_switch (argc, argv, "--json");
  const bool quiet = pcl::console::find_switch (argc, argv, "-q");

  try
  {
    // Exactly one positional argument; refuse unknown options.
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
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
    if (files.size () != 1)
      throw Error ("expected exactly one MESH, got " + std::to_string (files.size ()) + " (see --help)");
    const std::string& path = files.front ();

    SparseSurfaceEncoderOptions options;
    options.patches.rho = numberOption (argc, argv, "-rho", options.patches.rho);
    options.coding.nyquist_factor = numberOption (argc, argv, "-f", options.coding.nyquist_factor);
    options.coding.max_atoms = integerOption (argc, argv, "-L", options.coding.max_atoms);
    options.coding.tolerance = numberOption (argc, argv, "-eps", options.coding.tolerance);
    options.coding.min_samples = integerOption (argc, argv, "-min-samples", options.coding.min_samples);
    options.coding.seed = static_cast<std::uint64_t> (integerOption (argc, argv, "-seed", 42));
    if (pcl::console::find_switch (argc, argv, "--authors-nyquist"))
      options.coding.nyquist_rule = NyquistRule::AuthorsCode;
    const std::string basis_name = stringOption (argc, argv, "-basis");
    if (basis_name == "dct")
      options.basis = CosineBasisKind::Dct;
    else if (!basis_name.empty () && basis_name != "paper")
      throw Error ("option -basis: expected paper or dct, got '" + basis_name + "'");
    const int threads = integerOption (argc, argv, "-threads", 0);
    if (threads < 0)
      throw Error ("option -threads: expected >= 0, got " + std::to_string (threads));
    const std::string recon_path = stringOption (argc, argv, "-recon");
    const std::string error_path = stringOption (argc, argv, "-error");
    const std::string model_path = stringOption (argc, argv, "-o");
    ModelWriteOptions write_options;
    write_options.tolerance = numberOption (argc, argv, "-tolerance", 0.0);
    write_options.include_vertices = pcl::console::find_switch (argc, argv, "--store-vertices");
    if (write_options.tolerance < 0.0 || write_options.tolerance > 0.1)
      throw Error ("option -tolerance: expected a fraction of the bbox diagonal in [0, 0.1]");
    if (model_path.empty () && (write_options.tolerance > 0.0 || write_options.include_vertices))
      throw Error ("options -tolerance and --store-vertices need -o MODEL.psm");
    options.validate ();
    if (!recon_path.empty () && !isMeshFileExtension (recon_path))
      throw Error ("option -recon: '" + recon_path + "' has no mesh extension (.obj .off .ply .stl)");
    if (!error_path.empty () && (error_path.size () < 4 || error_path.substr (error_path.size () - 4) != ".ply"))
      throw Error ("option -error: '" + error_path + "' must end in .ply");

    pcl::console::TicToc timer;
    timer.tic ();
    const TriangleMesh::ConstPtr mesh = std::make_shared<const TriangleMesh> (loadTriangleMesh (path));
    const double load_seconds = timer.toc () / 1000.0;

    SparseSurfaceEncoder encoder;
    encoder.setInputMesh (mesh);
    encoder.setOptions (options);
    encoder.setNumberOfThreads (threads);
    encoder.setProgressCallback (makeConsoleProgress (quiet || json));
    SparseSurfaceModel model;
    encoder.compute (model);

    timer.tic ();
    std::vector<double> errors;
    const ModelStatistics stats = model.statistics (mesh->vertices, &errors);
    const double statistics_seconds = timer.toc () / 1000.0;

    timer.tic ();
    if (!model_path.empty ())
      saveModel (model_path, model, write_options);
    if (!recon_path.empty () || !error_path.empty ())
    {
      TriangleMesh reconstructed = *mesh;
      const std::vector<Eigen::Vector3d> vertices = model.reconstructVertices (mesh->vertices.size ());
      for (std::size_t v = 0; v < vertices.size (); ++v)
        if (vertices[v].allFinite ())  // vertices in no patch keep their input position
          reconstructed.vertices[v] = vertices[v];
      if (!recon_path.empty ())
        saveTriangleMesh (recon_path, reconstructed);
      if (!error_path.empty ())
      {
        std::vector<std::array<std::uint8_t, 3>> colors (errors.size ());
        for (std::size_t v = 0; v < errors.size (); ++v)
          colors[v] = errorColor (stats.max_error > 0.0 ? errors[v] / stats.max_error : 0.0);
        saveColoredMesh (error_path, reconstructed, colors);
      }
    }
    const double write_seconds = timer.toc () / 1000.0;
    const EncoderTimings& t = encoder.getTimings ();

    if (json)
      std::printf ("{\"file\": %s, \"vertices\": %zu, \"faces\": %zu, \"patches\": %zu, \"rho\": %.17g, "
                   "\"nyquist_factor\": %.17g, \"basis\": \"%s\", \"max_atoms\": %d, \"tolerance\": %.17g, \"min_samples\": %d, "
                   "\"nnz\": %zu, \"cr\": %.17g, \"rmse\": %.17g, \"rmse_over_diag\": %.17g, \"max_error\": %.17g, "
                   "\"bbox_diagonal\": %.17g, \"uncovered\": %zu, \"seconds\": {\"load\": %.6f, \"patches\": %.6f, "
                   "\"coding\": %.6f, \"encode\": %.6f, \"statistics\": %.6f, \"write\": %.6f}}\n",
                   jsonString (path).c_str (), mesh->vertices.size (), mesh->triangles.size (), stats.num_patches,
                   options.patches.rho, options.coding.nyquist_factor, cosineBasisKindName (options.basis),
                   options.coding.max_atoms,
                   options.coding.tolerance, options.coding.min_samples, stats.num_nonzeros,
                   stats.compression_ratio, stats.rmse, stats.rmse_over_diagonal, stats.max_error, model.bbox_diagonal,
                   stats.uncovered, load_seconds, t.patches, t.coding, t.total, statistics_seconds, write_seconds);
    else
    {
      std::printf ("%10s %7s %8s %8s %11s %10s %6s\n", "N_V", "M", "rho", "nnz", "RMSE", "RMSE/diag", "CR");
      std::printf ("%10zu %7zu %8g %8zu %11.4e %10.3e %6.3f\n", stats.num_vertices, stats.num_patches,
                   options.patches.rho, stats.num_nonzeros, stats.rmse, stats.rmse_over_diagonal,
                   stats.compression_ratio);
      if (stats.uncovered > 0)
        std::printf ("uncovered vertices (not in the RMSE): %zu\n", stats.uncovered);
      std::printf ("seconds: load %.3f, patches %.3f, coding %.3f, statistics %.3f, write %.3f (encode %.3f)\n",
                   load_seconds, t.patches, t.coding, statistics_seconds, write_seconds, t.total);
    }
  }
  catch (const Error& e)
  {
    pcl::console::print_error ("pcl_sparse_encode: %s\n", e.what ());
    return 1;
  }
  catch (const std::exception& e)
  {
    pcl::console::print_error ("pcl_sparse_encode: unexpected failure: %s\n", e.what ());
    return 1;
  }
  return 0;
}
