#pragma once
/// \file patch_ownership.h
/// Which patch owns a place on the surface, so that overlapping patches do not double the density of a
/// resampled cloud (METHOD.md step 12).
///
/// The rule uses the model alone: a place q sampled from patch P is owned by the patch whose footprint
/// holds q most centrally, centrality c = |(x, y)| / extent(angle) in that patch's local coordinates
/// (c <= 1 inside the footprint), ties to the lower patch index. A patch Q is only a contender for q if
/// q also lies on Q's surface: |z' - h_Q(x', y')| <= height_tolerance (local units of Q) and Q's normal
/// N_Q faces the same side as the normal at q, so the two sides of a thin sheet do not steal each
/// other's places. Patches sample their own surface, so two patches see a seam place at slightly
/// different positions (their coding errors); the seams are consistent up to that error.

#include <pcl_sparse/resampling/patch_evaluator.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// Options of PatchOwnership.
  struct PatchOwnershipOptions
  {
    /// Largest distance from a patch's surface, in local units of that patch (fraction of r_P), at which
    /// a place still counts as lying on it.
    double height_tolerance = 0.1;
    /// Smallest cosine between a contender's frame normal N_Q and the normal at the place.
    double min_normal_cosine = 0.0;
  };

  /// Overlap structure of a model: for each patch, the patches whose extent may reach into it, and the
  /// ownership test. Holds a reference to the evaluator, which must outlive it.
  class PatchOwnership
  {
  public:
    PatchOwnership (const PatchEvaluator& evaluator, const PatchOwnershipOptions& options = PatchOwnershipOptions ());

    /// Whether patch \a p owns the place \a q (a point of p's surface) with unit normal \a n, where
    /// \a centrality is the centrality of q in p (must be <= 1).
    bool
    owns (std::size_t p, const Eigen::Vector3d& q, const Eigen::Vector3d& n, double centrality) const
    {
      for (std::size_t k = contender_begin_[p]; k < contender_begin_[p + 1]; ++k)
      {
        const Contender& other = contenders_[k];
        const Eigen::Vector3d d = q - other.origin;
        const double x = other.t1.dot (d), y = other.t2.dot (d);
        // Cheap bound first: the centrality in `other` is at least |(x, y)| / its largest extent.
        const double bound = other.max_extent * centrality;
        if (x * x + y * y > bound * bound)
          continue;
        if (beats (other, p, d, x, y, n, centrality))
          return false;
      }
      return true;
    }

    /// Patches that may overlap patch \a p (never p itself), in increasing index order.
    std::vector<int> neighbours (std::size_t p) const;

  private:
    /// A patch that may own places of another: its frame rows pre-divided by its radius.
    struct Contender
    {
      Eigen::Vector3d origin, t1, t2, n;  ///< s; T1 / r, T2 / r, N / r
      Eigen::Vector3d normal;             ///< N
      double max_extent;
      std::size_t patch;
    };

    bool
    beats (const Contender& other, std::size_t p, const Eigen::Vector3d& d, double x, double y, const Eigen::Vector3d& n,
           double centrality) const;

    const PatchEvaluator& evaluator_;
    PatchOwnershipOptions options_;
    std::vector<Contender> contenders_;
    std::vector<std::size_t> contender_begin_;  ///< #patches + 1 offsets into contenders_
  };
} // namespace pcl_sparse
