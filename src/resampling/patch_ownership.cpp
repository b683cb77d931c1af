#include <pcl_sparse/resampling/patch_ownership.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  double
  footprintCentrality (const PatchFootprint& footprint, double x, double y)
  {
    const double r = std::hypot (x, y);
    if (footprint.extent.empty ())
      return r;
    if (r == 0.0)
      return 0.0;
    const double e = footprint.extentAt (std::atan2 (y, x));
    return e > 0.0 ? r / e : std::numeric_limits<double>::infinity ();
  }

  double
  footprintMaxExtent (const PatchFootprint& footprint)
  {
    if (footprint.extent.empty ())
      return 1.0;
    return *std::max_element (footprint.extent.begin (), footprint.extent.end ());
  }

  PatchOwnership::PatchOwnership (const SparseSurfaceModel& model, const PatchOwnershipOptions& options)
    : model_ (model), options_ (options)
  {
    const std::size_t m = model.numPatches ();
    neighbours_.assign (m, {});
    max_extent_.assign (m, 0.0);
    if (m == 0)
      return;

    // World radius of a ball around each seed holding the whole patch: the footprint's largest extent
    // and the largest height seen on a coarse grid over it, with a margin for what the grid misses.
    std::vector<double> reach (m, 0.0);
#pragma omp parallel for schedule(dynamic, 16)
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      const double e = footprintMaxExtent (model.patches[p].footprint);
      max_extent_[p] = e;
      double h_max = 0.0;
      const int n = 8;
      for (int a = 0; a <= n; ++a)
        for (int b = 0; b <= n; ++b)
        {
          const double x = e * (2.0 * a / n - 1.0), y = e * (2.0 * b / n - 1.0);
          if (footprintCentrality (model.patches[p].footprint, x, y) <= 1.0)
            h_max = std::max (h_max, std::abs (model.evaluate (p, x, y).value));
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

#pragma omp parallel for schedule(dynamic, 16)
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      std::vector<int> found;
      std::vector<float> distances;
      tree.radiusSearch ((*seeds)[p], static_cast<float> ((reach[p] + reach_max) * 1.001), found, distances);
      std::vector<int>& list = neighbours_[p];
      for (int q : found)
      {
        if (static_cast<std::size_t> (q) == p)
          continue;
        const double d = (model.patches[p].origin - model.patches[q].origin).norm ();
        if (d <= reach[p] + reach[q])
          list.push_back (q);
      }
      std::sort (list.begin (), list.end ());
    }
  }

  bool
  PatchOwnership::owns (std::size_t p, const Eigen::Vector3d& q, const Eigen::Vector3d& n, double centrality) const
  {
    for (int other : neighbours_[p])
    {
      const PatchCode& code = model_.patches[other];
      const Eigen::Vector3d d = q - code.origin;
      const double x = code.frame.col (0).dot (d) / code.radius;
      const double y = code.frame.col (1).dot (d) / code.radius;
      // Cheap bound first: the centrality in `other` is at least |(x, y)| / its largest extent.
      const double r2 = x * x + y * y;
      const double bound = max_extent_[other] * centrality;
      if (r2 > bound * bound)
        continue;
      const double c = footprintCentrality (code.footprint, x, y);
      if (c > 1.0 || c > centrality || (c == centrality && static_cast<std::size_t> (other) > p))
        continue;
      if (code.frame.col (2).dot (n) < options_.min_normal_cosine)
        continue;
      const double z = code.frame.col (2).dot (d) / code.radius;
      if (std::abs (z - model_.evaluate (other, x, y).value) > options_.height_tolerance)
        continue;
      return false;
    }
    return true;
  }
} // namespace pcl_sparse
