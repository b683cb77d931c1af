#include "tool_input.h"

#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/mesh/mesh_cleaning.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/vertex_welding.h>
#include <pcl_sparse/tiles/spilled_tile_source.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  namespace tools
  {
    std::size_t
    SurfaceInput::points () const
    {
      return mesh ? mesh->vertices.size () : scan->size ();
    }

    std::vector<Eigen::Vector3d>
    SurfaceInput::worldPositions () const
    {
      return mesh ? mesh->vertices : pcl_sparse::worldPositions (*scan);
    }

    bool
    isSurfaceInputExtension (const std::string& path)
    {
      return isMeshFileExtension (path) || isScanFileExtension (path);
    }

    namespace
    {
      /// A file whose faces share no vertex (each repeats its corners, as some writers do) has no topology
      /// to grow patches on: its corners at equal positions are welded, with a note. Separate triangles
      /// (no two corners at one position) stay as they are, for each stage to take or refuse.
      TriangleMesh::ConstPtr
      weldTriangleSoup (const std::string& path, const TriangleMesh::ConstPtr& soup)
      {
        CleaningOptions weld_only{false, false, false, false};
        weld_only.weld_coincident_vertices = true;
        auto welded = std::make_shared<TriangleMesh> (cleanMesh (*soup, weld_only).mesh);
        if (isTriangleSoup (*welded))
        {
          printNote (path + ": its faces share no vertex, not even at equal positions (separate triangles): nothing "
                            "to weld");
          return soup;
        }
        printNote (format ("%s: its faces shared no vertex (a triangle soup): welded its %zu corners into %zu vertices "
                           "at equal positions",
                           path.c_str (), soup->vertices.size (), welded->vertices.size ()));
        return welded;
      }

      /// What the stages leave out of a mesh or cut it at without a word, said once: vertices in no face (no
      /// patch codes them), faces without area (no normal, never a patch triangle) and edges of more than two
      /// faces (no patch crosses one).
      void
      noteMeshDefects (const std::string& path, const TriangleMesh& mesh)
      {
        std::vector<std::uint8_t> in_a_face (mesh.vertices.size (), 0);
        std::size_t without_area = 0;
        for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
        {
          for (int k = 0; k < 3; ++k)
            in_a_face[mesh.triangles[f][k]] = 1;
          without_area += isDegenerateFace (mesh, static_cast<int> (f));
        }
        const auto in_no_face = static_cast<std::size_t> (std::count (in_a_face.begin (), in_a_face.end (), 0));
        if (in_no_face > 0)
          printNote (format ("%s: %zu of its %zu vertices are in no face: no surface there, left out", path.c_str (),
                             in_no_face, mesh.vertices.size ()));
        if (without_area > 0)
          printNote (format ("%s: %zu of its %zu faces have no area (a repeated or collinear corner): no surface there, "
                             "left out",
                             path.c_str (), without_area, mesh.triangles.size ()));
        // Counted as the stages see the mesh, without the extra copies of a face they leave out (a face
        // given twice made its three edges "non-manifold" and the note said the surface was cut there).
        if (const std::size_t nonmanifold = countNonManifoldEdges (mesh, findDuplicateFaces (mesh)); nonmanifold > 0)
          printNote (format ("%s: %zu of its edges are shared by more than two faces (non-manifold): the surface is cut "
                             "along them, no patch crosses one",
                             path.c_str (), nonmanifold));
      }
    } // namespace

    void
    refuseViewpointOnMesh (bool has_viewpoint, bool is_mesh, const std::string& path)
    {
      if (has_viewpoint && is_mesh)
        throw Error ("option -viewpoint orients a scan's normals; " + path + " is a mesh");
    }

    SurfaceInput
    loadSurfaceInput (const std::string& path, const Eigen::Vector3d* sensor)
    {
      SurfaceInput input;
      if (isMeshFileExtension (path) && !hasExtension (path, ".pcd") && !hasExtension (path, ".xyz"))
      {
        // A file of points only (a .ply scan) is a scan, NaN points and all; a mesh is read strictly.
        MeshLoadOptions lenient;
        lenient.allow_no_faces = true;
        lenient.allow_non_finite = true;
        auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path, lenient));
        if (!mesh->triangles.empty ())
        {
          for (const Eigen::Vector3d& v : mesh->vertices)
            if (!v.allFinite ())
              return SurfaceInput{std::make_shared<TriangleMesh> (loadTriangleMesh (path)), nullptr};  // its error
          input.mesh = isTriangleSoup (*mesh) ? weldTriangleSoup (path, mesh) : mesh;
          noteMeshDefects (path, *input.mesh);
          return input;
        }
      }
      if (hasExtension (path, ".psm"))
        throw Error (path + ": a model file, not a mesh or a cloud (pcl_sparse_decode and pcl_sparse_resample read it)");
      if (!isScanFileExtension (path))
        throw Error (path + ": unknown input extension (a mesh .obj .off .ply .stl, or a cloud .pcd .ply .xyz)");
      auto scan = std::make_shared<ScanCloud> ();
      ScanLoadOptions load;
      if (sensor)
        load.cleaning.sensor_position = *sensor;
      loadScanCloud (path, *scan, load);
      // As the spilled path says it (spillIntoTiles): naming the file and the causes, not "the scan has no
      // points" from whichever stage met the empty scan first (a frame of no-returns, all NaN or all 0,0,0).
      if (scan->size () == 0)
        throw Error (path + ": " + scan->report.whyNoPointIsLeft ());
      input.scan = scan;
      return input;
    }

    bool
    parseViewpoint (const CommandLine& args, Eigen::Vector3d& viewpoint)
    {
      std::vector<double> v;
      if (!args.numbers ("-viewpoint", 3, "X,Y,Z (three numbers)", v))
        return false;
      // The stages take it as floats (as pcl::Feature::setViewPoint): 1e300 became infinite there, refused
      // by a tile's encoder after the spill, and taken without a word untiled.
      for (double x : v)
        if (!(std::abs (x) <= static_cast<double> (std::numeric_limits<float>::max ())))
          throw Error ("option -viewpoint: " + args.value ("-viewpoint") + " is beyond what a float holds (3.4e38)");
      viewpoint = Eigen::Vector3d (v[0], v[1], v[2]);
      return true;
    }

    const ScanCleaningReport*
    cleaningReportOf (const SurfaceInput& input, const TileSource* spilled)
    {
      if (input.scan)
        return &input.scan->report;
      const auto* spilled_scan = dynamic_cast<const SpilledTileSource*> (spilled);
      return spilled_scan ? &spilled_scan->cleaningReport () : nullptr;
    }

    void
    addInputJson (JsonObject& json, const ScanCleaningReport* cleaning, const CloudSurface* surface)
    {
      json.add ("input_kind", cleaning ? "scan" : "mesh");
      if (!cleaning)
        return;
      const ScanCleaningReport& report = *cleaning;
      json.add ("input_points", report.input_points)
        .add ("finite_points", report.finitePoints ())
        .add ("dropped_non_finite", report.non_finite)
        .add ("dropped_at_sensor_origin", report.at_sensor_origin)
        .add ("dropped_duplicates", report.duplicates_merged)
        .add ("kept_points", report.kept)
        .add ("non_finite_intensities", report.non_finite_intensities);
      if (surface)
        json.add ("outliers", surface->outliers)
          .add ("isolated_points", surface->isolated)
          .add ("unreferenced_points", surface->unreferenced)
          .add ("noise", surface->noise)
          .add ("spacing", surface->spacing)
          .add ("default_pose_ignored", surface->default_pose_ignored);
    }

    void
    printAttributeGaps (const std::string& path, const AttributeGaps& gaps)
    {
      if (gaps.filled > 0)
        printNote (format (gaps.filled == 1 ? "%s: %zu colour or intensity value is NaN or infinite: it takes the nearest point's"
                                            : "%s: %zu colour or intensity values are NaN or infinite: each takes the nearest point's",
                           path.c_str (), gaps.filled));
      for (AttributeChannel channel : gaps.dropped)
        printNote (format ("%s: no point has a finite value in its '%s' field: the channel is left out", path.c_str (),
                           attributeChannelName (channel)));
    }

    void
    printIntensityGaps (const std::string& path, const ScanCleaningReport& report)
    {
      if (report.non_finite_intensities == 0)
        return;
      AttributeGaps gaps;
      if (report.non_finite_intensities >= report.kept)
        gaps.dropped.push_back (AttributeChannel::Intensity);
      else
        gaps.filled = report.non_finite_intensities;
      printAttributeGaps (path, gaps);
    }

    void
    printScanSummary (const ScanCleaningReport* cleaning, const CloudSurface* surface)
    {
      if (!cleaning)
        return;
      const ScanCleaningReport& report = *cleaning;
      pcl::console::print_info ("Scan: %zu points, %zu kept (dropped: %zu non-finite, %zu at the sensor origin, %zu duplicates)",
                                report.input_points, report.kept, report.non_finite, report.at_sensor_origin,
                                report.duplicates_merged);
      if (surface)
        pcl::console::print_info ("; surface: spacing %.4g, noise %.3g, %zu outliers, %zu isolated", surface->spacing,
                                  surface->noise, surface->outliers, surface->isolated);
      pcl::console::print_info ("\n");
      if (surface && surface->default_pose_ignored)
        printNote ("the scan's sensor pose is PCL's default (0, 0, 0), but its points do not thin out away from there: "
                   "no sensor stood there, so the normals are oriented consistently instead (-viewpoint X,Y,Z if one did)");
    }
  } // namespace tools
} // namespace pcl_sparse
