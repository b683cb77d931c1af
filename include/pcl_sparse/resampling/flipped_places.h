#pragma once
/// \file flipped_places.h
/// Footprints cut back where a code points the wrong way (ours, issue 13).
///
/// Near creases, corners and thin parts a height field of few atoms can bend past the surface it codes: at
/// places in its footprint (mostly towards the rim) the code's normal then points more than 120 degrees away
/// from the normal of the nearest input face, and resampling emits a flipped normal there (cheese-cgal, a CAD part
/// whose codes the compression bound keeps short; sword at a 74-degree crease; horse where the input folds).
/// The encoder has the mesh: it samples every footprint on rays, finds the places resampling would emit
/// (valid and owned, PatchOwnership) whose normal is off by more than max_normal_angle from the nearest
/// face's, and draws the footprint in to just inside them. Cut places go to the overlapping patches that
/// hold them, or stay empty; ownership then changes around the cut, so the patches there are checked again:
/// those of the cut patch's side, and those facing away across a knife edge, whose places near its surface
/// it no longer clears (PatchOwnership::clearedByFacingAway; sword's last flipped point came from one).

#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/sparse_surface_model.h>

#include <cstddef>

namespace pcl_sparse
{
  /// Options of trimFlippedPlaces.
  struct FlippedPlaceOptions
  {
    /// A place is cut off when its code's normal is more than this many degrees from the surface normal at
    /// its nearest input point (NearestFaceNormal). Below the 120 degrees that count as flipped in
    /// evaluateCloudQuality: a flipped region is wider than the places the rays test, and its rim, a few
    /// degrees short of 120, is where the next resampling's points land. In (90, 180].
    double max_normal_angle = 110.0;
    /// Places tested on each ray, at 1/n, 2/n, ..., n/n of the extent, and at 1 - 1/(2n) and 1 - 1/(4n)
    /// (a flipped sliver along the rim, where the border place is held by another patch: cheese-cgal's
    /// last flipped point in memory); rays on every footprint angle and halfway between (2 K rays). >= 1.
    int radial_steps = 8;
    /// Rounds of testing and cutting at most (the first over every patch, the next over the patches
    /// around a cut, both sides of a knife edge). >= 1.
    int max_rounds = 3;

    /// Checks the ranges. \throws pcl_sparse::Error naming the first field out of range
    void validate () const;
  };

  /// What trimFlippedPlaces did.
  struct FlippedPlaceTrim
  {
    std::size_t places = 0;   ///< places found pointing the wrong way, over all rounds
    std::size_t patches = 0;  ///< patches whose footprint was cut
    int rounds = 0;           ///< rounds run (the last found nothing, or was max_rounds)
  };

  /// \brief Draws in the footprints of \a model where resampling would emit a place whose normal points away
  /// from the surface of \a mesh (see the file comment). The extent of a ray's footprint angle (both angles
  /// around a ray halfway between them) is lowered to the tested place just inside the innermost one found.
  /// Where a place near a tilted face is not emitted (held by another patch, or cleared), the place halfway
  /// to the one inside is tested too: a flipped stretch of the patch's own may end there.
  /// Only a patch with an input face near its places whose normal is over max_normal_angle minus the
  /// steepest slope among those places from the patch's normal can have such places: the others are
  /// evaluated but not searched (most patches of a smooth mesh). 0.03-1.4 s on 2 threads over the 25 shared
  /// meshes (bench/results/flips.md: cheese-cgal 1.35 s, blade 0.28 s, spot 0.07 s), up to 27x the coding
  /// itself, which is fast where patches have few atoms (blade 0.012 s).
  /// \param[in] mesh        the input surface (the model's)
  /// \param[in,out] model   the model; only footprint extents change
  /// \param[in] options     the angle, rays and rounds
  /// \param[in] threads     OpenMP threads (0: OpenMP's default); the result does not depend on it
  /// \return counts of what was cut
  /// \throws pcl_sparse::Error for options out of range, or a mesh TriangleTree refuses (triangles with a
  ///         corner out of range or not finite are left out first)
  FlippedPlaceTrim
  trimFlippedPlaces (const TriangleMesh& mesh, SparseSurfaceModel& model,
                     const FlippedPlaceOptions& options = FlippedPlaceOptions (), int threads = 0);
} // namespace pcl_sparse
