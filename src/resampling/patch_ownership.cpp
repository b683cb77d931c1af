#include <pcl_sparse/resampling/patch_ownership.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/huge_pages.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/geometry/point_kd_tree.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// Appends \a index to the lists of the angular sectors of \a self's plane that \a other's ball (world
    /// radius \a reach around its seed) can reach: the ball projects to a disk in the plane.
    void
    addToSectors (const PatchCode& self, const PatchCode& other, double reach, std::uint32_t index,
                  std::vector<std::uint32_t>* sector_lists)
    {
      const int sectors = PatchOwnership::sectors;
      const Eigen::Vector3d centre = self.frame.transpose () * (other.origin - self.origin) / self.radius;
      const double distance = centre.head<2> ().norm (), disk = reach / self.radius;
      if (distance <= disk * 1.0001)
      {
        for (int s = 0; s < sectors; ++s)
          sector_lists[s].push_back (index);
        return;
      }
      // Angular interval of the disk seen from the seed, as fractions of a turn.
      const double middle = std::atan2 (centre.y (), centre.x ()) * (0.5 / M_PI);
      const double half = std::asin (std::min (1.0, disk / distance)) * (0.5 / M_PI) + 1e-6;
      for (int s = 0; s < sectors; ++s)
      {
        // Sector s spans [s, s + 1) / sectors; compare on the circle.
        const double sector_middle = (s + 0.5) / sectors;
        double gap = std::abs (sector_middle - middle);
        gap -= std::floor (gap);
        gap = std::min (gap, 1.0 - gap);
        if (gap <= half + 0.5 / sectors)
          sector_lists[s].push_back (index);
      }
    }

    /// For each patch, the other patches whose balls (world radius reach around the seeds) meet its own:
    /// d <= reach[p] + reach[q], each pair found by the patch of the larger reach within twice its own
    /// (searching every patch within reach[p] + the largest reach made every search as wide as the largest
    /// patch's: 8x the mean on cheese-cgal). In no particular order.
    std::vector<std::vector<int>>
    overlappingPatches (const SparseSurfaceModel& model, const std::vector<double>& reach, int threads)
    {
      const std::size_t m = model.patches.size ();
      // Float seeds relative to the seeds' centre, searched a float rounding wider: in map coordinates
      // (5.4e6 m, where floats are 0.5 m apart) the world positions lost most pairs, and a spot.obj moved
      // there had other footprints (FOOT 4409 -> 4603 bytes) than at the origin.
      Eigen::AlignedBox3d box;
      for (const PatchCode& patch : model.patches)
        box.extend (patch.origin);
      const Eigen::Vector3d centre = m > 0 ? Eigen::Vector3d (box.center ()) : Eigen::Vector3d (Eigen::Vector3d::Zero ());
      const double rounding = m > 0 ? 8.0 * std::numeric_limits<float>::epsilon () * box.sizes ().maxCoeff () : 0.0;
      pcl::PointCloud<pcl::PointXYZ>::Ptr seeds (new pcl::PointCloud<pcl::PointXYZ>);
      seeds->resize (m);
      for (std::size_t p = 0; p < m; ++p)
        (*seeds)[p].getVector3fMap () = (model.patches[p].origin - centre).cast<float> ();
      const PointKdTree tree (*seeds);
      std::vector<std::vector<std::pair<int, int>>> pairs (static_cast<std::size_t> (threads));
#pragma omp parallel num_threads(threads)
      {
        std::vector<std::pair<int, int>>& found_pairs = pairs[static_cast<std::size_t> (omp_get_thread_num ())];
        std::vector<int> found;
        std::vector<float> distances;
#pragma omp for schedule(dynamic, 16)
        for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
        {
          const std::size_t p = static_cast<std::size_t> (pi);
          tree.radius ((*seeds)[p], static_cast<float> (2.0 * reach[p] * 1.001 + rounding), found, distances, false);
          for (int q : found)
          {
            const std::size_t uq = static_cast<std::size_t> (q);
            if (uq == p || reach[uq] > reach[p] || (reach[uq] == reach[p] && uq < p))
              continue;
            if ((model.patches[p].origin - model.patches[uq].origin).norm () <= reach[p] + reach[uq])
              found_pairs.emplace_back (static_cast<int> (p), q);
          }
        }
      }
      std::vector<std::vector<int>> lists (m);
      for (const auto& thread_pairs : pairs)
        for (const auto& [p, q] : thread_pairs)
        {
          lists[static_cast<std::size_t> (p)].push_back (q);
          lists[static_cast<std::size_t> (q)].push_back (p);
        }
      return lists;
    }

    /// \a lists one after another in \a flat (reserved first: a round of the trimming builds an ownership of
    /// the whole model, and growing the vector was 4 % of cheese-cgal's encode), \a begin[b + 1] the end of
    /// list b (\a begin holds lists.size () + 1 offsets, begin[0] = 0).
    void
    layEndToEnd (const std::vector<std::vector<std::uint32_t>>& lists, std::vector<std::uint32_t>& flat,
                 std::vector<std::size_t>& begin)
    {
      std::size_t total = 0;
      for (const std::vector<std::uint32_t>& list : lists)
        total += list.size ();
      flat.clear ();
      flat.reserve (total);
      for (std::size_t b = 0; b < lists.size (); ++b)
      {
        flat.insert (flat.end (), lists[b].begin (), lists[b].end ());
        begin[b + 1] = flat.size ();
      }
    }
  } // namespace

  void
  PatchOwnershipOptions::validate () const
  {
    auto fail = [] (const std::string& field, double value, const std::string& range) {
      throwOutOfRange ("PatchOwnershipOptions", field, value, range);
    };
    if (!(height_tolerance >= 0.0) || !std::isfinite (height_tolerance))
      fail ("height_tolerance", height_tolerance, "height_tolerance >= 0, finite");
    if (!(min_normal_cosine >= -1.0 && min_normal_cosine <= 1.0))
      fail ("min_normal_cosine", min_normal_cosine, "-1 <= min_normal_cosine <= 1");
    if (!(max_height > 0.0) || !std::isfinite (max_height))
      fail ("max_height", max_height, "max_height > 0, finite");
    if (!(opposite_clearance >= 0.0) || !std::isfinite (opposite_clearance))
      fail ("opposite_clearance", opposite_clearance, "opposite_clearance >= 0, finite");
    if (!(opposite_outside_clearance >= 0.0) || !std::isfinite (opposite_outside_clearance))
      fail ("opposite_outside_clearance", opposite_outside_clearance, "opposite_outside_clearance >= 0, finite");
    if (!(max_slope_angle > 0.0 && max_slope_angle <= 90.0))
      fail ("max_slope_angle", max_slope_angle, "0 < max_slope_angle <= 90 degrees");
  }

  PatchOwnership::PatchOwnership (const PatchEvaluator& evaluator, const PatchOwnershipOptions& options, int threads)
    : evaluator_ (evaluator), options_ (options)
  {
    options.validate ();
    threads = resolveThreadCount (threads);
    const double slope = std::tan (std::min (options.max_slope_angle, 90.0) * M_PI / 180.0);
    max_slope_squared_ = options.max_slope_angle >= 90.0 ? std::numeric_limits<double>::infinity () : slope * slope;
    const SparseSurfaceModel& model = evaluator.model ();
    const std::size_t m = model.numPatches ();
    contender_begin_.assign (m + 1, 0);
    if (m == 0)
      return;

    // World radius of a ball around each seed holding the whole patch: the footprint's largest extent
    // and the largest height seen on a coarse grid over it, with a margin for what the grid misses.
    std::vector<double> reach (m, 0.0), height_bound (m, 0.0);
    std::vector<char> tame (m, 0);
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      const double e = evaluator.maxExtent (p);
      double h_max = 0.0, slope_max = 0.0;
      const int n = 8;
      for (int a = 0; a <= n; ++a)
        for (int b = 0; b <= n; ++b)
        {
          const double x = e * (2.0 * a / n - 1.0), y = e * (2.0 * b / n - 1.0);
          if (evaluator.centrality (p, x, y) <= 1.0)
          {
            const HeightSample h = evaluator.sample (p, x, y, false);
            h_max = std::max (h_max, std::abs (h.value));
            slope_max = std::max (slope_max, h.gradient.squaredNorm ());
          }
        }
      // A code well inside both bounds on the grid is taken as valid everywhere: the validity test of
      // contenders (a full evaluation) is skipped for it.
      tame[p] = h_max <= 0.5 * options.max_height && slope_max <= 0.25 * max_slope_squared_;
      height_bound[p] = model.patches[p].heightBound (*model.basis);
      // Places above max_height are never the patch's (see beats), which also bounds the reach.
      h_max = std::min (h_max * 1.5 + 0.05, options.max_height);
      reach[p] = model.patches[p].radius * std::sqrt (e * e + h_max * h_max) * 1.01;
    }

    const std::vector<std::vector<int>> lists = overlappingPatches (model, reach, threads);
    // Contenders of each patch, and per angular sector of its plane those whose ball can reach the
    // sector (the ball projects to a disk in the plane), nearest seed first so owners are found early.
    // Patches with an opposite normal never beat (see beats), so they are left out here already; those
    // facing away by more than opposite_angle go to the clearance lists (see nearSurface) unless it is 0.
    // Each patch's lists are made in parallel with indices into its own contenders, then laid end to end.
    bin_begin_.assign (m * sectors + 1, 0);
    opposite_begin_.assign (m * sectors + 1, 0);
    std::vector<std::vector<std::uint32_t>> bins (m * sectors), opposite_bins (m * sectors);
    std::vector<std::vector<int>> same_side (m), facing_away (m);
    const double opposite_cosine = std::cos (PatchOwnership::opposite_angle * M_PI / 180.0);
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      const PatchCode& self = model.patches[p];
      std::vector<std::pair<double, int>> sorted;
      for (int q : lists[p])
        sorted.emplace_back ((model.patches[q].origin - self.origin).squaredNorm (), q);
      std::sort (sorted.begin (), sorted.end ());
      for (const auto& entry : sorted)
      {
        const int q = entry.second;
        const double cosine = model.patches[q].frame.col (2).dot (self.frame.col (2));
        if (cosine >= options_.min_normal_cosine)
        {
          addToSectors (self, model.patches[q], reach[q], static_cast<std::uint32_t> (same_side[p].size ()), &bins[p * sectors]);
          same_side[p].push_back (q);
        }
        else if (cosine < opposite_cosine && options_.opposite_clearance > 0.0)
        {
          addToSectors (self, model.patches[q], reach[q], static_cast<std::uint32_t> (facing_away[p].size ()),
                        &opposite_bins[p * sectors]);
          facing_away[p].push_back (q);
        }
      }
    }
    auto contender = [&] (int q) {
      const PatchCode& code = model.patches[q];
      const double inverse = 1.0 / code.radius;
      return Contender{code.origin, code.frame.col (0) * inverse, code.frame.col (1) * inverse,
                       code.frame.col (2) * inverse, evaluator.maxExtent (q), height_bound[q], static_cast<std::size_t> (q),
                       tame[q] != 0};
    };
    opposite_patch_begin_.assign (m + 1, 0);
    for (std::size_t p = 0; p < m; ++p)
    {
      contender_begin_[p + 1] = contender_begin_[p] + same_side[p].size ();
      opposite_patch_begin_[p + 1] = opposite_patch_begin_[p] + facing_away[p].size ();
    }
    // Tens of MB on CAD meshes, rebuilt for every round of trimFlippedPlaces: on huge pages.
    resizeOnHugePages (contenders_, contender_begin_[m]);
    resizeOnHugePages (opposites_, opposite_patch_begin_[m]);
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      for (std::size_t k = 0; k < same_side[p].size (); ++k)
        contenders_[contender_begin_[p] + k] = contender (same_side[p][k]);
      for (std::size_t k = 0; k < facing_away[p].size (); ++k)
        opposites_[opposite_patch_begin_[p] + k] = contender (facing_away[p][k]);
      for (int sector = 0; sector < sectors; ++sector)
      {
        for (std::uint32_t& k : bins[p * sectors + sector])
          k += static_cast<std::uint32_t> (contender_begin_[p]);
        for (std::uint32_t& k : opposite_bins[p * sectors + sector])
          k += static_cast<std::uint32_t> (opposite_patch_begin_[p]);
      }
    }
    layEndToEnd (bins, bin_contenders_, bin_begin_);
    layEndToEnd (opposite_bins, opposite_contenders_, opposite_begin_);
  }

  bool
  PatchOwnership::nearSurface (const Contender& other, const Eigen::Vector3d& q, double radius) const
  {
    const Eigen::Vector3d d = q - other.origin;
    // Cheap bounds first, before the clearances' scale (a square root): the two sides of a thin part are
    // usually farther apart than the heights of a code plus the widest clearance (the scale is at most 1),
    // and the centrality in `other` is at least |(x, y)| / its largest extent (as in heldByAnother; a margin
    // for the rounding of the interpolated extent): most facing-away patches of a sector are nowhere near.
    const double z = other.n.dot (d);
    const double height = std::min (other.height_bound, options_.max_height);
    const double widest = std::max (options_.opposite_clearance, options_.opposite_outside_clearance);
    if (std::abs (z) > height + widest)
      return false;
    const double x = other.t1.dot (d), y = other.t2.dot (d);
    // A quantised file's footprint may be drawn up to footprint_step inside the true one at a knife edge.
    const double step = evaluator_.model ().footprint_step;
    const double reach = other.max_extent * (1.0 + 1e-9) + step;
    if (x * x + y * y > reach * reach)
      return false;
    // The clearances are in the smaller radius of the two: a large Q (one that took a merged patch's
    // triangles) would otherwise clear a band along the edge wider than a small P holds.
    const double scale = std::min (1.0, radius * other.n.norm ());
    const double below = options_.opposite_clearance * scale;
    const double outside = widest * scale;
    if (std::abs (z) > height + outside)
      return false;
    const double c = evaluator_.centrality (other.patch, x, y);
    const double rho = std::sqrt (x * x + y * y);  // within step of the border: rho <= rho / c + step
    return (c <= 1.0 || (step > 0.0 && c * (rho - step) <= rho)) && liesOnSurface (other, x, y, z, below, outside);
  }

  bool
  PatchOwnership::liesOnSurface (const Contender& other, double x, double y, double z, double below, double above) const
  {
    const double h = evaluator_.height (other.patch, x, y);
    if (!(std::abs (h) <= options_.max_height && z - h >= -below && z - h <= above))
      return false;
    return other.tame || isValidPlace (evaluator_.sample (other.patch, x, y, false), options_, max_slope_squared_);
  }

  bool
  PatchOwnership::beats (const Contender& other, std::size_t p, const Eigen::Vector3d& d, double x, double y,
                         double centrality) const
  {
    const double c = evaluator_.centrality (other.patch, x, y);
    if (c > 1.0 || c > centrality || (c == centrality && other.patch > p))
      return false;
    return liesOnSurface (other, x, y, other.n.dot (d), options_.height_tolerance, options_.height_tolerance);
  }

  std::vector<Eigen::Vector3d>
  PatchOwnership::oppositeDisks (std::size_t p) const
  {
    std::vector<Eigen::Vector3d> disks;
    const PatchCode& self = evaluator_.model ().patches[p];
    // p's places lie within its height bound of its plane; each facing-away patch within a ball around its
    // seed holding its footprint and its clearance band. A ball reaching that slab clears at most the disk
    // where it crosses the slab's nearer face.
    const double self_height = std::min (self.heightBound (*evaluator_.model ().basis), options_.max_height);
    const double outside = std::max (options_.opposite_clearance, options_.opposite_outside_clearance);
    for (std::size_t k = opposite_patch_begin_[p]; k < opposite_patch_begin_[p + 1]; ++k)
    {
      const Contender& other = opposites_[k];
      const double height = std::min (other.height_bound, options_.max_height) + outside;
      const double ball = std::sqrt (other.max_extent * other.max_extent + height * height) / (other.n.norm () * self.radius);
      const Eigen::Vector3d d = self.frame.transpose () * (other.origin - self.origin) / self.radius;
      const double gap = std::max (0.0, std::abs (d.z ()) - self_height);
      if (gap < ball)
        disks.emplace_back (d.x (), d.y (), std::sqrt (ball * ball - gap * gap));
    }
    return disks;
  }

  namespace
  {
    /// The patch indices of entries [begin, end) of a contender list.
    template <typename Contenders>
    std::vector<int>
    patchIndices (const Contenders& contenders, std::size_t begin, std::size_t end)
    {
      std::vector<int> list;
      for (std::size_t k = begin; k < end; ++k)
        list.push_back (static_cast<int> (contenders[k].patch));
      return list;
    }
  } // namespace

  std::vector<int>
  PatchOwnership::neighbours (std::size_t p) const
  {
    return patchIndices (contenders_, contender_begin_[p], contender_begin_[p + 1]);
  }

  std::vector<int>
  PatchOwnership::facingAway (std::size_t p) const
  {
    return patchIndices (opposites_, opposite_patch_begin_[p], opposite_patch_begin_[p + 1]);
  }
} // namespace pcl_sparse
