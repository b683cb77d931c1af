#pragma once
/// \file surface_stage.h
/// \brief The base of the stages that read a surface: a PCL input cloud with its polygons, or the library's
/// own double-precision TriangleMesh.
///
/// Input, two ways (pick one per compute):
///   - PCL's: setInputCloud (the vertices, any point type with x y z) and setInputPolygons (the faces,
///     as in pcl::PolygonMesh::polygons; polygons with more than three corners are fanned into triangles).
///     A pcl::PolygonMesh converts with pcl::fromPCLPointCloud2 (mesh.cloud, cloud).
///   - the library's: setInputMesh (TriangleMesh::ConstPtr), what the strict file loaders (io/mesh_io.h)
///     return, kept in double precision.
/// setIndices (PCL's) means one of two things, as each stage documents:
///   - IndexUse::CropSurface (patch sampling, encoding): the part of the surface to work on, the indexed
///     points and the faces whose corners are all indexed. Vertex numbers in the output are then positions
///     in the indices (output i belongs to point indices[i], as in PCL's features).
///   - IndexUse::SelectPoints (normals, keypoints): the points to compute an output for, while
///     neighbourhoods use the whole surface (PCL's search surface).

#include <pcl_sparse/common/point_types.h>
#include <pcl_sparse/common/stage_base.h>
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

    /// \brief The input cloud: the surface's vertices (with setInputPolygons). Replaces a mesh set before.
    /// \param[in] cloud the points; non-finite points may not be used by a polygon
    void
    setInputCloud (const PointCloudInConstPtr& cloud) override
    {
      pcl::PCLBase<PointInT>::setInputCloud (cloud);
      mesh_.reset ();
    }

    /// \brief The faces over the input cloud's points, as pcl::PolygonMesh holds them.
    /// \param[in] polygons each polygon's point indices, at least 3, counter-clockwise seen from outside
    void setInputPolygons (const PolygonsConstPtr& polygons) { polygons_ = polygons; }
    /// \brief The polygons set by setInputPolygons (empty pointer: none).
    const PolygonsConstPtr& getInputPolygons () const { return polygons_; }

    /// \brief The input as the library's own mesh (double precision); replaces a cloud set before.
    /// \param[in] mesh the mesh, e.g. from loadTriangleMesh (io/mesh_io.h)
    void
    setInputMesh (const TriangleMesh::ConstPtr& mesh)
    {
      mesh_ = mesh;
      this->input_.reset ();
      topology_.reset ();
    }
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

    /// \brief Releases the working surface after compute.
    void
    deinitCompute ()
    {
      surface_.reset ();
      surface_topology_.reset ();
      selected_.reset ();
    }

    IndexUse index_use_;
    TriangleMesh::ConstPtr mesh_;
    PolygonsConstPtr polygons_;
    std::shared_ptr<const MeshTopology> topology_;

    /// The surface of the current compute and its topology (set by initCompute).
    TriangleMesh::ConstPtr surface_;
    std::shared_ptr<const MeshTopology> surface_topology_;
    /// SelectPoints: the indices of the current compute, checked to be in range (empty: all points).
    pcl::IndicesConstPtr selected_;
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
#include <pcl_sparse/mesh/impl/surface_stage.hpp>
#else
#define PCL_SPARSE_EXTERN_SURFACE_STAGE(T) extern template class pcl_sparse::SurfaceStage<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_EXTERN_SURFACE_STAGE)
#undef PCL_SPARSE_EXTERN_SURFACE_STAGE
#endif
