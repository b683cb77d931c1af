#pragma once
/// \file tool_input.h
/// The surface a tool reads: a triangle mesh (.obj .off .ply with faces .stl) or a scan (.pcd .xyz, a .ply
/// without faces), loaded strictly, and handed to any SurfaceStage; the scan figures for --json.

#include "tool_support.h"

#include <pcl_sparse/cloud/cloud_surface.h>
#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/attribute_gaps.h>
#include <pcl_sparse/tiles/tile_source.h>

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pcl_sparse
{
  namespace tools
  {
    /// A loaded input: exactly one of mesh and scan is set.
    struct SurfaceInput
    {
      TriangleMesh::ConstPtr mesh;
      ScanCloud::ConstPtr scan;

      /// Vertices of the mesh, or kept points of the scan.
      std::size_t points () const;
      /// Their positions in the file's frame.
      std::vector<Eigen::Vector3d> worldPositions () const;
      /// "mesh" or "scan".
      const char* kind () const { return mesh ? "mesh" : "scan"; }
    };

    /// True if \a path has an extension loadSurfaceInput reads.
    bool
    isSurfaceInputExtension (const std::string& path);

    /// Loads \a path: .pcd and .xyz as scans (loadScanCloud: cleaned, local frame), the mesh formats as
    /// meshes (loadTriangleMesh), a mesh file without faces (a .ply of points) as a scan. A scan's points at
    /// \a sensor (the -viewpoint given, if not null) are dropped as no-returns, not those at the file's sensor
    /// origin.
    SurfaceInput
    loadSurfaceInput (const std::string& path, const Eigen::Vector3d* sensor = nullptr);

    /// Throws when -viewpoint is given (\a has_viewpoint) for a mesh (\a is_mesh): a mesh's normals come from its
    /// faces, so the option would do nothing without a word.
    void
    refuseViewpointOnMesh (bool has_viewpoint, bool is_mesh, const std::string& path);

    /// Gives \a input to \a stage (setInputMesh or setInputScan).
    template <typename Stage>
    void
    setSurfaceInput (Stage& stage, const SurfaceInput& input)
    {
      if (input.mesh)
        stage.setInputMesh (input.mesh);
      else
        stage.setInputScan (input.scan);
    }

    /// The surface \a stage's last compute worked on, in the input file's frame: the mesh itself, or a
    /// scan's neighbourhood surface moved back from its local frame (a copy only then).
    template <typename Stage>
    TriangleMesh::ConstPtr
    surfaceInInputFrame (const Stage& stage)
    {
      if (stage.getSurfaceOrigin ().isZero (0.0))
        return stage.getSurface ();
      auto moved = std::make_shared<TriangleMesh> (*stage.getSurface ());
      for (Eigen::Vector3d& v : moved->vertices)
        v += stage.getSurfaceOrigin ();
      return moved;
    }

    /// Option -viewpoint X,Y,Z of the scan tools: true and \a viewpoint set when given. Throws Error
    /// naming the option for anything but three finite numbers.
    bool
    parseViewpoint (const CommandLine& args, Eigen::Vector3d& viewpoint);

    /// What cleaning did to the input's scan: the loaded scan's report, or \a spilled's when the scan was
    /// spilled into tiles instead of loaded (its JSON and summary lacked the counts); null for a mesh.
    const ScanCleaningReport*
    cleaningReportOf (const SurfaceInput& input, const TileSource* spilled);

    /// Adds the input's figures to \a json (input kind; for a scan, \a report non-null: input_points,
    /// finite_points, the dropped counts by cause, kept points, and from \a surface the outliers, isolated
    /// points and noise).
    void
    addInputJson (JsonObject& json, const ScanCleaningReport* report, const CloudSurface* surface);

    /// A note for the attribute values the encoder filled or left out (SparseSurfaceEncoder::getAttributeGaps);
    /// nothing when there were none.
    void
    printAttributeGaps (const std::string& path, const AttributeGaps& gaps);

    /// The same for a tiled encoding, from what reading the scan counted (ScanCleaningReport::
    /// non_finite_intensities): each tile's encoder fills its part.
    void
    printIntensityGaps (const std::string& path, const ScanCleaningReport& report);

    /// One line on the console describing a scan (\a report non-null) and its surface (nothing for a mesh).
    void
    printScanSummary (const ScanCleaningReport* report, const CloudSurface* surface);
  } // namespace tools
} // namespace pcl_sparse
