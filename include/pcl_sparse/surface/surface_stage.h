#pragma once
/// \file surface_stage.h
/// \brief The base of the stages that read a surface: a PCL cloud (a mesh's vertices with their polygons,
/// or a sensor scan alone), or the library's own double-precision mesh or scan.
///
/// Input, one of (the last set wins):
///   - a mesh, PCL's way: setInputCloud (the vertices, any point type with x y z) and setInputPolygons (the
///     faces, as in pcl::PolygonMesh::polygons; polygons with more than three corners are fanned into
///     triangles). A pcl::PolygonMesh converts with pcl::fromPCLPointCloud2 (mesh.cloud, cloud).
///   - a scan, PCL's way: setInputCloud alone (organized or not). It is cleaned (non-finite points,
///     exact duplicates and points at the sensor origin dropped, io/scan_cleaning.h), moved to a local frame,
///     and its neighbourhood surface is built (cloud/cloud_surface.h: image grid, lidar rings or k nearest
///     neighbours; normals oriented toward setViewPoint, the cloud's sensor_origin_, or consistently).
///   - the library's: setInputMesh (TriangleMesh::ConstPtr, what the strict loaders of io/mesh_io.h return)
///     or setInputScan (ScanCloud::ConstPtr, from loadScanCloud), both in double precision.
/// For a scan, the surface's vertices are the kept points (getSurfaceInputIndices maps them to the
/// input's points) and outputs in space (seeds, keypoints) are in the input's frame.
/// setIndices (PCL's) means one of two things, as each stage documents:
///   - IndexUse::CropSurface (patch sampling, encoding): the part of the surface to work on, the indexed
///     points and the faces whose corners are all indexed. Vertex numbers in the output are then positions
///     in the indices (output i belongs to point indices[i], as in PCL's features).
///   - IndexUse::SelectPoints (normals, keypoints): the points to compute an output for, while
///     neighbourhoods use the whole surface (PCL's search surface).
/// With setInputScan, indices select the scan's points (its surface's vertices) for SelectPoints; a crop
/// (CropSurface) is refused: crop the scan itself.

#include <pcl_sparse/cloud/cloud_surface.h>
#include <pcl_sparse/common/point_types.h>
#include <pcl_sparse/common/stage_base.h>
#include <pcl_sparse/io/scan_cleaning.h>
#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/PolygonMesh.h>
#include <pcl/Vertices.h>
#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>

#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief What setIndices means to a stage (see the file's comment).
  enum class IndexUse
  {
    CropSurface,  ///< the stage works on the indexed part of the surface
    SelectPoints  ///< the stage computes outputs for the indexed points, over the whole surface
  };

  /// \brief Base of every stage whose input is a surface (PCL's pcl::PCLBase plus polygons or a mesh).
  /// \tparam PointInT point type of the input cloud (needs x, y, z)
  template <typename PointInT>
  class SurfaceStage : public pcl::PCLBase<PointInT>, public StageBase
  {
  public:
    using PointCloudIn = pcl::PointCloud<PointInT>;
    using PointCloudInConstPtr = typename PointCloudIn::ConstPtr;
    using Polygons = std::vector<pcl::Vertices>;
    using PolygonsConstPtr = std::shared_ptr<const Polygons>;

    /// \brief The input cloud: the surface's vertices (with setInputPolygons). Replaces a mesh or scan set
    /// before. Polygons set before stay, as indices do in PCL: to encode a new cloud as a scan after a
    /// mesh, call setInputPolygons (nullptr) (else the old faces are laid over the new points).
    /// \param[in] cloud the points; non-finite points may not be used by a polygon
    void
    setInputCloud (const PointCloudInConstPtr& cloud) override
    {
      pcl::PCLBase<PointInT>::setInputCloud (cloud);
      mesh_.reset ();
      scan_.reset ();
      topology_.reset ();
    }

    /// \brief The faces over the input cloud's points, as pcl::PolygonMesh holds them.
    /// \param[in] polygons each polygon's point indices, at least 3, counter-clockwise seen from outside
    void setInputPolygons (const PolygonsConstPtr& polygons) { polygons_ = polygons; }
    /// \brief The polygons set by setInputPolygons (empty pointer: none).
    const PolygonsConstPtr& getInputPolygons () const { return polygons_; }

    /// \brief The input as the library's own mesh (double precision); replaces a cloud or scan set before.
    /// \param[in] mesh the mesh, e.g. from loadTriangleMesh (io/mesh_io.h)
    void
    setInputMesh (const TriangleMesh::ConstPtr& mesh)
    {
      mesh_ = mesh;
      scan_.reset ();
      this->input_.reset ();
      topology_.reset ();
    }

    /// \brief The input as a scan already loaded and cleaned (double precision, local frame; e.g. from
    /// loadScanCloud); replaces a cloud or mesh set before. Its neighbourhood surface is built at compute.
    /// \param[in] scan the scan
    void
    setInputScan (const ScanCloud::ConstPtr& scan)
    {
      scan_ = scan;
      mesh_.reset ();
      this->input_.reset ();
      topology_.reset ();
    }
    /// \brief The scan set by setInputScan (empty pointer otherwise).
    const ScanCloud::ConstPtr& getInputScan () const { return scan_; }

    /// \brief How a scan's neighbourhood surface is built (neighbours, gap rule, normal orientation,
    /// outliers; cloud/cloud_surface_options.h). Used for a cloud without polygons and for setInputScan.
    void setCloudSurfaceOptions (const CloudSurfaceOptions& options) { cloud_options_ = options; }
    const CloudSurfaceOptions& getCloudSurfaceOptions () const { return cloud_options_; }

    /// \brief The viewpoint a scan's normals face (as pcl::Feature's setViewPoint), in the input's frame;
    /// without it, the cloud's sensor_origin_ (a PCD's VIEWPOINT) when plausible, else a consistent
    /// orientation (cloud/cloud_surface_options.h, NormalOrientation::Auto).
    void
    setViewPoint (float vpx, float vpy, float vpz)
    {
      cloud_options_.has_viewpoint = true;
      cloud_options_.viewpoint = Eigen::Vector3d (vpx, vpy, vpz);
    }

    /// \brief What cleaning drops from a cloud without polygons (default: non-finite points, exact
    /// duplicates, points at the sensor origin).
    void setCleaningOptions (const ScanCleaningOptions& options) { cleaning_options_ = options; }

    /// \brief The surface the last compute worked on: the input mesh or its indexed part (without the extra
    /// copies of repeated faces and the faces repeating a corner, see getDuplicateFaces and
    /// getFacesWithRepeatedCorners), or a scan's neighbourhood surface (in the scan's local frame: world
    /// position = getSurfaceOrigin () + vertex).
    const TriangleMesh::ConstPtr& getSurface () const { return surface_; }
    /// \brief After a compute on a mesh: how many faces it left out as extra copies of an earlier face (the
    /// same three vertices, in any order). A copy adds no surface, but every stage would count it again: area
    /// weights, Harris neighbourhoods, one more patch per copy.
    std::size_t getDuplicateFaces () const { return duplicate_faces_; }
    /// \brief After a compute on a mesh: how many faces it left out for repeating a corner (a, a, b). Such a
    /// face has no area and no normal, but its side a-b would join a and b in the topology, a shortcut for
    /// growth, geodesics and Harris rings where b is not a's neighbour.
    std::size_t getFacesWithRepeatedCorners () const { return repeated_corner_faces_; }
    /// \brief The offset of getSurface ()'s frame in the input's frame (0 but for scans far from the origin).
    const Eigen::Vector3d& getSurfaceOrigin () const { return surface_origin_; }

    /// \brief After a compute on a scan: its neighbourhood surface's figures (normals, noise, spacing,
    /// counts; the mesh itself is the surface the stage worked on). Empty pointer after a mesh input.
    const std::shared_ptr<const CloudSurface>& getCloudSurface () const { return cloud_surface_; }
    /// \brief After a compute on a scan: what cleaning dropped, one count per cause.
    const ScanCleaningReport& getCleaningReport () const { return cleaning_report_; }
    /// \brief After a compute on a scan: for each surface vertex, the index of its point in the input
    /// cloud (empty after a mesh input, where vertex i is point i or indices[i]).
    const std::vector<std::size_t>& getSurfaceInputIndices () const { return surface_input_indices_; }
    /// \brief The mesh set by setInputMesh (empty pointer when the input is a cloud).
    const TriangleMesh::ConstPtr& getInputMesh () const { return mesh_; }

    /// \brief The topology of the mesh given to setInputMesh, if the caller has built it already (saves
    /// rebuilding it). Ignored with indices, where the stage works on a part of the mesh.
    /// \param[in] topology buildMeshTopology (*mesh), set after setInputMesh
    void setTopology (const std::shared_ptr<const MeshTopology>& topology) { topology_ = topology; }

  protected:
    /// \param[in] name the class name, without namespace
    /// \param[in] index_use what setIndices means to the stage
    SurfaceStage (const std::string& name, IndexUse index_use) : StageBase (name), index_use_ (index_use) {}

    /// \brief Sets surface_ and surface_topology_ to the surface compute works on (the input mesh, or
    /// the cloud and its polygons; with CropSurface restricted to the indices), and selected_ to the
    /// indices (SelectPoints; empty pointer when none are set). Throws pcl_sparse::Error, naming the
    /// class, for a missing input, a cloud without polygons, a polygon with fewer than 3 corners, an
    /// index out of range, a polygon using a non-finite point, or a surface without triangles.
    void initCompute ();

    /// \brief Releases what compute needed only while it ran (the surface stays for getSurface).
    void
    deinitCompute ()
    {
      surface_topology_.reset ();
      selected_.reset ();
    }

    /// \brief SelectPoints: the surface vertices of the selected input points, in the order of the indices
    /// (for a scan, points cleaning dropped are left out).
    std::vector<int> selectedSurfaceVertices () const;

    /// \brief SelectPoints stages: the surface vertex behind each output point (-1: a point cleaning
    /// dropped; a duplicate it merged has the vertex of the point it kept). One output per index, or per
    /// input point (for a scan: every point of the input cloud, so outputs line up with the input as in
    /// PCL), or per surface vertex.
    std::vector<int> outputVertices () const;

    /// \brief Gives the input points cleaning merged as duplicates (no vertex in \a vertex_of_point) the
    /// vertex of the point kept at their position.
    void mapDuplicatesToTheirKeptPoint (std::vector<int>& vertex_of_point) const;

    /// \brief Position of output point \a row (vertex \a vertex of outputVertices) in the input's frame:
    /// the input cloud's point for a cloud without polygons, else the surface vertex.
    Eigen::Vector3d outputPosition (std::size_t row, int vertex) const;

    /// \brief Whether the current compute works on a scan (setInputScan, or a cloud without polygons).
    bool surfaceIsScan () const { return static_cast<bool> (cloud_surface_); }

    /// \brief Whether that scan is a spinning lidar frame arranged on its rings (PatchOptions::lidar_delta).
    bool surfaceIsLidarRings () const
    {
      return cloud_surface_ && cloud_surface_->neighborhood == CloudNeighborhood::LidarRings;
    }

    /// \brief Per-vertex normals the stages should grow and frame patches with: a scan's oriented PCA
    /// normals (smooth where the triangulation of noisy points is not), empty for a mesh (its own normals).
    const std::vector<Eigen::Vector3d>& surfaceNormals () const
    {
      static const std::vector<Eigen::Vector3d> none;
      return cloud_surface_ ? cloud_surface_->normals : none;
    }

    IndexUse index_use_;
    TriangleMesh::ConstPtr mesh_;
    ScanCloud::ConstPtr scan_;
    PolygonsConstPtr polygons_;
    CloudSurfaceOptions cloud_options_;
    ScanCleaningOptions cleaning_options_;
    std::shared_ptr<const MeshTopology> topology_;

    /// The surface of the current compute and its topology (set by initCompute).
    TriangleMesh::ConstPtr surface_;
    std::shared_ptr<const MeshTopology> surface_topology_;
    /// SelectPoints: the indices of the current compute, checked to be in range (empty: all points).
    pcl::IndicesConstPtr selected_;
    /// The input's frame: world position = surface_origin_ + surface vertex (non-zero only for a scan far
    /// from the origin, e.g. map coordinates).
    Eigen::Vector3d surface_origin_ = Eigen::Vector3d::Zero ();
    /// A scan's surface figures, cleaning counts and vertex-to-input map (see the getters).
    std::shared_ptr<const CloudSurface> cloud_surface_;
    ScanCleaningReport cleaning_report_;
    std::vector<std::size_t> surface_input_indices_;
    std::size_t duplicate_faces_ = 0;
    std::size_t repeated_corner_faces_ = 0;

  private:
    /// initCompute's part for a scan (setInputScan, or a cloud without polygons).
    void initScanSurface ();
    /// initCompute's part for a mesh: replaces surface_ by a copy without repeated faces and faces repeating
    /// a corner, if it has any; fails when no face is left.
    void dropFacesWithoutSurface ();
  };

  /// \brief The positions of a cloud's points in double precision, in storage order.
  /// \param[in] cloud any point type with x, y, z
  /// \return #points positions
  template <typename PointT>
  std::vector<Eigen::Vector3d>
  cloudPositions (const pcl::PointCloud<PointT>& cloud)
  {
    std::vector<Eigen::Vector3d> positions (cloud.size ());
    for (std::size_t i = 0; i < cloud.size (); ++i)
      positions[i] = Eigen::Vector3d (cloud[i].x, cloud[i].y, cloud[i].z);
    return positions;
  }
} // namespace pcl_sparse

#ifdef PCL_NO_PRECOMPILE
#include <pcl_sparse/surface/impl/surface_stage.hpp>
#else
#define PCL_SPARSE_EXTERN_SURFACE_STAGE(T) extern template class pcl_sparse::SurfaceStage<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_EXTERN_SURFACE_STAGE)
#undef PCL_SPARSE_EXTERN_SURFACE_STAGE
#endif
