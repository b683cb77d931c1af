#pragma once
/// \file patch_ownership.h
/// Which patch owns a place on the surface, so that overlapping patches do not double the density of a
/// resampled cloud (docs/METHOD.md step 12).
///
/// The rule uses the model alone: a place q sampled from patch P is owned by the patch whose footprint
/// holds q most centrally, centrality c = |(x, y)| / extent(angle) in that patch's local coordinates
/// (c <= 1 inside the footprint), ties to the lower patch index. A patch Q is only a contender for q if
/// q also lies on Q's surface: |z' - h_Q(x', y')| <= height_tolerance (local units of Q) and Q's frame
/// normal N_Q faces the same side as P's (N_Q . N_P >= min_normal_cosine), so the two sides of a thin
/// sheet do not steal each other's places, and only where Q's code is valid (isValidPlace). Patches
/// sample their own surface, so two patches see a seam place at slightly different positions (their
/// coding errors); the seams are consistent up to that error.
///
/// Where a patch P meets a patch Q facing away from it (frame normals more than opposite_angle = 95 degrees
/// apart: a knife edge or a thin part), a place of P that lies in Q's footprint within opposite_clearance
/// under Q's surface or opposite_outside_clearance over it is nobody's: within the coding error of both
/// sides, the other side's surface may be the nearer one, and the point's normal would then be more than
/// 120 degrees off the surface's there (a flipped normal). Both clearances are fractions of the smaller
/// radius of P and Q: a large Q beside a small P would otherwise clear a band along the edge wider than the
/// small patches there hold (holes at the tip of a 10-degree knife). In a quantised file's model Q's footprint
/// counts here up to SparseSurfaceModel::footprint_step past its border as drawn, which may lie that far
/// inside the true one.

#include <pcl_sparse/resampling/patch_evaluator.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Options of PatchOwnership.
  struct PatchOwnershipOptions
  {
    /// Largest distance from a patch's surface, in local units of that patch (fraction of r_P), at which
    /// a place still counts as lying on it. >= 0, finite.
    double height_tolerance = 0.1;
    /// Smallest cosine between a contender's frame normal N_Q and the sampling patch's frame normal N_P.
    /// In [-1, 1] (-1: any orientation).
    double min_normal_cosine = 0.0;
    /// Places where a patch's code leaves the slab |h| <= max_height (local units) are extrapolation of a
    /// badly conditioned code, not surface: no patch samples or claims them there. Patches fit the unit
    /// disk and their normals stay within 90 degrees of N, so true heights stay well inside |h| <= 1.
    /// > 0, finite.
    double max_height = 1.0;
    /// Likewise places where the code's normal leaves the cone of this half-angle (degrees) around N. A
    /// height field seen that obliquely is either extrapolating (tiny patches on thin features oscillate)
    /// or reaching over an edge onto a face that an overlapping patch sees more frontally and codes
    /// better: that patch samples such places. 50 rather than the 75 used before: over the 25 shared
    /// meshes the clouds' mean normal error falls on 22 (3 unchanged) and their distance to the mesh on
    /// 23 (wingnut +0.1 %, fandisk unchanged; cheese-cgal 2.1e-3 -> 1.5e-3 of the diagonal), flipped
    /// normals 249 -> 199, every 99th-percentile hole still within 3 spacings; 45 gains little more and
    /// widens koala's largest hole from 1.5 to 4.9 spacings (bench/results/max_slope.md). In (0, 90];
    /// 90: no bound.
    double max_slope_angle = 50.0;
    /// Clearance (a fraction of min(r_P, r_Q)) a place of P keeps from the surface of a patch Q facing
    /// away (see the file comment); closer places are left unsampled. With default options, 0.03 takes
    /// sword's flipped points from 63 to 0 (its knife edges are 20 degrees), cheese-cgal's from 97 to 55 and
    /// blade's from 20 to 10, and widens sword's 99th-percentile hole from 0.77 to 0.92 spacings; 0.06 takes
    /// few more flips away and widens it to 1.67 (bench/results/flips.md). >= 0, finite (0: no clearance).
    double opposite_clearance = 0.03;
    /// Clearance on Q's outer side (a fraction of min(r_P, r_Q); the larger of this and opposite_clearance applies): a
    /// place of P up to this far outside Q's surface is left unsampled too. Such a place has crossed the
    /// other side of a part thinner than P's coding error, so Q's surface is the nearer one and faces away
    /// from P's normal; a true place of P at a thin part or knife edge lies under Q's surface, never over
    /// it. With default options, 0.1 instead of 0.03 takes the flipped points of the 25 shared meshes at
    /// six resampling seeds from 370 to 242 (horse 41 -> 13, cheese-cgal 258 -> 173, blade 63 -> 50) and
    /// moves no 99th-percentile hole by more than 0.03 spacings (bench/results/flips.md). >= 0, finite;
    /// unused when opposite_clearance is 0.
    double opposite_outside_clearance = 0.1;

    /// Checks the ranges: height_tolerance >= 0, min_normal_cosine in [-1, 1], max_height > 0,
    /// opposite_clearance >= 0, opposite_outside_clearance >= 0 (all finite), max_slope_angle in (0, 90]
    /// degrees.
    /// \throws pcl_sparse::Error naming the first out-of-range field
    void validate () const;
  };

  /// Whether a height sample is a place of its patch's surface (height and slope bounds).
  /// \param[in] h                  height sample with the gradient
  /// \param[in] options            the height bound max_height
  /// \param[in] max_slope_squared  tan(max_slope_angle)^2 (PatchOwnership::maxSlopeSquared)
  /// \return true if |h| <= max_height and |grad h|^2 <= max_slope_squared
  inline bool
  isValidPlace (const HeightSample& h, const PatchOwnershipOptions& options, double max_slope_squared)
  {
    return std::abs (h.value) <= options.max_height && h.gradient.squaredNorm () <= max_slope_squared;
  }

  /// Overlap structure of a model: for each patch, the patches whose extent may reach into it, and the
  /// ownership test. Holds a reference to the evaluator, which must outlive it.
  class PatchOwnership
  {
  public:
    /// Finds, for each patch and angular sector, the patches that may own its places.
    /// \param[in] evaluator  the model's evaluator; kept by reference, it must outlive this object
    /// \param[in] options    surface and validity tolerances
    /// \param[in] threads    OpenMP threads for building the tables (0: OpenMP's default); the tables do not
    ///                       depend on it
    /// \throws pcl_sparse::Error if \a options are out of range (PatchOwnershipOptions::validate)
    PatchOwnership (const PatchEvaluator& evaluator, const PatchOwnershipOptions& options = PatchOwnershipOptions (),
                    int threads = 0);

    /// Angular sectors of a patch's local plane; each keeps only the contenders that can reach it.
    static constexpr int sectors = 16;
    /// Frame normals further apart than this (degrees) face away from each other (opposite_clearance). A
    /// code's normal may turn max_slope_angle from its frame's, so frames 95 degrees apart can already give
    /// points 120 degrees off the other side (wingnut, bunny-hr-closed: 1-2 flipped at 120, none at 95);
    /// right angles, such as a cube's edges, are left alone.
    static constexpr double opposite_angle = 95.0;

    /// Whether a patch owns a place of its surface.
    /// \param[in] p           patch index
    /// \param[in] q           the place: a world point of p's surface
    /// \param[in] centrality  centrality of q in p (PatchEvaluator::centrality), <= 1
    /// \param[in] turn        angle of q in p as a fraction of a turn
    /// \return true unless a contender (see the file comment) holds q more centrally, or as centrally
    ///         with a lower index, or q lies too near the surface of a patch facing away
    bool
    owns (std::size_t p, const Eigen::Vector3d& q, double centrality, double turn) const
    {
      return !clearedByFacingAway (p, q, turn) && !heldByAnother (p, q, centrality, turn);
    }

    /// Whether a place of patch \a p lies in the footprint of a patch facing away from it, within
    /// opposite_clearance under that patch's surface or opposite_outside_clearance over it (a knife edge or
    /// a thin part, see the file comment): the test of owns without the contenders.
    /// \param[in] p     patch index
    /// \param[in] q     world point
    /// \param[in] turn  angle of q in p as a fraction of a turn (its sector)
    bool
    clearedByFacingAway (std::size_t p, const Eigen::Vector3d& q, double turn) const
    {
      const std::size_t bin = p * sectors + std::min<std::size_t> (sectors - 1, static_cast<std::size_t> (turn * sectors));
      for (std::size_t k = opposite_begin_[bin]; k < opposite_begin_[bin + 1]; ++k)
        if (nearSurface (opposites_[opposite_contenders_[k]], q, evaluator_.model ().patches[p].radius))
          return true;
      return false;
    }

    /// Whether a contender of patch \a p (on its surface there, facing p's side) holds a place at most as
    /// centrally as \a centrality (ties to the lower patch index): the test of owns without the facing-away
    /// clearance.
    /// \param[in] p           patch index
    /// \param[in] q           world point
    /// \param[in] centrality  the bound, <= 1 for contenders' footprints
    /// \param[in] turn        angle of q in p as a fraction of a turn (its sector)
    bool
    heldByAnother (std::size_t p, const Eigen::Vector3d& q, double centrality, double turn) const
    {
      const std::size_t bin = p * sectors + std::min<std::size_t> (sectors - 1, static_cast<std::size_t> (turn * sectors));
      for (std::size_t k = bin_begin_[bin]; k < bin_begin_[bin + 1]; ++k)
      {
        const Contender& other = contenders_[bin_contenders_[k]];
        const Eigen::Vector3d d = q - other.origin;
        const double x = other.t1.dot (d), y = other.t2.dot (d);
        // Cheap bound first: the centrality in `other` is at least |(x, y)| / its largest extent.
        const double bound = other.max_extent * centrality;
        if (x * x + y * y > bound * bound)
          continue;
        if (beats (other, p, d, x, y, centrality))
          return true;
      }
      return false;
    }

    /// The options given to the constructor.
    const PatchOwnershipOptions& options () const { return options_; }
    /// tan(max_slope_angle)^2.
    double maxSlopeSquared () const { return max_slope_squared_; }

    /// Patches that may overlap a patch.
    /// \param[in] p  patch index
    /// \return patch indices (never \a p), nearest seed first
    std::vector<int> neighbours (std::size_t p) const;

    /// Patches facing away from a patch whose footprints may clear its places (clearedByFacingAway).
    /// \param[in] p  patch index
    /// \return patch indices (never \a p), nearest seed first
    std::vector<int> facingAway (std::size_t p) const;

    /// Where the patches facing away from patch \a p may clear its places: per such patch that can reach
    /// them, a disk (x, y, radius) in p's local units that holds every place of p it may clear.
    std::vector<Eigen::Vector3d> oppositeDisks (std::size_t p) const;

  private:
    /// A patch that may own places of another: its frame rows pre-divided by its radius.
    struct Contender
    {
      Eigen::Vector3d origin, t1, t2, n;  ///< s; T1 / r, T2 / r, N / r
      double max_extent;
      double height_bound;  ///< bound on |h| over its footprint (PatchCode::heightBound, local units)
      std::size_t patch;
      bool tame;  ///< its code stays well inside the validity bounds: no need to test them
    };

    bool
    beats (const Contender& other, std::size_t p, const Eigen::Vector3d& d, double x, double y, double centrality) const;
    /// Whether the place \a q of a patch of radius \a radius lies in a facing-away patch's footprint within
    /// opposite_clearance under its surface or opposite_outside_clearance over it, where its code is valid.
    bool
    nearSurface (const Contender& other, const Eigen::Vector3d& q, double radius) const;
    /// Whether the place at local (x, y, z) of \a other (z in its local units) lies at most \a below under
    /// and \a above over its surface, where its code is a valid place (|h| <= max_height, slope bound).
    bool
    liesOnSurface (const Contender& other, double x, double y, double z, double below, double above) const;

    const PatchEvaluator& evaluator_;
    PatchOwnershipOptions options_;
    double max_slope_squared_ = 0.0;
    std::vector<Contender> contenders_;
    std::vector<std::size_t> contender_begin_;  ///< #patches + 1 offsets into contenders_
    std::vector<std::uint32_t> bin_contenders_;  ///< per (patch, sector): indices into contenders_, nearest seed first
    std::vector<std::size_t> bin_begin_;         ///< #patches * sectors + 1 offsets into bin_contenders_
    /// Likewise the patches facing away (more than opposite_angle) whose surface a patch's places keep clear of:
    /// per (patch, sector) indices into opposites_, nearest seed first, and the offsets into that list.
    std::vector<Contender> opposites_;
    std::vector<std::size_t> opposite_patch_begin_;  ///< #patches + 1 offsets into opposites_
    std::vector<std::uint32_t> opposite_contenders_;
    std::vector<std::size_t> opposite_begin_;
  };
} // namespace pcl_sparse
