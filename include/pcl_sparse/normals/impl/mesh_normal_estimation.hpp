#pragma once
/// \file mesh_normal_estimation.hpp
/// \brief Definitions of MeshNormalEstimation (normals/mesh_normal_estimation.h).

#include <pcl_sparse/surface/impl/surface_stage.hpp>
#include <pcl_sparse/normals/mesh_normal_estimation.h>

#include <pcl/point_types.h>

#include <cstdint>
#include <limits>

namespace pcl_sparse
{
  template <typename PointInT>
  template <typename PointT>
  void
  MeshNormalEstimation<PointInT>::computeNormals (pcl::PointCloud<PointT>& output)
  {
    const TriangleMesh& mesh = *this->surface_;
    const MeshTopology& topology = *this->surface_topology_;
    // A scan's normals are its neighbourhood surface's (PCA, oriented); a mesh's come from its faces.
    const bool scan = this->surfaceIsScan ();
    const std::vector<Eigen::Vector3d> normals =
      scan ? this->cloud_surface_->normals : computeVertexNormals (mesh, topology, weighting_);
    const std::vector<int> rows = this->outputVertices ();
    const std::int64_t size = static_cast<std::int64_t> (rows.size ());
    output.resize (rows.size ());
    const float nan = std::numeric_limits<float>::quiet_NaN ();
    bool dense = true;
#pragma omp parallel for schedule(dynamic, 1024) reduction(&& : dense) num_threads(this->threadsToUse ())
    for (std::int64_t i = 0; i < size; ++i)
    {
      const int v = rows[i];
      PointT& p = output[i];
      if constexpr (pcl::traits::has_xyz_v<PointT>)
        p.getVector3fMap () = this->outputPosition (static_cast<std::size_t> (i), v).template cast<float> ();
      if (v >= 0 && normals[v].squaredNorm () > 0.0 && mesh.vertices[v].allFinite ())
      {
        p.normal_x = static_cast<float> (normals[v].x ());
        p.normal_y = static_cast<float> (normals[v].y ());
        p.normal_z = static_cast<float> (normals[v].z ());
        p.curvature = ringSurfaceVariation (mesh, topology, v);
      }
      else
      {
        p.normal_x = p.normal_y = p.normal_z = p.curvature = nan;
        dense = false;
      }
    }
    output.width = static_cast<std::uint32_t> (output.size ());
    output.height = 1;
    output.is_dense = dense;
    // As PCL's features: the input's header (frame and stamp), and an organized input's width x height
    // when each input point has its row (code reading normals.at (x, y) threw on a 1-row cloud).
    if (this->input_)
    {
      output.header = this->input_->header;
      if (!this->selected_ && this->input_->height > 1 && output.size () == this->input_->size ())
      {
        output.width = this->input_->width;
        output.height = this->input_->height;
      }
    }
  }

  template <typename PointInT>
  void
  MeshNormalEstimation<PointInT>::compute (pcl::PointCloud<pcl::Normal>& output)
  {
    output.clear ();
    this->initCompute ();
    computeNormals (output);
    this->deinitCompute ();
  }

  template <typename PointInT>
  void
  MeshNormalEstimation<PointInT>::compute (pcl::PointCloud<pcl::PointNormal>& output)
  {
    output.clear ();
    this->initCompute ();
    computeNormals (output);
    this->deinitCompute ();
  }
} // namespace pcl_sparse
