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

#include <pcl_sparse/model/sparse_surface_model.h>

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

  /// Centrality of local (x, y) in \a footprint: |(x, y)| / extent(angle); <= 1 inside, > 1 outside.
  /// An empty footprint (no extents) stands for the unit disk.
  double
  footprintCentrality (const PatchFootprint& footprint, double x, double y);

  /// Largest extent of \a footprint (1 for an empty footprint).
  double
  footprintMaxExtent (const PatchFootprint& footprint);

  /// Overlap structure of a model: for each patch, the patches whose extent may reach into it, and the
  /// ownership test. Holds a reference to the model, which must outlive it.
  class PatchOwnership
  {
  public:
    PatchOwnership (const SparseSurfaceModel& model, const PatchOwnershipOptions& options = PatchOwnershipOptions ());

    /// Whether patch \a p owns the place \a q (a point of p's surface) with unit normal \a n, where
    /// \a centrality is footprintCentrality of q in p (must be <= 1).
    bool
    owns (std::size_t p, const Eigen::Vector3d& q, const Eigen::Vector3d& n, double centrality) const;

    /// Patches that may overlap patch \a p (never p itself), in increasing index order.
    const std::vector<int>& neighbours (std::size_t p) const { return neighbours_[p]; }
    /// Largest footprint extent of patch \a p, local units.
    double maxExtent (std::size_t p) const { return max_extent_[p]; }

  private:
    const SparseSurfaceModel& model_;
    PatchOwnershipOptions options_;
    std::vector<std::vector<int>> neighbours_;
    std::vector<double> max_extent_;
  };
} // namespace pcl_sparse
