#pragma once
/// \file patch_options.h
/// Parameters of patch growth and feature-aware seed sampling (docs/METHOD.md steps 4 and 5).
/// Defaults are the paper's numbers except where another measured better (the cone angle: the authors'
/// 72 degrees; our pairwise cone and face completion); each field says where the authors' code (gproshan,
/// src/mdict) differs. EncoderPreset::Paper sets the paper's configuration.

#include <cmath>
#include <string>

namespace pcl_sparse
{
  /// Conditions of patch growth and seed sampling (defaults: see the file's comment).
  struct PatchOptions
  {
    /// Smooth variation: a triangle t may join only if angle(n_t, n_w) < delta for an accepted corner w
    /// (vertex normal). Paper and authors' code: pi / 6.
    double delta = M_PI / 6.0;
    /// Smooth variation on a spinning lidar's rings (ours; CloudNeighborhood::LidarRings): replaces delta
    /// there (patchOptionsFor). Their normals are taken over windows that reach along the rings
    /// (gridNeighborhoods), smooth enough that growth at delta crossed the corner between a road and a wall
    /// through the triangles joining their rings, in steps under 30 degrees, and the code rounded the corner;
    /// at 10 degrees patches stop there (bench/results/scans-notes.md). 0: delta. Radians, 0 .. pi.
    double lidar_delta = M_PI / 18.0;
    /// Normal cone: angle(n_t, n_s) < theta against the seed's vertex normal. Paper: pi / 2 (EncoderPreset::Paper);
    /// the authors' code and our default: pi / 2.5 (72 degrees). At equal CR, 72 degrees gives a lower RMSE
    /// on 17 of the 21 shared meshes where the two can be compared, 5x lower on anchor-dense and 8x at rho
    /// 0.001 on couplingdown, where patches at 90 degrees take in faces almost perpendicular to the seed's
    /// plane; up to 9 % higher on armadillo-43k and fandisk (bench/results/cone_angle.md). Whatever the
    /// value, a triangle whose projection on the seed's tangent plane would flip is refused too, so the
    /// patch stays a height field.
    double cone_angle = M_PI / 2.5;
    /// Also require angle(n_t, n_m) < cone_angle between any two patch triangles (ours). With the cone
    /// around n_s alone two triangles may differ by up to twice the cone angle: 180 degrees for the
    /// paper's pi / 2. Neither the paper nor the authors' code checks it. With it, growth and face
    /// completion also refuse a vertex that would put all three corners of a face facing away from n_s in
    /// the patch (its vertices would fold over the seed's plane). Default true; false in
    /// EncoderPreset::Paper.
    bool pairwise_cone = true;
    /// Flatness bound eta on A_p / A_p^proj (patch area over its area projected on the seed's tangent
    /// plane; always >= 1: the paper prints the ratio upside down). Paper and code: 1.01.
    double eta = 1.01;
    /// Size bound rho on A_p / A (patch area over the mesh's total area): below it a patch grows whatever
    /// its flatness. Per model in the paper: 0.005, 0.001 (default), 0.0002.
    double rho = 0.001;
    /// Overlap control: seeds closer than sigma * r_P (Euclidean) to a kept patch's seed are not used.
    /// Paper and code: 0.8. r_P here is the growth radius (tangent plane of the seed's vertex normal).
    double sigma = 0.8;
    /// A sampled patch is kept only with at least this many vertices. Paper and code: 7.
    int min_patch_size = 7;
    /// true: growth stops at the first vertex (in geodesic order) that fails the conditions, as in the
    /// authors' code; it keeps patches disk-like (star-shaped around the seed) and their cost bounded.
    /// false: a refused vertex is only skipped (not expanded) and growth goes on around it; the paper's
    /// text does not say which. Default true: the footprint, frame and coding stages assume disk-like
    /// patches.
    bool stop_at_first_refusal = true;
    /// Coverage pass (ours; the authors have none and leave 58 % of CAD-like meshes, 11.5 % of turbine.off
    /// uncovered): after the sampling loop every still-uncovered vertex seeds a patch of any size >= 1.
    bool cover_all_vertices = true;
    /// Face completion (ours; face_completion.h): growth makes a face a patch triangle only when its three
    /// corners joined one patch, so faces whose corners joined different patches lie outside every
    /// footprint and resampling leaves holes there (85 % of couplingdown's area, 42 % of blade's). true
    /// (default): after the coverage pass each such face joins a patch holding one of its corners, within
    /// cone_angle of that patch's seed normal, without flipping or overlapping its triangles on the seed's
    /// plane; no patch is added. false: the paper's patches (EncoderPreset::Paper).
    bool complete_faces = true;
    /// Patches seeded on faces (ours, with complete_faces; face_completion.h): a face completion can put in
    /// no patch (outside the normal cone of every patch holding a corner: strips between creases, coarse
    /// CAD faces, a cube's side between two patches) grows a patch of its own over faces
    /// (PatchGrower::growFromFace), kept unless it is a long thin strip, so that every other proper face
    /// lies in some patch (couplingdown 24.5 % of the area in no patch -> 0, cheese-cgal 27 % -> 0.04 %).
    /// true (default); false: such faces stay in no patch and the patches at their corners cover them with
    /// unclipped footprints (EncoderPreset::Paper has no completion at all).
    bool seed_patches_on_faces = true;
    /// Hidden triangles released (ours, with seed_patches_on_faces; hidden_triangles.h): on the final
    /// partition, a patch's triangles that its seed sees only across more than this x R of its tangent plane
    /// without surface on its side (R: the patch's reach) leave it and grow patches of their own from a face,
    /// so its star-shaped footprint does not span the bay between (blade's patch 298: 5 flipped normals). A
    /// released face no new patch takes goes back to its patch. -1 (default, by surface; patchOptionsFor):
    /// 0.3 on a mesh, 0 on a scan, whose footprints are clipped at holes instead (on the shared scans the
    /// release added 0.5-4 % patches and bytes and moved the flipped normals both ways: office1 +106,
    /// small_gicp -59; bench/results/flips.md); 0: none released.
    double hidden_triangle_gap = -1.0;
    /// Redundant patches (ours; redundant_patches.h): after face completion, drop the patches whose every
    /// vertex and triangle other patches also hold (up to 27 % of the patches of the shared meshes), each of which
    /// costs the model a seed, frame, radius and footprint. true (default); false: the paper's patches
    /// (EncoderPreset::Paper, authorsCodePatchOptions).
    bool drop_redundant_patches = true;
    /// Patch merging (ours; patch_merging.h): after redundant patches are dropped, a patch holding at most
    /// this many vertices plus triangles no other patch holds hands its triangles to its neighbours (under
    /// face completion's rules) and is dropped, when they all find one. 8 (default): the default files of
    /// the 25 shared meshes are 0.63-1.08x as large, their Chamfer distance 0.90-1.29x, 13 instead of 9 reach
    /// Draco's bytes at equal Chamfer, and the RMSE at the authors' CR falls on 13 of 15; the changed
    /// partition moves ties at thin parts, single flipped points on horse (3), koala and nefertiti-35k
    /// (bench/results/patch_merging.md). 0 (the paper's patches, authorsCodePatchOptions): none.
    int merge_own_elements = 8;
    /// Unreferenced vertices (in no face): 1 (true): each gets a one-vertex patch, a small disc along its
    /// normal, so that every finite vertex has an estimate (NaN ones are left out either way); 0 (false):
    /// they are left out and reported by FeatureAwarePatchSampling::getUncoveredVertices. -1 (default): 1
    /// on a scan, whose points the neighbourhood triangulation left out (at depth edges, thin parts) are
    /// still samples of the surface, and 0 on a mesh, whose faces are its surface: stanford-bunny.obj's 1113
    /// unreferenced vertices took 1113 of its 2476 patches and 11 % of its default file for 0.4 % of its
    /// Chamfer distance.
    int cover_unreferenced_vertices = -1;
    /// With cover_unreferenced_vertices, an unreferenced vertex gets its patch only if it lies farther than
    /// this many mean edge lengths of the nearest vertex of a face from that vertex (3, default): next to
    /// the triangulated surface (a depth edge's points, a lidar ring's whose edges were refused) the surface's
    /// patches resample its neighbourhood already: such discs, up to 59 % of a scan's patches, took up to 15 %
    /// of its default file for at most 0.1 % completeness of clouds resampled to 1x or 4x its points
    /// (room_scan1.pcd: 9000 -> 3677 patches; bench/results/unreferenced_points.md). Such a vertex is left
    /// uncovered. Points farther (thin parts, stray returns) keep theirs. 0: every one gets its patch.
    double unreferenced_patch_spacings = 3.0;
    /// Harris 3D neighbourhoods of the default candidate order: 0 (default) = the paper's adaptive rings
    /// (radius 1 % of the bbox diagonal) on a mesh and 2 rings (the paper's fixed option) on a scan, where
    /// 1 % of the diagonal holds hundreds of points and took most of the encoding time; k > 0 = k rings;
    /// < 0 = adaptive on scans too.
    int harris_rings = 0;
    /// The sampling loop ends after this many grown seeds in a row covered no new vertex (the coverage
    /// pass covers the rest): on a flat scan one patch can span the whole cloud, and vertices no patch can
    /// take (folded triangles) would otherwise keep every later candidate growing that whole patch again,
    /// O(N^2). 0 = never (the paper's loop, and the default on meshes); -1 (default) = 0 on a mesh and
    /// 256 on a scan.
    int max_fruitless_seeds = -1;
    /// Pruned tail of the sampling loop (ours): once this fraction of the vertices to cover is covered, a
    /// candidate already covered and more than R edges from every vertex still uncovered grows no patch and
    /// counts as a fruitless seed, as its patch would most likely cover nothing new (R = ceil(sqrt(mean
    /// vertex count of the patches kept so far)), about twice the edge radius of a disc-shaped patch). The
    /// paper's loop grows them all: on a 640x480 RGB-D frame the last 1.3 % of the points took half of its
    /// 6922 growths. 1 = never (the paper's loop, and the default on meshes, where it saved under 10 %);
    /// -1 (default) = 1 on a mesh and 0.9 on a scan.
    double tail_pruning_after = -1.0;
    /// Growth stops once a patch has this many vertices. 0 = no bound (the paper's, and the default on
    /// meshes, where eta bounds curved patches and flat ones are cheap); -1 (default) = 0 on a mesh and
    /// 4096 on a scan, where a flat wall or floor would otherwise make each grown seed cost O(N).
    int max_patch_vertices = -1;
    /// Growth floor (ours): while a patch has fewer than this many vertices the area bound (rho, eta) is
    /// waived; smooth variation, the cone and no flip still hold, so patches still stop at sharp features.
    /// On a mesh whose triangles are large against rho A a patch otherwise stops after a few vertices
    /// and its 13 frame values cost more than the vertices it holds. 0 (default, the paper's) = no floor;
    /// the encoder raises it only where its model would exceed SparseSurfaceEncoderOptions::
    /// max_compression_ratio.
    int min_growth_vertices = 0;
    /// Frame fallback (ours, docs/METHOD.md section 6): a jet whose normal makes the patch's steepest
    /// triangle steeper than this and steeper than the seed's plane does is refused as the frame (the seed's
    /// plane is used). Radians; 0 = only a jet that flips a triangle is refused (as before); -1 (default) =
    /// 72 degrees on a mesh (on a strip of thin triangles a nearly singular jet lay in the strip's plane)
    /// and 0 on a scan, whose noisy triangles are steep for any normal (with it, sensor-facing flipped
    /// normals over the shared scans rose from 45603 to 53481; bench/results/frames.md).
    double steep_frame_angle = -1.0;
    /// Frames of patches grown from faces (ours; Patch::seed_face >= 0: the coverage pass and
    /// seed_patches_on_faces): the jet is refused, as by steep_frame_angle, once the patch's steepest
    /// triangle is steeper than this (radians), where steep_frame_angle is larger. Such a patch holds
    /// faces no other patch could, so the places resampling leaves to overlapping patches for being
    /// steeper than PatchOwnershipOptions::max_slope_angle (50 degrees) were holes there: at 50 (default)
    /// couplingdown's p99 hole at 100000 points falls from 3.17 to 2.03 spacings and cheese-cgal's flipped
    /// points from 12 to 5 (bench/results/face_seeded_patches.md). 0: as steep_frame_angle
    /// (EncoderPreset::Paper, authorsCodePatchOptions). Only where steep_frame_angle resolves above 0
    /// (meshes): on scans no frame is refused for steepness.
    double face_steep_frame_angle = 50.0 * M_PI / 180.0;

    /// Checks the ranges: angles in (0, pi] (lidar_delta [0, pi]), eta >= 1, rho >= 0, sigma >= 0, min_patch_size >= 1,
    /// min_growth_vertices >= 0, face_steep_frame_angle in [0, pi / 2], hidden_triangle_gap -1 or >= 0.
    /// \throws pcl_sparse::Error naming the first out-of-range field
    void validate () const;
  };

  /// The paper's patch steps (EncoderPreset::Paper): the 90-degree cone and none of ours (pairwise cone, face
  /// completion, patches seeded on faces, hidden triangles released, steep face frames refused, redundant
  /// patches dropped, small ones merged, lidar_delta); every other field as \a base.
  /// \param[in] base the other conditions (rho, delta, eta, coverage pass, ...)
  PatchOptions
  paperPatchOptions (PatchOptions base = PatchOptions ());

  /// The patch conditions of the authors' code (gproshan) as far as they are options: the 72-degree cone,
  /// no pairwise cone, no coverage pass (vertices no patch takes stay uncovered, unreferenced ones too), no
  /// face completion and delta on lidar rings too; every other field as \a base. Its area accounting (one triangle per accepted
  /// vertex, docs/METHOD.md step 5) is not reproduced.
  /// \param[in] base the other conditions (rho, delta, eta, ...)
  PatchOptions
  authorsCodePatchOptions (PatchOptions base = PatchOptions ());
} // namespace pcl_sparse
