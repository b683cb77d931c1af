#pragma once
/// \file coding_order.h
/// The order a model's patches code smallest in. The quantised file codes each seed as a step from the
/// previous patch's (seed_coding.h), and its other per-patch fields with adaptive probabilities that follow
/// the statistics along the order. The Morton order of the seeds makes the seed steps short (26-42 bits a
/// seed on the shared meshes, where the sampling order's byte planes took 25-48 under zstd) and keeps
/// neighbouring, mostly similar patches together; the sampling order (decreasing Harris response) keeps
/// patches of like curvature together, which on some CAD meshes is worth more (blade and turbine: 8 %
/// smaller files in it). So the encoder codes both and keeps the smaller (bench/results/patch_order.md).

#include <pcl_sparse/model/sparse_surface_model.h>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// \brief The Morton order of \a model's seeds (geometry/morton_order.h), the patches with atoms before
  /// those without (planes, the compression bound's cheapest codes: mixed in among the others they cost
  /// the other fields' adaptive models more than their seeds save; stanford-bunny's file, 40 % of its
  /// patches without atoms, 60.6 kB instead of 58.0).
  /// \param[in] model the model
  /// \return a permutation of 0 .. M - 1: entry k is the patch to put at k
  std::vector<int>
  seedMortonOrder (const SparseSurfaceModel& model);

  /// \brief Of the model's own patch order and seedMortonOrder, the one whose quantised file (default
  /// ModelWriteOptions at \a tolerance, footprint slack off, zstd level 1) is smaller; the model's own on a
  /// tie, or when either trial fails. The two files' sizes keep their ratio within 1 % from tolerance 3e-5
  /// to 1e-3 on the shared meshes, so one tolerance decides for every file. Costs two in-memory writes, run
  /// at once on two threads (spot: within the noise of its 0.38 s encoding; room_scan1.pcd, 10141 patches,
  /// 0.04 s of 0.21 s). Models of more than \a max_trial_patches patches take the Morton order untried: it
  /// coded smaller on all 11 shared scans and every shared mesh of over 1000 patches (the sampling order won
  /// only on blade, couplingdown and turbine, CAD meshes of 302-968 patches), and office1.pcd's 38249
  /// patches took 0.37 s of its 2.0 s encoding to try.
  /// \param[in] model              the model, as encodeModel takes it
  /// \param[in] num_threads        OpenMP threads (0 = default; two are used); the order does not depend on it
  /// \param[in] max_trial_patches  larger models take seedMortonOrder without a trial
  /// \param[in] tolerance          the trial files' tolerance (fraction of the bbox diagonal, > 0)
  /// \return a permutation of 0 .. M - 1: entry k is the patch to put at k
  std::vector<int>
  smallerCodingOrder (const SparseSurfaceModel& model, int num_threads = 0, std::size_t max_trial_patches = 4096,
                      double tolerance = 1e-4);
} // namespace pcl_sparse
