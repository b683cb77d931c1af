#include <pcl_sparse/mesh/mesh_normal_estimation.h>

#include <pcl/console/print.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdint>
#include <limits>

namespace pcl_sparse
{
  namespace
  {
    /// Surface variation of v and its 1-ring: smallest covariance eigenvalue over their sum.
    float
    surfaceVariation (const TriangleMesh& mesh, const MeshTopology& topology, int v)
    {
      const auto ring = topology.neighborsOf (v);
      Eigen::Vector3d centroid = mesh.vertices[v];
      for (int u : ring)
        centroid += mesh.vertices[u];
      centroid /= static_cast<double> (ring.size () + 1);
      Eigen::Matrix3d covariance = (mesh.vertices[v] - centroid) * (mesh.vertices[v] - centroid).transpose ();
      for (int u : ring)
        covariance += (mesh.vertices[u] - centroid) * (mesh.vertices[u] - centroid).transpose ();
      const Eigen::Vector3d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> (covariance, Eigen::EigenvaluesOnly).eigenvalues ();
      const double sum = lambda.sum ();
      return sum > 0.0 ? static_cast<float> (std::max (0.0, lambda[0]) / sum) : 0.0f;
    }
  } // namespace

  bool
  MeshNormalEstimation::initCompute ()
  {
    if (!mesh_ || mesh_->empty ())
    {
      PCL_ERROR ("[pcl_sparse::%s::compute] No input mesh given (or it has no triangles)!\n", getClassName ().c_str ());
      return false;
    }
    if (topology_ && topology_->numVertices () != mesh_->numVertices ())
    {
      PCL_ERROR ("[pcl_sparse::%s::compute] The topology given does not belong to the input mesh!\n", getClassName ().c_str ());
      return false;
    }
    if (!topology_)
      topology_ = std::make_shared<const MeshTopology> (buildMeshTopology (*mesh_));
    return true;
  }

  template <typename PointT>
  void
  MeshNormalEstimation::computeNormals (pcl::PointCloud<PointT>& output)
  {
    const TriangleMesh& mesh = *mesh_;
    const std::vector<Eigen::Vector3d> normals = computeVertexNormals (mesh, *topology_, weighting_);
    const float nan = std::numeric_limits<float>::quiet_NaN ();
    bool dense = true;
#pragma omp parallel for schedule(dynamic, 1024) reduction(&& : dense)
    for (std::int64_t i = 0; i < static_cast<std::int64_t> (normals.size ()); ++i)
    {
      PointT& p = output[i];
      const Eigen::Vector3d& n = normals[i];
      if (n.squaredNorm () > 0.0 && mesh.vertices[i].allFinite ())
      {
        p.normal_x = static_cast<float> (n.x ());
        p.normal_y = static_cast<float> (n.y ());
        p.normal_z = static_cast<float> (n.z ());
        p.curvature = surfaceVariation (mesh, *topology_, static_cast<int> (i));
      }
      else
      {
        p.normal_x = p.normal_y = p.normal_z = p.curvature = nan;
        dense = false;
      }
    }
    output.is_dense = dense;
  }

  void
  MeshNormalEstimation::compute (pcl::PointCloud<pcl::Normal>& output)
  {
    output.clear ();
    if (!initCompute ())
      return;
    output.resize (mesh_->numVertices ());
    computeNormals (output);
    output.width = static_cast<std::uint32_t> (output.size ());
    output.height = 1;
  }

  void
  MeshNormalEstimation::compute (pcl::PointCloud<pcl::PointNormal>& output)
  {
    output.clear ();
    if (!initCompute ())
      return;
    output.resize (mesh_->numVertices ());
    for (std::size_t i = 0; i < mesh_->numVertices (); ++i)
      output[i].getVector3fMap () = mesh_->vertices[i].cast<float> ();
    computeNormals (output);
    output.width = static_cast<std::uint32_t> (output.size ());
    output.height = 1;
  }
} // namespace pcl_sparse
