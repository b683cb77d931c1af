#include <pcl_sparse/keypoints/harris_keypoint3d_mesh.h>

#include <pcl/console/print.h>

#include <algorithm>

namespace pcl_sparse
{
  void
  HarrisKeypoint3DMesh::compute (PointCloudOut& output)
  {
    output.clear ();
    output.header = pcl::PCLHeader ();
    responses_.clear ();
    keypoints_indices_ = std::make_shared<pcl::PointIndices> ();
    if (!mesh_ || mesh_->empty ())
    {
      PCL_ERROR ("[pcl_sparse::%s::compute] No input mesh given (or it has no triangles)!\n", getClassName ().c_str ());
      return;
    }
    if (topology_ && topology_->numVertices () != mesh_->numVertices ())
    {
      PCL_ERROR ("[pcl_sparse::%s::compute] The topology given does not belong to the input mesh!\n", getClassName ().c_str ());
      return;
    }
    if (indices_)
      for (int v : *indices_)
        if (v < 0 || static_cast<std::size_t> (v) >= mesh_->numVertices ())
        {
          PCL_ERROR ("[pcl_sparse::%s::compute] Index %d out of range (%zu vertices)!\n", getClassName ().c_str (), v,
                     mesh_->numVertices ());
          return;
        }
    validateHarris3DOptions (options_);
    if (!topology_)
      topology_ = std::make_shared<const MeshTopology> (buildMeshTopology (*mesh_));
    detectKeypoints (output);
  }

  void
  HarrisKeypoint3DMesh::detectKeypoints (PointCloudOut& output)
  {
    const TriangleMesh& mesh = *mesh_;
    const MeshTopology& topology = *topology_;
    std::size_t num_candidates = mesh.numVertices ();
    if (indices_)
    {
      responses_ = computeHarris3DResponses (mesh, topology, options_, *indices_);
      std::vector<int> distinct (*indices_);
      std::sort (distinct.begin (), distinct.end ());
      num_candidates = static_cast<std::size_t> (std::unique (distinct.begin (), distinct.end ()) - distinct.begin ());
    }
    else
      responses_ = computeHarris3DResponses (mesh, topology, options_);

    const std::vector<int> keypoints = selectHarris3DKeypoints (mesh, topology, responses_, options_, num_candidates);
    keypoints_indices_->indices.assign (keypoints.begin (), keypoints.end ());
    output.resize (keypoints.size ());
    for (std::size_t i = 0; i < keypoints.size (); ++i)
    {
      const Eigen::Vector3d& p = mesh.vertices[keypoints[i]];
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
