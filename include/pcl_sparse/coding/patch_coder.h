#pragma once
/// \file patch_coder.h
/// Codes one patch as a sparse height field (docs/METHOD.md steps 7-9): samples, Nyquist cap, OMP, footprint.

#include <pcl_sparse/coding/nyquist_cap.h>
#include <pcl_sparse/coding/patch_attribute_coder.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/model/surface_basis.h>
#include <pcl_sparse/patches/patch.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Options of the sparse coding stage. Defaults are the paper's.
  struct SparseCodingOptions
  {
    double nyquist_factor = 0.5;                  ///< f in [0, 1]; 0 = plain OMP (paper's experiments: 0.5)
    NyquistRule nyquist_rule = NyquistRule::Paper;  ///< paper: lambda / 2 > f mu; authors' code: lambda >= f mu
    int max_atoms = 12;                           ///< L, atoms per patch at most
    double tolerance = 0.01;                      ///< eps: stop at ||r|| <= eps ||y||
    /// With a basis that has monomial atoms (QuadricDctDictionary, the encoder's default): an OMP step takes
    /// the best of the quadric's atoms (the constant and x, y, x^2, x y, y^2) instead of the best atom when it
    /// scores (squared normalised correlation) at least this fraction of the best atom's, so the quadric codes
    /// a patch's bulk and the cosines its detail. 0: the quadric's atoms first while they correlate; 1: no
    /// preference. 0.3 measured best (bench/results/quadric_basis.md): at 0 the file is 5-7 % smaller but the
    /// vertex RMSE up to 15 % higher than the cosines alone on armadillo-43k; at 0.3 the RMSE is lower than
    /// the cosines' on every mesh measured, the bytes within 3 %. In [0, 1].
    double quadric_preference = 0.3;
    int min_samples = 64;                         ///< m_min: fewer points get extra samples (authors' code: 128)
    /// Extra samples per patch triangle (ours): each patch draws at least ceil(triangle_samples * #triangles)
    /// extra samples on its triangles (by area), however many vertices it has. With vertices alone, a
    /// patch of many vertices and long thin faces fits its vertices and oscillates between them: blade
    /// resampled with 1082 flipped normals of 32924 and 17.7 degrees mean normal error, 10 and 2.0 with
    /// 0.5 (kitten-53k's cloud 10 % closer to the mesh, its vertex RMSE 8 % higher: the samples lie on
    /// the flat triangles). 0 = the paper's (EncoderPreset::Paper); default 0.5. Meshes only: a scan's
    /// triangles join noisy points, and samples on them doubled the resampled points' distance to the
    /// truth on simulated scans (bench/results/scans.md), so SparseSurfaceEncoder uses 0 for scans. At most 16.
    double triangle_samples = 0.5;
    int footprint_angles = 64;                    ///< K in [3, 4096], angles of the stored footprint (16 overshoots
                                                  ///< open borders and sharp edges: bench/results/resample_quality.md)
    std::uint64_t seed = 42;                      ///< global seed of the extra samples (per patch: mixSeed)
    /// Basis support over patch radius: local coordinates are p' = R^T (p - s) / (support_scale r_P), so the
    /// patch fills the disk of radius 1 / support_scale inside the basis square [-1, 1]^2 and the stored
    /// radius is support_scale r_P. Paper and authors' code: 1 (the patch touches the square's sides, where
    /// every cosine atom has zero slope, which costs accuracy on curved patches); > 1 is our option.
    double support_scale = 1.0;
    /// Round the stored radius support_scale r_P up to the grid 2^(k / 32) (radiusOnGrid; local coordinates
    /// divided by at most 2^(1/32) more), so that a quantised file codes it exactly in a few bits
    /// (coding/radius_grid.h). Ours; false in EncoderPreset::Paper (the paper's r_P).
    bool radius_on_grid = true;
    /// Noise level of the input, in world units (standard deviation; 0 = none, the meshes' case). OMP also
    /// stops once the residual's RMS over the patch's samples is at most this (in the patch's local units),
    /// so that the code smooths sensor noise instead of coding it (ours, for scans).
    double noise_level = 0.0;
    /// With noise_level > 0 (scans): each patch stops at the larger of noise_level and its own noise, the
    /// robust residual of a height quadric over its points (quadricNoiseLevel), so that parts noisier than
    /// the scan's median and the depth steps of a quantising sensor are smoothed as well (ours).
    bool local_noise = true;
    /// Clip footprints where a ray from the seed first leaves the patch's triangles
    /// (computePatchFootprint), so a patch that grew around a hole does not cover it. The encoder turns it
    /// on for scans, whose neighbourhood surfaces have holes (shadows, missing depth); default false.
    bool clip_footprints_at_holes = false;
    /// Clip footprints at the outermost crossing of each ray with the border of the patch's triangles
    /// (computePatchFootprint's clip_at_border; ours): the footprint no longer overshoots open borders and
    /// sharp edges, where the overshoot gave flipped normals past thin parts. Patches beside a face that
    /// no patch holds (Patch::beside_uncovered_face) keep the overshoot, which covers that face. Default
    /// true; false in EncoderPreset::Paper.
    bool clip_footprints_at_border = true;
    /// With clip_footprints_at_border: where the surface goes on smoothly past a patch's border, its
    /// footprint reaches this many degrees (either way) along the border to the outer corners of its
    /// triangles, by at most half an edge (computePatchFootprint's reach; ours). 17 (3 of the 64 angles), on
    /// the 25 shared meshes: the lossless model's Chamfer distance 0.9-6.1 % smaller on 24 (blade +1.2 %), the
    /// default file 1.6-6.5 % smaller on 23 and nearer the mesh on 24 (bench/results/footprint_reach.md).
    /// 0: clipped at every border. Needs codePatch's topology; the encoder passes it. Scans: 0 (not measured).
    double footprint_reach_degrees = 17.0;
    /// The reach goes over a border edge only where the face beyond it is tilted at most this far from the
    /// patch's normal (so not at open borders, sharp edges, or where a thin part's rounded edge curls away:
    /// at 30 blade's Chamfer distance grew 8 %). Default 20.
    double footprint_reach_max_tilt_degrees = 20.0;
  };

  /// Diagnostics of one coded patch (not stored in the model).
  struct PatchCodingInfo
  {
    int num_samples = 0;          ///< points coded: vertices plus extra samples
    double spacing = 0.0;         ///< mu, local units
    int allowed_atoms = 0;        ///< atoms passing the Nyquist cap
    double relative_residual = 0.0;  ///< ||r|| / ||y|| (0 for a zero signal)
    /// ||r|| over the samples after each prefix of the code (0, 1, ..., all its atoms), in the patch's
    /// local units (OmpResult::residual_norms): what each atom buys (atom_budget.h).
    std::vector<double> residual_norms;
    /// The code's coefficients after each prefix of its atoms (OmpResult::prefix_coefficients): what
    /// truncatePatchCode cuts a code to. The encoder's coding info (SurfaceEncoding) leaves them out.
    std::vector<double> prefix_coefficients;
  };

  /// Codes one patch as a sparse height field (docs/METHOD.md steps 7 to 9). The signal is the local
  /// height z' at the patch's vertices plus, if there are fewer than options.min_samples of them, that
  /// many minus the vertex count of extra points on its triangles (seeded by mixSeed (options.seed,
  /// \a patch_index)).
  /// \param[in]  patch                   frame, radius and local coordinates set (computePatchFrame)
  /// \param[in]  patch_index             the patch's index in the model (seeds its extra samples)
  /// \param[in]  mesh                    the mesh
  /// \param[in]  mean_ring_edge_lengths  #V (meanRingEdgeLengths): gives the sample spacing mu of the cap
  /// \param[in]  basis                   the dictionary
  /// \param[in]  options                 cap, OMP, samples, footprint and support options
  /// \param[out] info                    diagnostics of the coding (optional)
  /// \param[in]  attributes              colour / intensity to code at the same samples (optional;
  ///                                     codePatchAttributes); the height's code is the same without them
  /// \param[in]  topology                the mesh's (optional: without it the footprint reaches past no
  ///                                     border, SparseCodingOptions::footprint_reach_degrees)
  /// \return origin, frame, radius, atoms, coefficients, footprint, vertices and their local x', y', and
  ///         with \a attributes one code per attribute channel
  PatchCode
  codePatch (const Patch& patch, std::size_t patch_index, const TriangleMesh& mesh,
             const std::vector<double>& mean_ring_edge_lengths, const SurfaceBasis& basis, const SparseCodingOptions& options, PatchCodingInfo* info = nullptr,
             const AttributeCodingInput* attributes = nullptr, const MeshTopology* topology = nullptr);

  /// Cuts \a code, coded with \a info by codePatch, to its first \a max_atoms atoms (nothing changes when
  /// it has no more): the code and info that codePatch with options.max_atoms = \a max_atoms gives, bit for
  /// bit, without sampling, evaluating or pursuing again (OMP's first k steps do not depend on L).
  void
  truncatePatchCode (int max_atoms, PatchCode& code, PatchCodingInfo& info);

  /// The fewest atoms \a code, coded with \a info by codePatch, can be cut to (truncatePatchCode) while its
  /// heights move by at most \a max_change over its footprint, in local units: at most the sum of the
  /// coefficients' changes (the dropped atoms' whole coefficients), each times its atom's bound there (as
  /// PatchCode::heightBound: 1 for a cosine, more for the quadric's monomials past the unit square).
  /// \param[in] code        the code
  /// \param[in] basis       the basis it is over
  /// \param[in] info        its coding info (OMP's prefixes)
  /// \param[in] max_change  the largest change allowed (local units)
  /// \return a count in [0, code.atoms.size ()]; the whole code where \a info holds no prefixes
  int
  shortestPrefixWithin (const PatchCode& code, const SurfaceBasis& basis, const PatchCodingInfo& info,
                        double max_change);
} // namespace pcl_sparse
