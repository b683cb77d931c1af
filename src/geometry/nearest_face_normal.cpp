#include <pcl_sparse/geometry/nearest_face_normal.h>

#include <pcl_sparse/mesh/mesh_normals.h>

#include <algorithm>

namespace pcl_sparse
{
  NearestFaceNormal::NearestFaceNormal (const TriangleMesh& mesh, int num_threads)
    : tree_ (mesh, num_threads), face_normals_ (computeFaceNormals (mesh))
  {
    // Double arithmetic: two faces' distances to their shared edge differ by rounding only.
    double largest = 0.0;
    for (const Eigen::Vector3d& v : mesh.vertices)
      largest = std::max (largest, v.cwiseAbs ().maxCoeff ());
    tie_ = 1e-12 * largest;
  }

  TriangleTree::Nearest
  NearestFaceNormal::nearest (const Eigen::Vector3d& p, const Eigen::Vector3d& direction, double& cosine,
                              std::vector<TriangleTree::Nearest>& tied) const
  {
    const TriangleTree::Nearest found = tree_.nearestAndTied (p, tie_, tied);
    cosine = -1.0;
    if (found.triangle < 0)
      return found;
    cosine = direction.dot (face_normals_[static_cast<std::size_t> (found.triangle)]);
    for (const TriangleTree::Nearest& face : tied)
      cosine = std::max (cosine, direction.dot (face_normals_[static_cast<std::size_t> (face.triangle)]));
    return found;
  }
} // namespace pcl_sparse
