#include <pcl_sparse/cloud/depth_steps_removal.h>

#include <pcl_sparse/cloud/grid_neighborhoods.h>
#include <pcl_sparse/common/thread_count.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// Half-width of the lattice in lattice steps (7 x 7 pixels, spread), and how many depth steps it reaches.
    constexpr int kLatticeRadius = 3;
    constexpr double kStepsReached = 1.0;
    constexpr std::size_t kMinNeighbors = 8;
    /// |cos| between the plane's normal and the line of sight below which the plane says little of the depth.
    constexpr double kMinRayCosine = 0.1;
    /// Steps are taken out only where they are wider than the sampling: the median step at least this many
    /// pixel spacings (over horizontally adjacent pixels). Finer steps make no terraces the normals' windows
    /// could sit on (table_scene_mug_stereo_textured.pcd: 0.65 spacings, milk_cartoon 1.2; office1 5.5).
    constexpr double kMinStepOverSpacing = 2.0;

    /// Median over horizontally adjacent pixels of the depth step at the left one over their distance across
    /// the depth axis.
    double
    medianStepOverSpacing (const std::vector<Eigen::Vector3d>& positions, const ScanGrid& grid, const DepthQuantization& steps)
    {
      std::vector<double> ratios;
      const int levels = static_cast<int> (steps.levels.size ());
      for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x + 1 < grid.width; ++x)
        {
          const int a = grid.at (x, y), b = grid.at (x + 1, y);
          if (a < 0 || b < 0)
            continue;
          Eigen::Vector3d across = positions[b] - positions[a];
          across[steps.axis] = 0.0;
          const int l = steps.level[a];
          if (l >= 0 && l + 1 < levels && across.norm () > 0.0)
            ratios.push_back ((steps.levels[l + 1] - steps.levels[l]) / across.norm ());
        }
      if (ratios.empty ())
        return 0.0;
      auto median = ratios.begin () + static_cast<std::ptrdiff_t> (ratios.size () / 2);
      std::nth_element (ratios.begin (), median, ratios.end ());
      return *median;
    }
  } // namespace

  bool
  removeDepthSteps (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& finite,
                    const ScanGrid& grid, const DepthQuantization& steps, const Eigen::Vector3d& viewpoint,
                    const ShadowRule& shadow, double gap_factor, int num_threads, std::vector<Eigen::Vector3d>& moved)
  {
    if (!steps.active () || medianStepOverSpacing (positions, grid, steps) < kMinStepOverSpacing)
      return false;
    moved = positions;
    const GridEdges edges = classifyGridEdges (grid, positions, gap_factor, shadow, num_threads, &steps);
    const PointNeighborhoods hoods =
      gridNeighborhoods (grid, positions, edges, kLatticeRadius, gap_factor, num_threads, &steps, kStepsReached);
    const int axis = steps.axis;
    const int levels = static_cast<int> (steps.levels.size ());
#pragma omp parallel for num_threads(resolveThreadCount (num_threads)) schedule(static)
    for (long p = 0; p < static_cast<long> (positions.size ()); ++p)
    {
      const std::size_t i = static_cast<std::size_t> (p);
      const int l = steps.level[i];
      const auto around = hoods.of (i);
      if (!finite[i] || l < 0 || around.size () < kMinNeighbors)
        continue;
      Eigen::Vector3d centroid = positions[i];
      for (const int j : around)
        centroid += positions[j];
      centroid /= static_cast<double> (around.size () + 1);
      Eigen::Matrix3d scatter = (positions[i] - centroid) * (positions[i] - centroid).transpose ();
      for (const int j : around)
        scatter += (positions[j] - centroid) * (positions[j] - centroid).transpose ();
      const Eigen::Vector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> (scatter).eigenvectors ().col (0);
      const Eigen::Vector3d ray = positions[i] - viewpoint;
      const double along = normal.dot (ray);
      if (!(std::abs (along) > kMinRayCosine * ray.norm ()) || ray[axis] == 0.0)
        continue;
      // Where the line of sight meets the plane, as a multiple of the ray, kept within the point's bin.
      double t = normal.dot (centroid - viewpoint) / along;
      const double low = l > 0 ? 0.5 * (steps.levels[l - 1] + steps.levels[l]) : steps.levels[l];
      const double high = l + 1 < levels ? 0.5 * (steps.levels[l] + steps.levels[l + 1]) : steps.levels[l];
      const double depth = viewpoint[axis] + t * ray[axis];
      const double kept = std::min (high, std::max (low, depth));
      if (kept != depth)
        t = (kept - viewpoint[axis]) / ray[axis];
      moved[i] = viewpoint + t * ray;
    }
    return true;
  }
} // namespace pcl_sparse
