/// pcl_sparse_patches: partitions a mesh into the paper's overlapping height-field patches (METHOD.md
/// steps 3-6) and writes the mesh coloured by patch, seeds marked, so the partition can be inspected.
///
///   pcl_sparse_patches MESH OUT.ply [-rho R] [-delta D] [-cone C] [-eta E] [-sigma S] [-min-size N]
///                      [--authors] [--json] [-q]

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/patches/patch_checks.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const char* const kProgram = "pcl_sparse_patches";

  void
  printHelp (const char* program)
  {
    const PatchOptions d;
    pcl::console::print_error ("Syntax is: %s MESH OUT.ply [options]\n", program);
    pcl::console::print_info ("  MESH            a triangle mesh: .obj .off .ply .stl\n");
    pcl::console::print_info ("  OUT.ply         the mesh, each vertex coloured by one of its patches, seeds black\n");
    pcl::console::print_info ("  -rho R          size bound A_p / A (default %g)\n", d.rho);
    pcl::console::print_info ("  -delta D        smooth variation angle in degrees (default %g)\n", d.delta * 180.0 / M_PI);
    pcl::console::print_info ("  -cone C         normal cone angle in degrees (default %g; authors' code 72)\n", d.cone_angle * 180.0 / M_PI);
    pcl::console::print_info ("  -eta E          flatness bound A_p / A_p^proj (default %g)\n", d.eta);
    pcl::console::print_info ("  -sigma S        seed overlap control (default %g)\n", d.sigma);
    pcl::console::print_info ("  -min-size N     smallest patch the sampling keeps (default %d)\n", d.min_patch_size);
    pcl::console::print_info ("  --authors       the authors' code: cone 72 degrees, no pairwise cone, no coverage pass\n");
    pcl::console::print_info ("  --json          print one JSON object on stdout\n");
    pcl::console::print_info ("  -q              quiet (no progress, no messages besides the report and errors)\n");
  }

  /// Reads the number after \a name if present; throws Error for a missing or malformed value.
  template <typename T>
  void
  parseNumber (int argc, char** argv, const char* name, T& value)
  {
    const int i = pcl::console::find_argument (argc, argv, name);
    if (i < 0)
      return;
    if (i + 1 >= argc)
      throw Error (std::string ("option ") + name + " needs a value");
    char* end = nullptr;
    const double x = std::strtod (argv[i + 1], &end);
    if (end == argv[i + 1] || *end != '\0' || !std::isfinite (x))
      throw Error (std::string ("option ") + name + ": '" + argv[i + 1] + "' is not a number");
    if (std::is_integral<T>::value && (x != std::floor (x) || std::abs (x) > std::numeric_limits<int>::max ()))
      throw Error (std::string ("option ") + name + ": '" + argv[i + 1] + "' is not an integer");
    value = static_cast<T> (x);
  }

  bool
  endsWithPly (const std::string& path)
  {
    if (path.size () < 4)
      return false;
    std::string tail = path.substr (path.size () - 4);
    std::transform (tail.begin (), tail.end (), tail.begin (), [] (unsigned char c) { return std::tolower (c); });
    return tail == ".ply";
  }

  /// A well spread colour for patch \a i (golden-ratio hue steps), never black.
  std::array<std::uint8_t, 3>
  patchColor (std::size_t i)
  {
    const double h = std::fmod (0.61803398875 * static_cast<double> (i), 1.0) * 6.0;
    const double s = 0.55 + 0.35 * static_cast<double> ((i * 7) % 5) / 4.0, v = 0.95;
    const int k = static_cast<int> (h);
    const double f = h - k, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (k % 6)
    {
      case 1: r = q; g = v; b = p; break;
      case 2: r = p; g = v; b = t; break;
      case 3: r = p; g = q; b = v; break;
      case 4: r = t; g = p; b = v; break;
      case 5: r = v; g = p; b = q; break;
      default: break;
    }
    return {static_cast<std::uint8_t> (255 * r), static_cast<std::uint8_t> (255 * g), static_cast<std::uint8_t> (255 * b)};
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
  if (quiet)
    pcl::console::setVerbosityLevel (pcl::console::L_ERROR);

  try
  {
    // Positional arguments and unknown options.
    const std::vector<std::string> valued = {"-rho", "-delta", "-cone", "-eta", "-sigma", "-min-size"};
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
      if (std::find (valued.begin (), valued.end (), arg) != valued.end ())
      {
        ++i;
        continue;
      }
      if (arg == "--json" || arg == "-q" || arg == "--authors")
        continue;
      if (arg.size () > 1 && arg[0] == '-')
        throw Error ("unknown option '" + arg + "' (see --help)");
      files.push_back (arg);
    }
    if (files.size () != 2)
      throw Error ("expected MESH and OUT.ply, got " + std::to_string (files.size ()) + " file arguments (see --help)");
    const std::string& input = files[0];
    const std::string& output = files[1];
    if (!endsWithPly (output))
      throw Error (output + ": the output must be a .ply file");

    PatchOptions options;
    if (pcl::console::find_switch (argc, argv, "--authors"))
    {
      options.cone_angle = M_PI / 2.5;
      options.pairwise_cone = false;
      options.cover_all_vertices = false;
      options.cover_unreferenced_vertices = false;
    }
    double delta_degrees = options.delta * 180.0 / M_PI, cone_degrees = options.cone_angle * 180.0 / M_PI;
    parseNumber (argc, argv, "-rho", options.rho);
    parseNumber (argc, argv, "-delta", delta_degrees);
    parseNumber (argc, argv, "-cone", cone_degrees);
    parseNumber (argc, argv, "-eta", options.eta);
    parseNumber (argc, argv, "-sigma", options.sigma);
    parseNumber (argc, argv, "-min-size", options.min_patch_size);
    options.delta = delta_degrees * M_PI / 180.0;
    options.cone_angle = cone_degrees * M_PI / 180.0;
    try
    {
      options.validate ();
    }
    catch (const Error& e)
    {
      throw Error (std::string (e.what ()) + " (angles are given in degrees)");
    }

    auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (input));
    pcl::console::TicToc timer;
    timer.tic ();
    FeatureAwarePatchSampling sampling;
    sampling.setInputMesh (mesh);
    sampling.setOptions (options);
    sampling.setProgressCallback (makeConsoleProgress (quiet || json));
    std::vector<Patch> patches;
    sampling.compute (patches);
    const double seconds = timer.toc () / 1000.0;

    // Statistics.
    std::vector<std::size_t> sizes;
    std::vector<int> count (mesh->vertices.size (), 0);
    for (const Patch& p : patches)
    {
      sizes.push_back (p.size ());
      for (int v : p.vertices)
        ++count[v];
    }
    std::sort (sizes.begin (), sizes.end ());
    std::size_t covered = 0, memberships = 0;
    for (int c : count)
      if (c > 0)
      {
        ++covered;
        memberships += static_cast<std::size_t> (c);
      }
    std::size_t kinds[3] = {0, 0, 0};
    for (PatchFrameKind k : sampling.getFrameKinds ())
      ++kinds[static_cast<int> (k)];
    const double per_vertex = covered > 0 ? static_cast<double> (memberships) / covered : 0.0;
    const std::size_t smin = sizes.empty () ? 0 : sizes.front (), smax = sizes.empty () ? 0 : sizes.back ();
    const std::size_t smed = sizes.empty () ? 0 : sizes[sizes.size () / 2];
    PatchInvariantChecker checker (*mesh, options);
    std::size_t invalid = 0;
    for (const Patch& p : patches)
      if (!checker.check (p).empty ())
        ++invalid;
    const std::size_t uncovered = mesh->vertices.size () - covered;

    // Colour: for each vertex the patch where it is most central (smallest local |(x', y')|).
    std::vector<std::array<std::uint8_t, 3>> colors (mesh->vertices.size (), {128, 128, 128});
    std::vector<double> best (mesh->vertices.size (), std::numeric_limits<double>::infinity ());
    for (std::size_t i = 0; i < patches.size (); ++i)
      for (std::size_t k = 0; k < patches[i].size (); ++k)
      {
        const int v = patches[i].vertices[k];
        const double r = patches[i].local[k].head<2> ().norm ();
        if (r < best[v])
        {
          best[v] = r;
          colors[v] = patchColor (i);
        }
      }
    for (const Patch& p : patches)
      colors[p.seed] = {0, 0, 0};
    saveColoredMesh (output, *mesh, colors);

    if (json)
      std::printf ("{\"file\": %s, \"vertices\": %zu, \"patches\": %zu, \"uncovered\": %zu, \"unreferenced\": %zu, "
                   "\"coverage_patches\": %zu, \"keypoints\": %zu, \"size_min\": %zu, \"size_median\": %zu, "
                   "\"size_max\": %zu, \"patches_per_vertex\": %.6f, \"invalid_patches\": %zu, \"frames_jet\": %zu, "
                   "\"frames_seed_normal\": %zu, \"frames_normal_only\": %zu, \"seconds\": %.6f}\n",
                   jsonString (input).c_str (), mesh->vertices.size (), patches.size (), uncovered,
                   sampling.getUnreferencedVertices ().size (), sampling.getNumCoveragePatches (),
                   sampling.getKeypoints ().size (), smin, smed, smax, per_vertex, invalid, kinds[0], kinds[1], kinds[2],
                   seconds);
    else
    {
      std::printf ("file: %s\n", input.c_str ());
      std::printf ("vertices: %zu\n", mesh->vertices.size ());
      std::printf ("patches (M): %zu\n", patches.size ());
      std::printf ("uncovered vertices: %zu\n", uncovered);
      std::printf ("unreferenced vertices: %zu\n", sampling.getUnreferencedVertices ().size ());
      std::printf ("coverage-pass patches: %zu\n", sampling.getNumCoveragePatches ());
      std::printf ("patch size min/median/max: %zu / %zu / %zu\n", smin, smed, smax);
      std::printf ("mean patches per vertex: %.3f\n", per_vertex);
      std::printf ("patches violating an invariant: %zu\n", invalid);
      std::printf ("frames jet / seed normal / normal only: %zu / %zu / %zu\n", kinds[0], kinds[1], kinds[2]);
      std::printf ("seconds: %.3f\n", seconds);
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
