/// pcl_sparse_info: what is in a mesh file and what is wrong with it (counts, defects, topology, scale).
///
///   pcl_sparse_info FILE [--json] [--allow-non-finite]

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <pcl/console/time.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>

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
    pcl::console::print_error ("Syntax is: %s FILE [options]\n", program);
    pcl::console::print_info ("  FILE                a triangle mesh: .obj .off .ply .stl, or a model file .psm; a point cloud\n");
    pcl::console::print_info ("                      (.pcd, or one of those without faces) is reported with faces: 0\n");
    pcl::console::print_info ("  --json              print one JSON object on stdout instead of 'name: value' lines\n");
    pcl::console::print_info ("  --allow-non-finite  count NaN/Inf vertices instead of refusing the file\n");
    pcl::console::print_info ("  -q                  quiet (no messages besides the report and errors)\n");
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

  /// A mesh file, or a point cloud as a mesh without faces (every point is an unreferenced vertex).
  TriangleMesh
  loadInput (const std::string& path, const MeshLoadOptions& options)
  {
    if (!hasExtension (path, ".pcd"))
      return loadTriangleMesh (path, options);
    pcl::PointCloud<pcl::PointXYZ> cloud;
    loadPointCloud (path, cloud);
    TriangleMesh mesh;
    mesh.vertices.reserve (cloud.size ());
    for (const auto& p : cloud)
    {
      if (!options.allow_non_finite && !std::isfinite (p.x + p.y + p.z))
        throw Error (path + ": point " + std::to_string (mesh.vertices.size ()) + " has a non-finite coordinate");
      mesh.vertices.emplace_back (p.x, p.y, p.z);
    }
    return mesh;
  }

  void
  printPlain (const std::string& path, const MeshReport& r, double seconds)
  {
    std::printf ("file: %s\n", path.c_str ());
    std::printf ("vertices: %zu\n", r.vertices);
    std::printf ("faces: %zu\n", r.faces);
    std::printf ("edges: %zu\n", r.edges);
    std::printf ("unreferenced_vertices: %zu\n", r.unreferenced_vertices);
    std::printf ("non_finite_vertices: %zu\n", r.non_finite_vertices);
    std::printf ("degenerate_faces: %zu\n", r.degenerate_faces);
    std::printf ("duplicate_faces: %zu\n", r.duplicate_faces);
    std::printf ("boundary_edges: %zu\n", r.boundary_edges);
    std::printf ("boundary_loops: %zu\n", r.boundary_loops);
    std::printf ("nonmanifold_edges: %zu\n", r.nonmanifold_edges);
    std::printf ("nonmanifold_vertices: %zu\n", r.nonmanifold_vertices);
    std::printf ("components: %zu\n", r.components);
    std::printf ("euler_characteristic: %ld\n", r.euler_characteristic);
    std::printf ("manifold: %s\n", r.manifold ? "yes" : "no");
    std::printf ("orientable: %s\n", r.orientable ? "yes" : "no");
    std::printf ("closed: %s\n", r.closed ? "yes" : "no");
    if (r.genus >= 0)
      std::printf ("genus: %d\n", r.genus);
    else
      std::printf ("genus: unknown (%s)\n", r.manifold ? "not orientable" : "not manifold");
    std::printf ("bbox_diagonal: %.6g\n", r.bbox_diagonal);
    std::printf ("mean_edge_length: %.6g\n", r.mean_edge_length);
    std::printf ("seconds: %.3f\n", seconds);
  }

  void
  printJson (const std::string& path, const MeshReport& r, double seconds)
  {
    std::printf ("{\"file\": %s, \"vertices\": %zu, \"faces\": %zu, \"edges\": %zu, "
                 "\"unreferenced_vertices\": %zu, \"non_finite_vertices\": %zu, \"degenerate_faces\": %zu, "
                 "\"duplicate_faces\": %zu, \"boundary_edges\": %zu, \"boundary_loops\": %zu, "
                 "\"nonmanifold_edges\": %zu, \"nonmanifold_vertices\": %zu, \"components\": %zu, "
                 "\"euler_characteristic\": %ld, \"manifold\": %s, \"orientable\": %s, \"closed\": %s, "
                 "\"genus\": %d, \"bbox_diagonal\": %.17g, \"mean_edge_length\": %.17g, \"seconds\": %.6f}\n",
                 jsonString (path).c_str (), r.vertices, r.faces, r.edges, r.unreferenced_vertices,
                 r.non_finite_vertices, r.degenerate_faces, r.duplicate_faces, r.boundary_edges, r.boundary_loops,
                 r.nonmanifold_edges, r.nonmanifold_vertices, r.components, r.euler_characteristic,
                 r.manifold ? "true" : "false", r.orientable ? "true" : "false", r.closed ? "true" : "false",
                 r.genus, r.bbox_diagonal, r.mean_edge_length, seconds);
  }
  /// Summary of a .psm model file: header, patches, atoms and the bytes of each section.
  void
  printModelInfo (const std::string& path, bool json, pcl::console::TicToc& timer)
  {
    const ModelFileInfo info = inspectModelFile (path);
    const SparseSurfaceModel model = loadModel (path);
    const double seconds = timer.toc () / 1000.0;
    const double bits = info.num_input_vertices ? 8.0 * info.file_bytes / info.num_input_vertices : 0.0;
    if (json)
    {
      std::printf ("{\"file\": %s, \"version\": %u, \"quantised\": %s, \"tolerance\": %.17g, \"basis\": %s, "
                   "\"patches\": %u, \"atoms\": %zu, \"input_vertices\": %llu, \"bbox_diagonal\": %.17g, "
                   "\"vertices_stored\": %s, \"bytes\": %llu, \"bits_per_input_vertex\": %.6g, \"sections\": {",
                   jsonString (path).c_str (), info.version, info.quantised ? "true" : "false", info.tolerance,
                   jsonString (info.basis).c_str (), info.num_patches, model.numNonZeros (),
                   static_cast<unsigned long long> (info.num_input_vertices), info.bbox_diagonal,
                   info.has_vertices ? "true" : "false", static_cast<unsigned long long> (info.file_bytes), bits);
      for (std::size_t i = 0; i < info.sections.size (); ++i)
        std::printf ("%s\"%s\": {\"bytes\": %llu, \"raw_bytes\": %llu}", i ? ", " : "", info.sections[i].tag.c_str (),
                     static_cast<unsigned long long> (info.sections[i].stored_bytes),
                     static_cast<unsigned long long> (info.sections[i].raw_bytes));
      std::printf ("}, \"seconds\": %.6f}\n", seconds);
      return;
    }
    std::printf ("file: %s\n", path.c_str ());
    std::printf ("format version: %u\n", info.version);
    if (info.quantised)
      std::printf ("mode: quantised, surface tolerance %g of the bbox diagonal\n", info.tolerance);
    else
      std::printf ("mode: lossless\n");
    std::printf ("basis: %s\n", info.basis.c_str ());
    std::printf ("patches: %u\n", info.num_patches);
    std::printf ("atoms (nnz): %zu (%.2f per patch)\n", model.numNonZeros (),
                 info.num_patches ? static_cast<double> (model.numNonZeros ()) / info.num_patches : 0.0);
    std::printf ("input vertices: %llu\n", static_cast<unsigned long long> (info.num_input_vertices));
    std::printf ("bbox diagonal: %.6g\n", info.bbox_diagonal);
    std::printf ("patch vertices stored: %s\n", info.has_vertices ? "yes" : "no");
    std::printf ("bytes: %llu (%.3f bits per input vertex)\n", static_cast<unsigned long long> (info.file_bytes), bits);
    for (const ModelFileSection& section : info.sections)
      std::printf ("section %s: %llu bytes (%llu decompressed)\n", section.tag.c_str (),
                   static_cast<unsigned long long> (section.stored_bytes),
                   static_cast<unsigned long long> (section.raw_bytes));
    std::printf ("seconds: %.3f\n", seconds);
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
  MeshLoadOptions load_options;
  load_options.allow_no_faces = true;  // a PLY/OBJ of points is a cloud: reported with faces: 0
  load_options.allow_non_finite = pcl::console::find_switch (argc, argv, "--allow-non-finite");

  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--json" || arg == "-q" || arg == "--allow-non-finite")
      continue;
    if (arg.size () > 1 && arg[0] == '-')
    {
      pcl::console::print_error ("pcl_sparse_info: unknown option '%s' (see --help)\n", arg.c_str ());
      return 1;
    }
    files.push_back (arg);
  }
  if (files.size () != 1)
  {
    pcl::console::print_error ("pcl_sparse_info: expected exactly one FILE, got %zu (see --help)\n", files.size ());
    return 1;
  }
  const std::string& path = files.front ();
  if (quiet)
    pcl::console::setVerbosityLevel (pcl::console::L_ERROR);

  try
  {
    pcl::console::TicToc timer;
    timer.tic ();
    if (hasExtension (path, ".psm"))
    {
      printModelInfo (path, json, timer);
      return 0;
    }
    const TriangleMesh mesh = loadInput (path, load_options);
    const MeshTopology topology = buildMeshTopology (mesh);
    const MeshReport report = computeMeshReport (mesh, topology);
    const double seconds = timer.toc () / 1000.0;
    if (json)
      printJson (path, report, seconds);
    else
      printPlain (path, report, seconds);
  }
  catch (const Error& e)
  {
    pcl::console::print_error ("pcl_sparse_info: %s\n", e.what ());
    return 1;
  }
  catch (const std::exception& e)
  {
    pcl::console::print_error ("pcl_sparse_info: %s: %s\n", path.c_str (), e.what ());
    return 1;
  }
  return 0;
}
