#include <pcl_sparse/normals/impl/mesh_normal_estimation.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>

namespace pcl_sparse
{
  float
  ringSurfaceVariation (const TriangleMesh& mesh, const MeshTopology& topology, int v)
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

#define PCL_SPARSE_INSTANTIATE_NORMALS(T) template class MeshNormalEstimation<T>;
  PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_INSTANTIATE_NORMALS)
#undef PCL_SPARSE_INSTANTIATE_NORMALS
} // namespace pcl_sparse
