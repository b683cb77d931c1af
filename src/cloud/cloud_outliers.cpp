#include <pcl_sparse/cloud/cloud_outliers.h>
#include <pcl_sparse/common/thread_count.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  std::vector<std::uint8_t>
  findCloudOutliers (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                     const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                     double noise, double noise_factor, double spacing_factor, int num_threads,
                     const std::vector<int>* only)
  {
    std::vector<std::uint8_t> outlier (positions.size (), 0);
    const std::ptrdiff_t count = only ? static_cast<std::ptrdiff_t> (only->size ())
                                      : static_cast<std::ptrdiff_t> (positions.size ());
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
    for (std::ptrdiff_t m = 0; m < count; ++m)
    {
      const int i = only ? (*only)[m] : static_cast<int> (m);
      if (!only && !usable[i])
        continue;
      // Close to the surface of some neighbour j: within its noise or spacing (the neighbour's: an outlier's
      // own spacing is large, its neighbours being far).
      bool near = false, seen = false;
      for (const int j : neighborhoods.of (i))
        if (usable[j] && normals[j].squaredNorm () > 0.5)
        {
          seen = true;
          const double limit = std::max (noise_factor * noise, spacing_factor * neighborhoods.spacing[j]);
          if (std::abs ((positions[i] - positions[j]).dot (normals[j])) <= limit)
          {
            near = true;
            break;
          }
        }
      outlier[i] = (seen && !near) ? 1 : 0;
    }
    return outlier;
  }
} // namespace pcl_sparse
