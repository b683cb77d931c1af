#include <pcl_sparse/cloud/depth_steps_removal.h>

#include <pcl_sparse/cloud/grid_neighborhoods.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/common/upper_median.h>
#include <pcl_sparse/geometry/point_kd_tree.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <memory>

namespace pcl_sparse
{
  namespace
  {
    /// Half-width of the lattice in lattice steps (7 x 7 pixels, spread), and how many depth steps it reaches.
    constexpr int kLatticeRadius = 3;
    constexpr double kStepsReached = 1.0;
    /// Unorganized scans: the ball a point's plane is fitted in, in steps. Two, not one: a ball of one step
    /// around a point on a terrace does not reach the next terrace, a step deeper (the image lattice measures
    /// over the steps instead). On the stepped slanted plane of test_cloud_surface one step left the normals
    /// 38.7 degrees off.
    constexpr double kBallSteps = 2.0;
    /// Points wanted in such a ball (it is searched among every d-th point, d a power of 2 up to
    /// kMaxDecimation, for about this many).
    constexpr double kBallPoints = 48.0;
    constexpr std::size_t kMaxDecimation = 32;
    constexpr std::size_t kMinNeighbors = 8;
    /// |cos| between the plane's normal and the line of sight below which the plane says little of the depth.
    constexpr double kMinRayCosine = 0.1;
    /// Steps are taken out only where they are wider than the sampling: the median step at least this many
    /// pixel spacings (over horizontally adjacent pixels). Finer steps make no terraces the normals' windows
    /// could sit on (table_scene_mug_stereo_textured.pcd: 0.65 spacings, milk_cartoon 1.2; office1 5.5).
    constexpr double kMinStepOverSpacing = 2.0;
    /// Fewest ratios (pixel pairs, or points of an unorganized scan) a level's median is taken over: stray
    /// levels of a few points pass by chance (table_scene_mug_stereo_textured.pcd: 4 levels of 2-17 points
    /// among sparse far ones, and moving those 27 points cost a tenth of a second of its encoding), terraced
    /// ones hold more (office1's nearest levels 32-60 points each, milk_cartoon's 75 and more).
    constexpr std::size_t kMinLevelRatios = 32;

    /// Per level, whether the upper median of its step-over-spacing \a ratios (reordered), at least
    /// \a min_count of them, is at least kMinStepOverSpacing.
    std::vector<std::uint8_t>
    levelsAtLeastTheGate (std::vector<std::vector<double>>& ratios, std::size_t min_count)
    {
      std::vector<std::uint8_t> wide (ratios.size ());
      for (std::size_t l = 0; l < ratios.size (); ++l)
        wide[l] = ratios[l].size () >= min_count && upperMedian (ratios[l]) >= kMinStepOverSpacing ? 1 : 0;
      return wide;
    }

    /// The depth step at level \a l for the gate: the smaller of those above and below it (one where the other
    /// is missing). A gap in the levels is no step: the top level of a near surface has the whole gap to a few
    /// stray far points above it (table_scene_mug_stereo_textured.pcd: medians of 126 spacings).
    double
    gateStep (const DepthQuantization& steps, int l)
    {
      const double above = steps.stepAbove (l), below = steps.stepAbove (l - 1);
      return above > 0.0 && below > 0.0 ? std::min (above, below) : std::max (above, below);
    }

    bool
    anyLevel (const std::vector<std::uint8_t>& wide)
    {
      return std::find (wide.begin (), wide.end (), 1) != wide.end ();
    }

    /// Per depth level, whether its steps are wider than the sampling: the upper median, over horizontally
    /// adjacent pixels whose left one is at the level (kMinLevelRatios pairs at least), of the level's step
    /// (gateStep) over their distance across the depth axis, at least kMinStepOverSpacing. Per level, not
    /// over the frame: the steps grow with the square of the depth and the spacing only with the depth, so
    /// a frame's far part may be terraced where its near part, most of its pixels, is not
    /// (milk_cartoon_all_small_clorox.pcd: 1.2 over the frame).
    std::vector<std::uint8_t>
    wideLevels (const std::vector<Eigen::Vector3d>& positions, const ScanGrid& grid, const DepthQuantization& steps)
    {
      std::vector<std::vector<double>> ratios (steps.levels.size ());
      for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x + 1 < grid.width; ++x)
        {
          const int a = grid.at (x, y), b = grid.at (x + 1, y);
          if (a < 0 || b < 0 || steps.level[a] < 0)
            continue;
          Eigen::Vector3d across = positions[b] - positions[a];
          across[steps.axis] = 0.0;
          const double step = gateStep (steps, steps.level[a]);
          if (step > 0.0 && across.norm () > 0.0)
            ratios[steps.level[a]].push_back (step / across.norm ());
        }
      return levelsAtLeastTheGate (ratios, kMinLevelRatios);
    }

    /// Moves point \a i (into \a moved) along its line of sight from \a viewpoint onto the plane (PCA) of it
    /// and \a around, as far as its step's bin allows; leaves it with fewer than kMinNeighbors around, or
    /// where its line of sight meets the plane near grazing.
    template <typename Range>
    void
    moveOntoNeighboursPlane (const std::vector<Eigen::Vector3d>& positions, std::size_t i, const Range& around,
                             const DepthQuantization& steps, const Eigen::Vector3d& viewpoint, Eigen::Vector3d& moved)
    {
      const int l = steps.level[i];
      if (l < 0 || static_cast<std::size_t> (around.size ()) < kMinNeighbors)
        return;
      Eigen::Vector3d centroid = positions[i];
      for (const int j : around)
        centroid += positions[j];
      centroid /= static_cast<double> (around.size () + 1);
      Eigen::Matrix3d scatter = (positions[i] - centroid) * (positions[i] - centroid).transpose ();
      for (const int j : around)
        scatter += (positions[j] - centroid) * (positions[j] - centroid).transpose ();
      const Eigen::Vector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> (scatter).eigenvectors ().col (0);
      const int axis = steps.axis;
      const Eigen::Vector3d ray = positions[i] - viewpoint;
      const double along = normal.dot (ray);
      if (!(std::abs (along) > kMinRayCosine * ray.norm ()) || ray[axis] == 0.0)
        return;
      // Where the line of sight meets the plane, as a multiple of the ray, kept within the point's bin.
      const int levels = static_cast<int> (steps.levels.size ());
      double t = normal.dot (centroid - viewpoint) / along;
      const double low = l > 0 ? 0.5 * (steps.levels[l - 1] + steps.levels[l]) : steps.levels[l];
      const double high = l + 1 < levels ? 0.5 * (steps.levels[l] + steps.levels[l + 1]) : steps.levels[l];
      const double depth = viewpoint[axis] + t * ray[axis];
      const double kept = std::min (high, std::max (low, depth));
      if (kept != depth)
        t = (kept - viewpoint[axis]) / ray[axis];
      moved = viewpoint + t * ray;
    }
  } // namespace

  bool
  removeDepthSteps (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& finite,
                    const ScanGrid& grid, const DepthQuantization& steps, const Eigen::Vector3d& viewpoint,
                    const ShadowRule& shadow, double gap_factor, int num_threads, std::vector<Eigen::Vector3d>& moved)
  {
    if (!steps.active ())
      return false;
    const std::vector<std::uint8_t> wide = wideLevels (positions, grid, steps);
    if (!anyLevel (wide))
      return false;
    moved = positions;
    const GridEdges edges = classifyGridEdges (grid, positions, gap_factor, shadow, num_threads, &steps);
    const PointNeighborhoods hoods =
      gridNeighborhoods (grid, positions, edges, kLatticeRadius, gap_factor, num_threads, &steps, kStepsReached);
#pragma omp parallel for num_threads(resolveThreadCount (num_threads)) schedule(static)
    for (long p = 0; p < static_cast<long> (positions.size ()); ++p)
    {
      const std::size_t i = static_cast<std::size_t> (p);
      if (finite[i] && steps.level[i] >= 0 && wide[steps.level[i]])
        moveOntoNeighboursPlane (positions, i, hoods.of (i), steps, viewpoint, moved[i]);
    }
    return true;
  }

  bool
  removeDepthSteps (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& finite,
                    const DepthQuantization& steps, const Eigen::Vector3d& viewpoint, int num_threads,
                    std::vector<Eigen::Vector3d>& moved)
  {
    if (!steps.active ())
      return false;
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    std::vector<int> original;  // cloud index -> point index
    for (std::size_t i = 0; i < positions.size (); ++i)
      if (finite[i] && steps.level[i] >= 0)
      {
        const Eigen::Vector3f p = positions[i].cast<float> ();  // local frame: small numbers
        cloud->push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
        original.push_back (static_cast<int> (i));
      }
    if (original.size () < kMinNeighbors + 1)
      return false;
    const int threads = resolveThreadCount (num_threads);
    auto stepAt = [&] (int i) {  // the top level's step is the one below it
      const int l = steps.level[i];
      return l + 1 < static_cast<int> (steps.levels.size ()) ? steps.stepAbove (l) : steps.stepAbove (l - 1);
    };
    // Trees over every d-th point, d = 1, 2, 4, ..., so that a ball of two steps (hundreds of points at 5 m on
    // office1) is searched where it holds about kBallPoints: every point's ball, 5.6 s longer on office1. The
    // first (every point) serves the spacing and the gate; the others are made only past the gate.
    std::vector<std::unique_ptr<PointKdTree>> trees;
    auto addTree = [&] (std::size_t d) {
      pcl::PointCloud<pcl::PointXYZ> decimated;
      for (std::size_t c = 0; c < original.size (); c += d)
        decimated.push_back ((*cloud)[c]);
      trees.push_back (std::make_unique<PointKdTree> (decimated));
    };
    addTree (1);
    // Spacing: the mean distance to the 6 nearest (the neighbourhoods' radius). The gate's pitch: the
    // distance to the nearest across the depth axis, as between adjacent pixels of a grid (the 6 nearest
    // on a terrace reach along it, twice as far: milk_cartoon with its NaNs dropped had no level passing).
    const std::ptrdiff_t count = static_cast<std::ptrdiff_t> (original.size ());
    std::vector<double> spacing (original.size (), 0.0), pitch (original.size (), 0.0);
    auto measureSpacing = [&] (std::ptrdiff_t stride, bool skip_measured) {
#pragma omp parallel num_threads(threads)
      {
        std::vector<int> found;
        std::vector<float> squared;
#pragma omp for schedule(static)
        for (std::ptrdiff_t c = 0; c < count; c += stride)
        {
          if (skip_measured && c % 16 == 0)
            continue;
          trees[0]->nearestK ((*cloud)[c], 7, found, squared);
          double sum = 0.0;
          for (std::size_t q = 1; q < found.size (); ++q)
            sum += (positions[original[found[q]]] - positions[original[c]]).norm ();
          spacing[c] = found.size () > 1 ? sum / static_cast<double> (found.size () - 1) : 0.0;
          if (found.size () > 1)
          {
            Eigen::Vector3d across = positions[original[found[1]]] - positions[original[c]];
            across[steps.axis] = 0.0;
            pitch[c] = across.norm ();
          }
        }
      }
    };
    // The gate per depth level, as for an organized scan (wideLevels): over every 16th point first, so that a
    // scan whose steps are fine everywhere (table_scene_mug) costs no spacing of every point.
    auto wideOver = [&] (std::ptrdiff_t stride) {
      std::vector<std::vector<double>> ratios (steps.levels.size ());
      for (std::ptrdiff_t c = 0; c < count; c += stride)
        if (pitch[c] > 0.0)
          ratios[steps.level[original[c]]].push_back (gateStep (steps, steps.level[original[c]]) / pitch[c]);
      const std::size_t every = static_cast<std::size_t> (stride);  // every 16th point first: 2 of them
      return levelsAtLeastTheGate (ratios, (kMinLevelRatios + every - 1) / every);
    };
    measureSpacing (16, false);
    if (!anyLevel (wideOver (16)))
      return false;
    for (std::size_t d = 2; d <= kMaxDecimation && d * (kMinNeighbors + 1) <= original.size (); d *= 2)
      addTree (d);
    measureSpacing (1, true);
    const std::vector<std::uint8_t> wide = wideOver (1);
    if (!anyLevel (wide))
      return false;
    moved = positions;
    // Neighbours within two steps (at least 3 spacings), in index order so the sums do not depend on the tree.
#pragma omp parallel num_threads(threads)
    {
      std::vector<int> found;
      std::vector<float> squared;
      std::vector<int> around;
#pragma omp for schedule(dynamic, 256)
      for (std::ptrdiff_t c = 0; c < count; ++c)
      {
        const int i = original[c];
        if (!(spacing[c] > 0.0) || !wide[steps.level[i]])
          continue;
        const double radius = std::max (kBallSteps * stepAt (i), 3.0 * spacing[c]);
        const double expected = M_PI * (radius / spacing[c]) * (radius / spacing[c]);
        std::size_t level = 0;
        while (level + 1 < trees.size () && (std::size_t (2) << level) * kBallPoints <= expected)
          ++level;
        trees[level]->radius ((*cloud)[c], radius, found, squared);
        around.clear ();
        for (const auto f : found)
        {
          const int j = original[static_cast<std::size_t> (f) << level];
          if (j != i)
            around.push_back (j);
        }
        std::sort (around.begin (), around.end ());
        moveOntoNeighboursPlane (positions, static_cast<std::size_t> (i), around, steps, viewpoint, moved[i]);
      }
    }
    return true;
  }
} // namespace pcl_sparse
