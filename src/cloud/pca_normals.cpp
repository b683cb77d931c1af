#include <pcl_sparse/cloud/pca_normals.h>
#include <pcl_sparse/common/thread_count.h>

#include <Eigen/Eigenvalues>

namespace pcl_sparse
{
  namespace
  {
    Eigen::Vector3d
    pcaNormal (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& hoods,
               const std::vector<std::uint8_t>& usable, int i)
    {
      // One pass over offsets from the point itself (small numbers: no cancellation worth a second pass).
      Eigen::Vector3d sum = Eigen::Vector3d::Zero ();
      Eigen::Matrix3d products = Eigen::Matrix3d::Zero ();
      int count = 1;
      for (const int j : hoods.of (i))
        if (usable[j])
        {
          const Eigen::Vector3d d = positions[j] - positions[i];
          sum += d;
          products.noalias () += d * d.transpose ();
          ++count;
        }
      if (count < 3)
        return Eigen::Vector3d::Zero ();
      const Eigen::Vector3d mean = sum / count;
      const Eigen::Matrix3d covariance = products / count - mean * mean.transpose ();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
      solver.computeDirect (covariance);
      Eigen::Vector3d normal = solver.eigenvectors ().col (0);
      if (!normal.allFinite () || !(normal.squaredNorm () > 0.5))
      {
        solver.compute (covariance);  // the iterative solver where the closed form breaks down
        normal = solver.eigenvectors ().col (0);
      }
      return normal.allFinite () ? normal.normalized () : Eigen::Vector3d::Zero ();
    }
  } // namespace

  void
  estimatePcaNormals (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                      const std::vector<std::uint8_t>& usable, int num_threads, std::vector<Eigen::Vector3d>& normals,
                      const std::vector<int>* only)
  {
    normals.resize (positions.size (), Eigen::Vector3d::Zero ());
    const std::ptrdiff_t count = only ? static_cast<std::ptrdiff_t> (only->size ())
                                      : static_cast<std::ptrdiff_t> (positions.size ());
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
    for (std::ptrdiff_t m = 0; m < count; ++m)
    {
      const int i = only ? (*only)[m] : static_cast<int> (m);
      normals[i] = usable[i] ? pcaNormal (positions, neighborhoods, usable, i) : Eigen::Vector3d::Zero ();
    }
  }
} // namespace pcl_sparse
