#pragma once
/// \file harris_keypoint3d_mesh.h
/// Harris 3D keypoints of a triangle mesh as a PCL-style stage (METHOD.md step 3). The mathematics is in
/// harris3d.h; this class holds the input and the results.
///
///   pcl_sparse::HarrisKeypoint3DMesh harris;
///   harris.setInputMesh (mesh);                      // TriangleMesh::ConstPtr
///   pcl::PointCloud<pcl::PointXYZI> keypoints;
///   harris.compute (keypoints);                      // vertex positions, intensity = response
///   const auto& order = harris.getKeypointsIndices ()->indices;
///   const auto& responses = harris.getResponses ();  // every vertex (NaN: no response)

#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/PointIndices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Harris 3D keypoint detector for meshes (Sipiran & Bustos 2011). Output: keypoints at the input
  /// vertex positions, intensity = response, in decreasing response (ties by vertex index), identical for
  /// any thread count. Unlike pcl::HarrisKeypoint3D it works on the mesh's rings and fits a quadric.
  class HarrisKeypoint3DMesh
  {
  public:
    using Ptr = std::shared_ptr<HarrisKeypoint3DMesh>;
    using ConstPtr = std::shared_ptr<const HarrisKeypoint3DMesh>;
    using PointOut = pcl::PointXYZI;
    using PointCloudOut = pcl::PointCloud<PointOut>;
    /// Same type as pcl::IndicesConstPtr (pcl/pcl_base.h) with PCL's default 32-bit index_t.
    using IndicesConstPtr = std::shared_ptr<const std::vector<int>>;

    HarrisKeypoint3DMesh () = default;
    virtual ~HarrisKeypoint3DMesh () = default;

    /// The mesh to detect keypoints on (required).
    void setInputMesh (const TriangleMesh::ConstPtr& mesh) { mesh_ = mesh; topology_.reset (); }
    const TriangleMesh::ConstPtr& getInputMesh () const { return mesh_; }

    /// Topology of the input mesh, if already built (otherwise compute builds it). Set after setInputMesh.
    void setTopology (const std::shared_ptr<const MeshTopology>& topology) { topology_ = topology; }

    /// Restricts detection to these vertices (responses of the others are NaN; the selection fraction
    /// refers to their number). Empty pointer = all vertices.
    void setIndices (const IndicesConstPtr& indices) { indices_ = indices; }
    const IndicesConstPtr& getIndices () const { return indices_; }

    void setOptions (const Harris3DOptions& options) { options_ = options; }
    const Harris3DOptions& getOptions () const { return options_; }

    /// Harris constant (default 0.04).
    void setK (double k) { options_.k = k; }
    /// Fixed ring count (> 0) instead of the adaptive neighbourhood.
    void setRings (int rings) { options_.rings = rings; }
    /// Adaptive neighbourhood radius as a fraction of the bounding-box diagonal (and rings = 0).
    void setAdaptiveFraction (double fraction) { options_.rings = 0; options_.adaptive_fraction = fraction; }
    /// Keep this fraction of #V (Fraction selection).
    void setSelectionFraction (double fraction) { options_.selection = Harris3DSelection::Fraction; options_.selection_fraction = fraction; }
    /// Clustering selection with this minimum keypoint distance (fraction of the bounding-box diagonal).
    void setClustering (double fraction) { options_.selection = Harris3DSelection::Clustering; options_.cluster_fraction = fraction; }
    /// OpenMP threads (0 = default). Results do not depend on it.
    void setNumberOfThreads (int threads) { options_.num_threads = threads; }

    /// Detects the keypoints. On bad input prints a PCL_ERROR-style message, leaves \a output empty and
    /// returns (as PCL stages do); options out of range throw pcl_sparse::Error.
    void compute (PointCloudOut& output);

    /// Vertex indices of the keypoints of the last compute, in output order.
    pcl::PointIndicesConstPtr getKeypointsIndices () const { return keypoints_indices_; }

    /// Response of every vertex of the last compute (#V entries; NaN: no response).
    const std::vector<double>& getResponses () const { return responses_; }

    const std::string& getClassName () const { return name_; }

  protected:
    /// The detector proper; compute checks the input first.
    virtual void detectKeypoints (PointCloudOut& output);

    TriangleMesh::ConstPtr mesh_;
    std::shared_ptr<const MeshTopology> topology_;
    IndicesConstPtr indices_;
    Harris3DOptions options_;
    std::vector<double> responses_;
    pcl::PointIndicesPtr keypoints_indices_ = std::make_shared<pcl::PointIndices> ();
    std::string name_ = "HarrisKeypoint3DMesh";
  };
} // namespace pcl_sparse
