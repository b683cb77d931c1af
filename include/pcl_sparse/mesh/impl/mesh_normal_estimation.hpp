#pragma once
/// \file mesh_normal_estimation.hpp
/// \brief Definitions of MeshNormalEstimation (mesh/mesh_normal_estimation.h).

#include <pcl_sparse/mesh/impl/surface_stage.hpp>
#include <pcl_sparse/mesh/mesh_normal_estimation.h>

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
    const std::vector<Eigen::Vector3d> normals = computeVertexNormals (mesh, topology, weighting_);
    const std::int64_t size = this->selected_ ? static_cast<std::int64_t> (this->selected_->size ())
                                              : static_cast<std::int64_t> (normals.size ());
    output.resize (static_cast<std::size_t> (size));
    const float nan = std::numeric_limits<float>::quiet_NaN ();
    bool dense = true;
#pragma omp parallel for schedule(dynamic, 1024) reduction(&& : dense) num_threads(this->threadsToUse ())
    for (std::int64_t i = 0; i < size; ++i)
    {
      const int v = this->selected_ ? (*this->selected_)[i] : static_cast<int> (i);
      PointT& p = output[i];
      if constexpr (pcl::traits::has_xyz_v<PointT>)
        p.getVector3fMap () = mesh.vertices[v].template cast<float> ();
      const Eigen::Vector3d& n = normals[v];
      if (n.squaredNorm () > 0.0 && mesh.vertices[v].allFinite ())
      {
        p.normal_x = static_cast<float> (n.x ());
        p.normal_y = static_cast<float> (n.y ());
        p.normal_z = static_cast<float> (n.z ());
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
