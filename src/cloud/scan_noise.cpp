#include <pcl_sparse/cloud/scan_noise.h>

#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/common/upper_median.h>
#include <pcl_sparse/geometry/quadric_fit.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// |r| / sqrt (1 + h) for point i, or a negative value when the fit is not possible.
    double
    standardisedResidual (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& hoods,
                          const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                          int i, std::vector<Eigen::Vector3d>& local)
    {
      const Eigen::Matrix3d frame = frameAroundNormal (normals[i]);
      local.clear ();
      double extent = 0.0;
      for (const int j : hoods.of (i))
        if (usable[j])
        {
          local.push_back (frame.transpose () * (positions[j] - positions[i]));
          extent = std::max ({extent, std::abs (local.back ().x ()), std::abs (local.back ().y ())});
        }
      if (local.size () < 7 || !(extent > 0.0))
        return -1.0;
      // The neighbours must spread in both tangent directions: along a lidar ring or a scan line a quadric
      // interpolates them and the residual says nothing about the noise.
      Eigen::Vector2d mean = Eigen::Vector2d::Zero ();
      for (const auto& q : local)
        mean += q.head<2> ();
      mean /= static_cast<double> (local.size ());
      Eigen::Matrix2d spread = Eigen::Matrix2d::Zero ();
      for (const auto& q : local)
        spread.noalias () += (q.head<2> () - mean) * (q.head<2> () - mean).transpose ();
      const Eigen::Vector2d eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> (spread, Eigen::EigenvaluesOnly).eigenvalues ();
      if (!(eigenvalues[0] >= 0.05 * eigenvalues[1]))
        return -1.0;
      const double s = 1.0 / extent;
      Eigen::Matrix<double, 6, 6> AtA = Eigen::Matrix<double, 6, 6>::Zero ();
      Eigen::Matrix<double, 6, 1> Atz = Eigen::Matrix<double, 6, 1>::Zero ();
      for (const auto& q : local)
      {
        const double x = q.x () * s, y = q.y () * s;
        Eigen::Matrix<double, 6, 1> row;
        row << 1.0, x, y, x * x, x * y, y * y;
        AtA.selfadjointView<Eigen::Lower> ().rankUpdate (row);
        Atz += row * q.z ();
      }
      AtA = AtA.selfadjointView<Eigen::Lower> ();
      const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt (AtA);
      if (ldlt.info () != Eigen::Success || !ldlt.isPositive () ||
          ldlt.vectorD ().minCoeff () <= 1e-10 * ldlt.vectorD ().maxCoeff ())
        return -1.0;
      // The point is at the frame's origin: prediction c0, leverage e0^T (A^T A)^-1 e0.
      const Eigen::Matrix<double, 6, 1> e0 = Eigen::Matrix<double, 6, 1>::Unit (0);
      const double predicted = ldlt.solve (Atz)[0];
      const double leverage = ldlt.solve (e0)[0];
      if (!std::isfinite (predicted) || !(leverage >= 0.0))
        return -1.0;
      return std::abs (predicted) / std::sqrt (1.0 + leverage);
    }
  } // namespace

  double
  estimateScanNoise (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                     const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                     int num_threads, std::size_t max_samples)
  {
    const std::size_t n = positions.size ();
    const std::size_t stride = std::max<std::size_t> (1, (n + max_samples - 1) / std::max<std::size_t> (1, max_samples));
    const std::ptrdiff_t samples = static_cast<std::ptrdiff_t> ((n + stride - 1) / stride);
    std::vector<double> residuals (samples, -1.0);
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel num_threads(threads)
    {
      std::vector<Eigen::Vector3d> local;
#pragma omp for schedule(dynamic, 256)
      for (std::ptrdiff_t m = 0; m < samples; ++m)
      {
        const int i = static_cast<int> (m * stride);
        if (usable[i] && normals[i].squaredNorm () > 0.5)
          residuals[m] = standardisedResidual (positions, neighborhoods, normals, usable, i, local);
      }
    }
    residuals.erase (std::remove_if (residuals.begin (), residuals.end (), [] (double r) { return r < 0.0; }),
                     residuals.end ());
    return upperMedian (residuals) / 0.6744897501960817;
  }
} // namespace pcl_sparse
