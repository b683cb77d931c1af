#pragma once
/// \file footprint_slack.h
/// How far a model file may draw each footprint extent off without changing where resampling draws the surface.
///
/// Inside the surface most of a footprint's border runs through the footprints of same-side neighbours that
/// hold the places there more centrally, so resampling gives those places to the neighbours (PatchOwnership):
/// moving the border a little in or out at most hands places between patches that agree there. A quantised
/// file then need not spend refinement angles drawing such a border exactly (format/footprint_coding.h); at
/// open borders, creases and thin parts, where no neighbour holds the places, the border stays as exact as
/// the file's steps allow.

#include <pcl_sparse/model/sparse_surface_model.h>

#include <vector>

namespace pcl_sparse
{
  /// Where a writer may draw each extent of a footprint instead of the true one, per angle: anywhere in
  /// [lower, upper] (both the extent where it must stay), because resampling draws the same places there
  /// either way (format/footprint_coding.h takes it).
  struct FootprintSlack
  {
    std::vector<float> lower, upper;  ///< one per angle, lower <= extent <= upper
    /// One per angle: 1 where the border lies on a knife edge or a thin part (its place, or the one a tenth
    /// further in, lies on the surface of a patch facing away, PatchOwnership::clearedByFacingAway; and the
    /// angles beside such an angle): that patch's places beside the edge are left unsampled only inside
    /// this footprint, so a file draws the border there at most one level in, and its reader clears one
    /// level past it (SparseSurfaceModel::footprint_step). Empty: no such angle.
    std::vector<char> knife_edge;
  };

  /// Options of footprintSlack. The defaults, against exact extents (footprint_slack false), over the 25
  /// shared meshes: default files 1.2-11.2 % smaller, as near the mesh or nearer on 22 (Chamfer distance;
  /// bench/results/footprint_slack.md, with the variants tried).
  struct FootprintSlackOptions
  {
    /// A border place counts as held by a neighbour when the neighbour holds it at most this centrally
    /// (1: on its border), on its surface and facing the same side (PatchOwnership::heldByAnother). In (0, 1].
    double max_centrality = 0.9;
    /// The extent may be drawn down to (1 - inward) times itself where the places from there out are held
    /// at most max_centrality (1 - inward) centrally: the neighbour's own border may be drawn that much
    /// further in as well, and they stay inside it (held only at max_centrality, two borders drawn in
    /// towards each other left places of a torus in neither). In [0, 1).
    double inward = 0.3;
    /// The extent may be drawn up to (1 + outward) times itself where the places out there are the
    /// patch's valid surface and held at most max_centrality centrally; not at a trim cut
    /// (PatchFootprint::trimmed). >= 0, finite.
    double outward = 0.3;
    /// Checks the ranges. \throws pcl_sparse::Error naming the first field out of range
    void validate () const;
  };

  /// \brief The slack of every footprint of a model: per angle, the places of the patch's surface at the
  /// extent and at a third, two thirds and all of the way to (1 - inward) and (1 + outward) times it are
  /// tested; the slack reaches as far as every place tested up to there is held (FootprintSlackOptions).
  /// About 60-80 ms for the 1400-1900 patches of spot or horse on 2 threads (bench/results/footprint_slack.md).
  /// \param[in] model    the model (lossless footprints)
  /// \param[in] options  how central a hold must be and how far the slack may reach
  /// \param[in] threads  OpenMP threads (0: OpenMP's default); the result does not depend on it
  /// \return one slack per patch, with as many angles as its footprint
  /// \throws pcl_sparse::Error for options out of range
  std::vector<FootprintSlack>
  footprintSlack (const SparseSurfaceModel& model, const FootprintSlackOptions& options = FootprintSlackOptions (),
                  int threads = 0);

  /// \brief The slack of the patches [first, first + count) of a model, equal to those of footprintSlack over
  /// the whole model, found among the patches that can reach them only (a tiled file's runs: a tile's memory,
  /// not the whole model's).
  /// \param[in] model    the model (lossless footprints)
  /// \param[in] first    the first patch
  /// \param[in] count    how many
  /// \param[in] options  as footprintSlack
  /// \param[in] threads  as footprintSlack
  /// \return one slack per patch of the run
  /// \throws pcl_sparse::Error for options out of range or patches outside the model
  std::vector<FootprintSlack>
  footprintSlack (const SparseSurfaceModel& model, std::size_t first, std::size_t count,
                  const FootprintSlackOptions& options = FootprintSlackOptions (), int threads = 0);
} // namespace pcl_sparse
