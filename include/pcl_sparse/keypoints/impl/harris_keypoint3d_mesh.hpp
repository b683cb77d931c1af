#pragma once
/// \file harris_keypoint3d_mesh.hpp
/// \brief Definitions of HarrisKeypoint3DMesh (keypoints/harris_keypoint3d_mesh.h).

#include <pcl_sparse/keypoints/harris_keypoint3d_mesh.h>
#include <pcl_sparse/surface/impl/surface_stage.hpp>

#include <algorithm>

namespace pcl_sparse
{
  template <typename PointInT>
  void
  HarrisKeypoint3DMesh<PointInT>::compute (PointCloudOut& output)
  {
    output.clear ();
    output.header = pcl::PCLHeader ();
    responses_.clear ();
    keypoints_indices_ = std::make_shared<pcl::PointIndices> ();
    this->initCompute ();
    validateHarris3DOptions (options_);
    detectKeypoints (output);
    // As PCL's keypoints: the input's frame and stamp (a mesh input has none).
    if (this->input_)
      output.header = keypoints_indices_->header = this->input_->header;
    this->deinitCompute ();
  }

  template <typename PointInT>
  void
  HarrisKeypoint3DMesh<PointInT>::detectKeypoints (PointCloudOut& output)
  {
    const TriangleMesh& mesh = *this->surface_;
    const MeshTopology& topology = *this->surface_topology_;
    Harris3DOptions options = options_;
    options.num_threads = this->num_threads_;
    std::size_t num_candidates = mesh.numVertices ();
    if (this->selected_)
    {
      const std::vector<int> selected = this->selectedSurfaceVertices ();
      responses_ = computeHarris3DResponses (mesh, topology, options, selected);
      std::vector<int> distinct (selected);
      std::sort (distinct.begin (), distinct.end ());
      num_candidates = static_cast<std::size_t> (std::unique (distinct.begin (), distinct.end ()) - distinct.begin ());
    }
    else
      responses_ = computeHarris3DResponses (mesh, topology, options);

    const std::vector<int> keypoints = selectHarris3DKeypoints (mesh, topology, responses_, options, num_candidates);
    keypoints_indices_->indices.clear ();
    for (int v : keypoints)  // indices of the input's points (a scan's surface keeps only its clean points)
      keypoints_indices_->indices.push_back (this->surfaceIsScan () ? static_cast<int> (this->surface_input_indices_[v]) : v);
    output.resize (keypoints.size ());
    for (std::size_t i = 0; i < keypoints.size (); ++i)
    {
      const Eigen::Vector3d p = this->surface_origin_ + mesh.vertices[keypoints[i]];
      PointOut& q = output[i];
      q.x = static_cast<float> (p.x ());
      q.y = static_cast<float> (p.y ());
      q.z = static_cast<float> (p.z ());
      q.intensity = static_cast<float> (responses_[keypoints[i]]);
    }
    output.width = static_cast<std::uint32_t> (output.size ());
    output.height = 1;
    output.is_dense = true;
  }
} // namespace pcl_sparse
