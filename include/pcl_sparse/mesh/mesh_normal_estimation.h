#pragma once
/// \file mesh_normal_estimation.h
/// Vertex normals of a triangle mesh as a PCL-style stage (METHOD.md step 2): the mesh's own normals,
/// oriented by its faces, where pcl::NormalEstimation would fit planes to neighbours and guess the sign.
///
///   pcl_sparse::MeshNormalEstimation ne;
///   ne.setInputMesh (mesh);
///   pcl::PointCloud<pcl::Normal> normals;   // or pcl::PointCloud<pcl::PointNormal> (xyz filled too)
///   ne.compute (normals);

#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <memory>
#include <string>

namespace pcl_sparse
{
  /// Per-vertex unit normals (area- or angle-weighted face normals) and the surface variation
  /// lambda0 / (lambda0 + lambda1 + lambda2) of each vertex's 1-ring (the "curvature" pcl::NormalEstimation
  /// reports). Vertices without a non-degenerate face get NaN normals and curvature and make the output
  /// not dense, as in PCL.
  class MeshNormalEstimation
  {
  public:
    using Ptr = std::shared_ptr<MeshNormalEstimation>;
    using ConstPtr = std::shared_ptr<const MeshNormalEstimation>;

    MeshNormalEstimation () = default;
    virtual ~MeshNormalEstimation () = default;

    void setInputMesh (const TriangleMesh::ConstPtr& mesh) { mesh_ = mesh; topology_.reset (); }
    const TriangleMesh::ConstPtr& getInputMesh () const { return mesh_; }

    /// Topology of the input mesh, if already built (otherwise compute builds it). Set after setInputMesh.
    void setTopology (const std::shared_ptr<const MeshTopology>& topology) { topology_ = topology; }

    /// Face weighting of the vertex normals (default: area, as METHOD.md step 2 lists first).
    void setWeighting (NormalWeighting weighting) { weighting_ = weighting; }
    NormalWeighting getWeighting () const { return weighting_; }

    /// One normal per vertex, in vertex order. Bad input: PCL_ERROR-style message, empty output.
    void compute (pcl::PointCloud<pcl::Normal>& output);
    /// Same, with the vertex positions in x, y, z.
    void compute (pcl::PointCloud<pcl::PointNormal>& output);

    const std::string& getClassName () const { return name_; }

  protected:
    /// Fills normal_x.. and curvature of every output point (already sized #V).
    template <typename PointT>
    void computeNormals (pcl::PointCloud<PointT>& output);

    bool initCompute ();

    TriangleMesh::ConstPtr mesh_;
    std::shared_ptr<const MeshTopology> topology_;
    NormalWeighting weighting_ = NormalWeighting::Area;
    std::string name_ = "MeshNormalEstimation";
  };
} // namespace pcl_sparse
