#pragma once
/// \file harris_keypoint3d_mesh.h
/// Harris 3D keypoints of a triangle mesh as a PCL-style stage (docs/METHOD.md step 3). The mathematics is in
/// harris3d.h; this class holds the input and the results.
///
///   pcl_sparse::HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
///   harris.setInputCloud (cloud);                    // the vertices, and
///   harris.setInputPolygons (polygons);              // the faces (or setInputMesh (TriangleMesh::ConstPtr))
///   pcl::PointCloud<pcl::PointXYZI> keypoints;
///   harris.compute (keypoints);                      // vertex positions, intensity = response
///   const auto& order = harris.getKeypointsIndices ()->indices;  // input points
///   const auto& responses = harris.getResponses ();  // every surface vertex (NaN: no response)
///
/// With a mesh the two number the same vertices. With a scan (a cloud without polygons) they do not: the
/// keypoint indices are the input cloud's points, as in PCL, while the responses follow the scan's surface,
/// which keeps only its clean points (getSurfaceInputIndices gives the input point of each surface vertex).

#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/surface/surface_stage.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <pcl/PointIndices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief Harris 3D keypoint detector for meshes (Sipiran & Bustos 2011). Output: keypoints at the input
  /// vertex positions, intensity = response, in decreasing response (ties by vertex index), identical for
  /// any thread count. Unlike pcl::HarrisKeypoint3D it works on the mesh's rings and fits a quadric.
  /// setIndices restricts detection to those points (IndexUse::SelectPoints): the others get no response,
  /// neighbourhoods still span the whole surface, and the selection fraction refers to the indexed points.
  /// \tparam PointInT point type of the input cloud
  template <typename PointInT>
  class HarrisKeypoint3DMesh : public SurfaceStage<PointInT>
  {
  public:
    using Ptr = std::shared_ptr<HarrisKeypoint3DMesh<PointInT>>;
    using ConstPtr = std::shared_ptr<const HarrisKeypoint3DMesh<PointInT>>;
    using PointOut = pcl::PointXYZI;
    using PointCloudOut = pcl::PointCloud<PointOut>;

    HarrisKeypoint3DMesh () : SurfaceStage<PointInT> ("HarrisKeypoint3DMesh", IndexUse::SelectPoints) {}

    /// \brief All options of the detector (defaults: adaptive rings, k = 0.04, top 1 %).
    void setOptions (const Harris3DOptions& options) { options_ = options; }
    const Harris3DOptions& getOptions () const { return options_; }

    /// \brief Harris constant (default 0.04).
    void setK (double k) { options_.k = k; }
    /// \brief Fixed ring count (> 0) instead of the adaptive neighbourhood.
    void setRings (int rings) { options_.rings = rings; }
    /// \brief Adaptive neighbourhood radius as a fraction of the bounding-box diagonal (and rings = 0).
    void setAdaptiveFraction (double fraction) { options_.rings = 0; options_.adaptive_fraction = fraction; }
    /// \brief Keep this fraction of #V (Fraction selection).
    void setSelectionFraction (double fraction) { options_.selection = Harris3DSelection::Fraction; options_.selection_fraction = fraction; }
    /// \brief Clustering selection with this minimum keypoint distance (fraction of the bounding-box diagonal).
    void setClustering (double fraction) { options_.selection = Harris3DSelection::Clustering; options_.cluster_fraction = fraction; }

    /// \brief Detects the keypoints. Throws pcl_sparse::Error for a missing or empty surface, an index out of
    /// range or options out of range.
    /// \param[out] output keypoints (replaced), strongest first
    void compute (PointCloudOut& output);

    /// \brief Indices of the keypoints of the last compute, in output order: the mesh's vertices, or for a
    /// scan the input cloud's points (not the rows of getResponses; see getSurfaceInputIndices).
    pcl::PointIndicesConstPtr getKeypointsIndices () const { return keypoints_indices_; }

    /// \brief Response of every surface vertex of the last compute (#V entries; NaN: no response). For a scan
    /// the surface vertex v stands for input point getSurfaceInputIndices ()[v].
    const std::vector<double>& getResponses () const { return responses_; }

  protected:
    /// \brief The detector proper, on the surface initCompute prepared.
    virtual void detectKeypoints (PointCloudOut& output);

    Harris3DOptions options_;
    std::vector<double> responses_;
    pcl::PointIndicesPtr keypoints_indices_ = std::make_shared<pcl::PointIndices> ();
  };
} // namespace pcl_sparse

#ifdef PCL_NO_PRECOMPILE
#include <pcl_sparse/keypoints/impl/harris_keypoint3d_mesh.hpp>
#else
#define PCL_SPARSE_EXTERN_HARRIS(T) extern template class pcl_sparse::HarrisKeypoint3DMesh<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_EXTERN_HARRIS)
#undef PCL_SPARSE_EXTERN_HARRIS
#endif
