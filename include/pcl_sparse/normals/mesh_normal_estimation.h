#pragma once
/// \file mesh_normal_estimation.h
/// Vertex normals of a triangle mesh as a PCL-style stage (docs/METHOD.md step 2): the mesh's own normals,
/// oriented by its faces, where pcl::NormalEstimation would fit planes to neighbours and guess the sign.
///
///   pcl_sparse::MeshNormalEstimation<pcl::PointXYZ> ne;
///   ne.setInputCloud (cloud);              // the vertices, and
///   ne.setInputPolygons (polygons);        // the faces (or setInputMesh (TriangleMesh::ConstPtr))
///   pcl::PointCloud<pcl::Normal> normals;   // or pcl::PointCloud<pcl::PointNormal> (xyz filled too)
///   ne.compute (normals);

#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/surface/surface_stage.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <memory>
#include <string>

namespace pcl_sparse
{
  /// \brief Per-vertex unit normals (area- or angle-weighted face normals) and the surface variation
  /// lambda0 / (lambda0 + lambda1 + lambda2) of each vertex's 1-ring (the "curvature" pcl::NormalEstimation
  /// reports). Vertices without a non-degenerate face get NaN normals and curvature and make the output
  /// not dense, as in PCL. With setIndices, one output per index (IndexUse::SelectPoints), computed over the
  /// whole surface, as pcl::NormalEstimation does with its search surface.
  /// \tparam PointInT point type of the input cloud
  template <typename PointInT>
  class MeshNormalEstimation : public SurfaceStage<PointInT>
  {
  public:
    using Ptr = std::shared_ptr<MeshNormalEstimation<PointInT>>;
    using ConstPtr = std::shared_ptr<const MeshNormalEstimation<PointInT>>;

    MeshNormalEstimation () : SurfaceStage<PointInT> ("MeshNormalEstimation", IndexUse::SelectPoints) {}

    /// \brief Face weighting of the vertex normals (default: area, as docs/METHOD.md step 2 lists first).
    void setWeighting (NormalWeighting weighting) { weighting_ = weighting; }
    NormalWeighting getWeighting () const { return weighting_; }

    /// \brief One normal per vertex (or per index), in order. Throws pcl_sparse::Error for a missing or
    /// empty surface or an index out of range.
    /// \param[out] output the normals (replaced)
    void compute (pcl::PointCloud<pcl::Normal>& output);
    /// \brief Same, with the vertex positions in x, y, z.
    /// \param[out] output the points with normals (replaced)
    void compute (pcl::PointCloud<pcl::PointNormal>& output);

  protected:
    /// \brief Fills the output (normal_x.. and curvature, and x, y, z where PointT has them).
    template <typename PointT>
    void computeNormals (pcl::PointCloud<PointT>& output);

    NormalWeighting weighting_ = NormalWeighting::Area;
  };

  /// \brief Surface variation of vertex \a v and its 1-ring: smallest covariance eigenvalue over their sum.
  /// \param[in] mesh the mesh
  /// \param[in] topology its topology
  /// \param[in] v the vertex
  float
  ringSurfaceVariation (const TriangleMesh& mesh, const MeshTopology& topology, int v);
} // namespace pcl_sparse

#ifdef PCL_NO_PRECOMPILE
#include <pcl_sparse/normals/impl/mesh_normal_estimation.hpp>
#else
#define PCL_SPARSE_EXTERN_NORMALS(T) extern template class pcl_sparse::MeshNormalEstimation<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_EXTERN_NORMALS)
#undef PCL_SPARSE_EXTERN_NORMALS
#endif
