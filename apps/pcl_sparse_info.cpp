/// pcl_sparse_info: what is in a mesh file and what is wrong with it (counts, defects, topology, scale); for a
/// point cloud (.pcd, .xyz, a PLY without faces) also what cleaning would drop, by cause.
///
///   pcl_sparse_info FILE [--json] [--allow-non-finite]

#include "tool_support.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_io.h>
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
      {"", "(.pcd, .xyz, or one of those without faces) is reported with faces: 0;"},
      {"", ".pcd, .xyz and a PLY without faces also with the counts of cleaning (NaN/Inf"},
      {"", "points, points at the sensor, exact duplicates), fields and grid"},
      {"--json", "print one JSON object on stdout instead of 'name: value' lines"},
      {"--allow-non-finite", "count NaN/Inf mesh vertices instead of refusing the file (scans: always counted)"},
      {"-q", "quiet (no messages besides the report and errors)"},
    },
    1, {}, {"--json", "-q", "--allow-non-finite"}};

  /// What a scan holds and what cleaning drops (for .pcd, .xyz and PLY files without faces).
  struct CloudInfo
  {
    ScanCloud raw;              ///< every point of the file
    ScanCleaningReport report;  ///< cleanScan on a copy
    double kept_bbox_diagonal = 0.0;
  };

  /// A point cloud file as a mesh without faces (every point, NaN too, is an unreferenced vertex), with
  /// the cleaning counts in \a cloud.
  TriangleMesh
  loadCloud (const std::string& path, CloudInfo& cloud)
  {
    ScanLoadOptions raw;
    raw.clean = false;
    loadScanCloud (path, cloud.raw, raw);
    ScanCloud cleaned = cloud.raw;
    cloud.report = cleanScan (cleaned);
    if (!cleaned.positions.empty ())
    {
      Eigen::Vector3d lo = cleaned.positions.front (), hi = lo;
      for (const Eigen::Vector3d& p : cleaned.positions)
      {
        lo = lo.cwiseMin (p);
        hi = hi.cwiseMax (p);
      }
      cloud.kept_bbox_diagonal = (hi - lo).norm ();
    }
    TriangleMesh mesh;
    mesh.vertices = worldPositions (cloud.raw);
    return mesh;
  }

  /// The input as a mesh. Point clouds (.pcd, .xyz, a PLY without faces) also fill \a cloud and set
  /// \a is_cloud; NaN/Inf points are counted there whatever --allow-non-finite says (organized scans are
  /// full of them).
  TriangleMesh
  loadInput (const std::string& path, const MeshLoadOptions& options, CloudInfo& cloud, bool& is_cloud)
  {
    is_cloud = tools::hasExtension (path, ".pcd") || tools::hasExtension (path, ".xyz");
    if (is_cloud)
      return loadCloud (path, cloud);
    if (!tools::hasExtension (path, ".ply"))
      return loadTriangleMesh (path, options);
    MeshLoadOptions lenient = options;
    lenient.allow_no_faces = true;
    lenient.allow_non_finite = true;
    TriangleMesh mesh = loadTriangleMesh (path, lenient);
    if (mesh.triangles.empty ())
    {
      is_cloud = true;
      return loadCloud (path, cloud);
    }
    if (!options.allow_non_finite)
      for (const Eigen::Vector3d& v : mesh.vertices)
        if (!v.allFinite ())
          return loadTriangleMesh (path, options);  // refuses the file with the mesh reader's message
    return mesh;
  }

  std::string
  joinedFields (const std::vector<std::string>& fields)
  {
    std::string text;
    for (const std::string& field : fields)
      text += (text.empty () ? "" : " ") + field;
    return text;
  }

  void
  printPlain (const std::string& path, const MeshReport& r, const CloudInfo* cloud, double seconds)
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
    if (cloud)
    {
      const ScanCleaningReport& c = cloud->report;
      std::printf ("input_points: %zu\n", c.input_points);
      std::printf ("finite_points: %zu\n", c.finitePoints ());
      std::printf ("dropped_non_finite: %zu\n", c.non_finite);
      std::printf ("dropped_at_sensor_origin: %zu\n", c.at_sensor_origin);
      std::printf ("dropped_duplicates: %zu\n", c.duplicates_merged);
      std::printf ("kept_points: %zu\n", c.kept);
      if (cloud->raw.isOrganized ())
        std::printf ("organized: %ux%u\n", cloud->raw.width, cloud->raw.height);
      else
        std::printf ("organized: no\n");
      std::printf ("fields: %s\n", joinedFields (cloud->raw.fields).c_str ());
      std::printf ("kept_bbox_diagonal: %.6g\n", cloud->kept_bbox_diagonal);
    }
    std::printf ("seconds: %.3f\n", seconds);
  }

  void
  printJson (const std::string& path, const MeshReport& r, const CloudInfo* cloud, double seconds)
  {
    tools::JsonObject json;
    json.add ("file", path)
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
      .add ("mean_edge_length", r.mean_edge_length);
    if (cloud)
    {
      const ScanCleaningReport& c = cloud->report;
      json.add ("input_points", c.input_points)
        .add ("finite_points", c.finitePoints ())
        .add ("dropped_non_finite", c.non_finite)
        .add ("dropped_at_sensor_origin", c.at_sensor_origin)
        .add ("dropped_duplicates", c.duplicates_merged)
        .add ("kept_points", c.kept)
        .add ("organized", cloud->raw.isOrganized ())
        .add ("width", cloud->raw.width)
        .add ("height", cloud->raw.height)
        .add ("fields", joinedFields (cloud->raw.fields))
        .add ("kept_bbox_diagonal", cloud->kept_bbox_diagonal);
    }
    json.addSeconds ("seconds", seconds).print ();
  }

  /// Summary of a .psm model file: header, patches, atoms and the bytes of each section.
  void
  printModelInfo (const std::string& path, bool json, pcl::console::TicToc& timer)
  {
    const ModelFileInfo info = inspectModelFile (path);
    const SparseSurfaceModel model = loadModel (path);
    // A tiled file's grid, so that users can place regions (pcl_sparse_decode -box) on its tiles.
    const bool tiled = isTiledModelFile (path);
    const TileGrid grid = tiled ? readTiledModelIndex (path).grid : TileGrid ();
    const double seconds = timer.toc () / 1000.0;
    const double bits = info.num_input_vertices ? 8.0 * info.file_bytes / info.num_input_vertices : 0.0;
    // The channels with their ranges: what pcl_sparse_decode writes (rgb or intensity) and where it clamps.
    tools::JsonObject attributes;
    std::string attribute_text;
    for (const AttributeChannelInfo& channel : model.attribute_channels)
    {
      attributes.add (attributeChannelName (channel.channel), std::vector<double> {channel.lower, channel.upper});
      attribute_text += tools::format ("%s%s (%.9g .. %.9g)", attribute_text.empty () ? "" : ", ",
                                       attributeChannelName (channel.channel), channel.lower, channel.upper);
    }
    if (json)
    {
      tools::JsonObject sections;
      for (const ModelFileSection& section : info.sections)
        sections.add (section.tag, tools::JsonObject ()
                                     .add ("bytes", static_cast<unsigned long long> (section.stored_bytes))
                                     .add ("raw_bytes", static_cast<unsigned long long> (section.raw_bytes)));
      tools::JsonObject out;
      out.add ("file", path)
        .add ("version", info.version)
        .add ("quantised", info.quantised)
        .add ("range_coded", info.range_coded)
        .add ("tolerance", info.tolerance)
        .add ("basis", info.basis)
        .add ("patches", info.num_patches)
        .add ("atoms", model.numNonZeros ())
        .add ("input_vertices", static_cast<unsigned long long> (info.num_input_vertices))
        .add ("bbox_diagonal", info.bbox_diagonal)
        .add ("vertices_stored", info.has_vertices)
        .add ("attributes", attributes)
        .add ("bytes", static_cast<unsigned long long> (info.file_bytes))
        .add ("bits_per_input_vertex", bits)
        .add ("sections", sections);
      if (tiled)
        out.add ("grid", tools::JsonObject ()
                           .add ("origin", std::vector<double> {grid.origin.x (), grid.origin.y (), grid.origin.z ()})
                           .add ("edge", grid.edge)
                           .add ("counts", std::vector<double> {double (grid.counts.x ()), double (grid.counts.y ()),
                                                                double (grid.counts.z ())})
                           .add ("tiles_with_patches", info.num_tiles));
      out.addSeconds ("seconds", seconds).print ();
      return;
    }
    std::printf ("file: %s\n", path.c_str ());
    std::printf ("format version: %u\n", info.version);
    if (info.quantised)
      std::printf ("mode: quantised%s, surface tolerance %g of the bbox diagonal\n",
                   info.range_coded ? " (range-coded fields)" : "", info.tolerance);
    else
      std::printf ("mode: lossless\n");
    std::printf ("basis: %s\n", info.basis.c_str ());
    std::printf ("patches: %u\n", info.num_patches);
    std::printf ("atoms (nnz): %zu (%.2f per patch)\n", model.numNonZeros (),
                 info.num_patches ? static_cast<double> (model.numNonZeros ()) / info.num_patches : 0.0);
    std::printf ("input vertices: %llu\n", static_cast<unsigned long long> (info.num_input_vertices));
    std::printf ("bbox diagonal: %.6g\n", info.bbox_diagonal);
    std::printf ("patch vertices stored: %s\n", info.has_vertices ? "yes" : "no");
    std::printf ("attributes: %s\n", attribute_text.empty () ? "none" : attribute_text.c_str ());
    std::printf ("bytes: %llu (%.3f bits per input vertex)\n", static_cast<unsigned long long> (info.file_bytes), bits);
    if (tiled)
      std::printf ("tile grid: %d x %d x %d tiles of edge %.9g from (%.9g, %.9g, %.9g), %zu with patches\n", grid.counts.x (),
                   grid.counts.y (), grid.counts.z (), grid.edge, grid.origin.x (), grid.origin.y (), grid.origin.z (),
                   info.num_tiles);
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
      if (!isScanFileExtension (path))  // the meshes' loader would list its own four only
        throw Error (path + ": unknown file extension (expected a mesh .obj .off .ply .stl, a model .psm, or a "
                            "point cloud .pcd .xyz)");
      CloudInfo cloud;
      bool is_cloud = false;
      const TriangleMesh mesh = loadInput (path, load_options, cloud, is_cloud);
      const MeshTopology topology = buildMeshTopology (mesh);
      const MeshReport report = computeMeshReport (mesh, topology);
      const double seconds = timer.toc () / 1000.0;
      if (json)
        printJson (path, report, is_cloud ? &cloud : nullptr, seconds);
      else
        printPlain (path, report, is_cloud ? &cloud : nullptr, seconds);
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
