#include <pcl_sparse/resampling/patch_ownership.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  PatchOwnership::PatchOwnership (const PatchEvaluator& evaluator, const PatchOwnershipOptions& options)
    : evaluator_ (evaluator), options_ (options)
  {
    const SparseSurfaceModel& model = evaluator.model ();
    const std::size_t m = model.numPatches ();
    contender_begin_.assign (m + 1, 0);
    if (m == 0)
      return;

    // World radius of a ball around each seed holding the whole patch: the footprint's largest extent
    // and the largest height seen on a coarse grid over it, with a margin for what the grid misses.
    std::vector<double> reach (m, 0.0);
#pragma omp parallel for schedule(dynamic, 16)
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      const double e = evaluator.maxExtent (p);
      double h_max = 0.0;
      const int n = 6;
      for (int a = 0; a <= n; ++a)
        for (int b = 0; b <= n; ++b)
        {
          const double x = e * (2.0 * a / n - 1.0), y = e * (2.0 * b / n - 1.0);
          if (evaluator.centrality (p, x, y) <= 1.0)
            h_max = std::max (h_max, std::abs (evaluator.height (p, x, y)));
        }
      reach[p] = model.patches[p].radius * (std::sqrt (e * e + h_max * h_max) * 1.1 + 0.05);
    }
    const double reach_max = *std::max_element (reach.begin (), reach.end ());

    pcl::PointCloud<pcl::PointXYZ>::Ptr seeds (new pcl::PointCloud<pcl::PointXYZ>);
    seeds->resize (m);
    for (std::size_t p = 0; p < m; ++p)
      (*seeds)[p].getVector3fMap () = model.patches[p].origin.cast<float> ();
    pcl::KdTreeFLANN<pcl::PointXYZ> tree (false);
    tree.setInputCloud (seeds);

    std::vector<std::vector<int>> lists (m);
#pragma omp parallel for schedule(dynamic, 16)
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      std::vector<int> found;
      std::vector<float> distances;
      tree.radiusSearch ((*seeds)[p], static_cast<float> ((reach[p] + reach_max) * 1.001), found, distances);
      for (int q : found)
      {
        if (static_cast<std::size_t> (q) == p)
          continue;
        const double d = (model.patches[p].origin - model.patches[q].origin).norm ();
        if (d <= reach[p] + reach[q])
          lists[p].push_back (q);
      }
      std::sort (lists[p].begin (), lists[p].end ());
    }
    for (std::size_t p = 0; p < m; ++p)
    {
      for (int q : lists[p])
      {
        const PatchCode& code = model.patches[q];
        const double inverse = 1.0 / code.radius;
        contenders_.push_back ({code.origin, code.frame.col (0) * inverse, code.frame.col (1) * inverse,
                                code.frame.col (2) * inverse, code.frame.col (2), evaluator.maxExtent (q),
                                static_cast<std::size_t> (q)});
      }
      contender_begin_[p + 1] = contenders_.size ();
    }
  }

  bool
  PatchOwnership::beats (const Contender& other, std::size_t p, const Eigen::Vector3d& d, double x, double y,
                         const Eigen::Vector3d& n, double centrality) const
  {
    const double c = evaluator_.centrality (other.patch, x, y);
    if (c > 1.0 || c > centrality || (c == centrality && other.patch > p))
      return false;
    if (other.normal.dot (n) < options_.min_normal_cosine)
      return false;
    const double z = other.n.dot (d);
    return std::abs (z - evaluator_.height (other.patch, x, y)) <= options_.height_tolerance;
  }

  std::vector<int>
  PatchOwnership::neighbours (std::size_t p) const
  {
    std::vector<int> list;
    for (std::size_t k = contender_begin_[p]; k < contender_begin_[p + 1]; ++k)
      list.push_back (static_cast<int> (contenders_[k].patch));
    return list;
  }
} // namespace pcl_sparse
