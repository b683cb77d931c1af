/// pcl_sparse_info: what is in a mesh file and what is wrong with it (counts, defects, topology, scale).
///
///   pcl_sparse_info FILE [--json] [--allow-non-finite]

#include "tool_support.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <pcl/console/time.h>
#include <pcl/console/print.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  const tools::ToolDescription kTool = {
    "pcl_sparse_info", "FILE [options]",
    {
      {"FILE", "a triangle mesh: .obj .off .ply .stl, or a model file .psm; a point cloud"},
      {"", "(.pcd, or one of those without faces) is reported with faces: 0"},
      {"--json", "print one JSON object on stdout instead of 'name: value' lines"},
      {"--allow-non-finite", "count NaN/Inf vertices instead of refusing the file"},
      {"-q", "quiet (no messages besides the report and errors)"},
    },
    1, {}, {"--json", "-q", "--allow-non-finite"}};

  /// A mesh file, or a point cloud as a mesh without faces (every point is an unreferenced vertex).
  TriangleMesh
  loadInput (const std::string& path, const MeshLoadOptions& options)
  {
    if (!tools::hasExtension (path, ".pcd"))
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
    tools::JsonObject ()
      .add ("file", path)
      .add ("vertices", r.vertices)
      .add ("faces", r.faces)
      .add ("edges", r.edges)
      .add ("unreferenced_vertices", r.unreferenced_vertices)
      .add ("non_finite_vertices", r.non_finite_vertices)
      .add ("degenerate_faces", r.degenerate_faces)
      .add ("duplicate_faces", r.duplicate_faces)
      .add ("boundary_edges", r.boundary_edges)
      .add ("boundary_loops", r.boundary_loops)
      .add ("nonmanifold_edges", r.nonmanifold_edges)
      .add ("nonmanifold_vertices", r.nonmanifold_vertices)
      .add ("components", r.components)
      .add ("euler_characteristic", r.euler_characteristic)
      .add ("manifold", r.manifold)
      .add ("orientable", r.orientable)
      .add ("closed", r.closed)
      .add ("genus", r.genus)
      .add ("bbox_diagonal", r.bbox_diagonal)
      .add ("mean_edge_length", r.mean_edge_length)
      .addSeconds ("seconds", seconds)
      .print ();
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
      tools::JsonObject sections;
      for (const ModelFileSection& section : info.sections)
        sections.add (section.tag, tools::JsonObject ()
                                     .add ("bytes", static_cast<unsigned long long> (section.stored_bytes))
                                     .add ("raw_bytes", static_cast<unsigned long long> (section.raw_bytes)));
      tools::JsonObject ()
        .add ("file", path)
        .add ("version", info.version)
        .add ("quantised", info.quantised)
        .add ("tolerance", info.tolerance)
        .add ("basis", info.basis)
        .add ("patches", info.num_patches)
        .add ("atoms", model.numNonZeros ())
        .add ("input_vertices", static_cast<unsigned long long> (info.num_input_vertices))
        .add ("bbox_diagonal", info.bbox_diagonal)
        .add ("vertices_stored", info.has_vertices)
        .add ("bytes", static_cast<unsigned long long> (info.file_bytes))
        .add ("bits_per_input_vertex", bits)
        .add ("sections", sections)
        .addSeconds ("seconds", seconds)
        .print ();
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
  return tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    const bool json = args.has ("--json");
    MeshLoadOptions load_options;
    load_options.allow_no_faces = true;  // a PLY/OBJ of points is a cloud: reported with faces: 0
    load_options.allow_non_finite = args.has ("--allow-non-finite");
    args.expectPositional (1, "exactly one FILE");
    const std::string& path = args.positional ().front ();
    if (args.has ("-q"))
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);

    pcl::console::TicToc timer;
    timer.tic ();
    try
    {
      if (tools::hasExtension (path, ".psm"))
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
    catch (const Error&)
    {
      throw;
    }
    catch (const std::exception& e)
    {
      throw Error (path + ": " + e.what ());  // name the file whatever failed
    }
    return 0;
  });
}
