#pragma once
/// \file atom_budget.h
/// Sharing a bounded number of coefficients among a model's patches (ours, issue 13: a model never
/// bigger than its input). Each patch keeps a prefix of its OMP code; the prefixes are chosen greedily
/// across the whole model, each next atom by the error it removes, so the coefficients go where they buy
/// most and atoms that buy little (a flat patch fitting round-off, a tiny patch over-fitting its
/// interpolated samples) are dropped first.

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// \brief What each atom of each patch's code buys: gains[p][k] is the decrease of patch p's weighted
  /// squared error when its code grows from k to k + 1 atoms (patchAtomGains).
  using AtomGains = std::vector<std::vector<double>>;

  /// \brief The gains of one patch's atoms in world units, weighted by the vertices it stands for: the
  /// mean squared residual over its samples stands for the squared error of each of its vertices.
  /// \param[in] residual_norms ||r|| over the patch's samples after 0, 1, ... atoms, local units
  ///            (PatchCodingInfo::residual_norms)
  /// \param[in] radius         world units per local unit (PatchCode::radius)
  /// \param[in] vertex_share   sum over the patch's vertices of 1 / (patches holding the vertex): the
  ///                           part of the input's squared error the patch answers for
  /// \param[in] num_samples    samples the residuals are over (PatchCodingInfo::num_samples; < 1 counts as 1)
  /// \return one gain per atom: max(0, ||r_k||^2 - ||r_{k+1}||^2) / num_samples * radius^2 * vertex_share
  std::vector<double>
  patchAtomGains (const std::vector<double>& residual_norms, double radius, double vertex_share, int num_samples);

  /// \brief The weight patchAtomGains puts on a patch's squared residual norm (local units, over its samples):
  /// radius^2 * vertex_share / num_samples (< 1 counts as 1), so that weight * ||r||^2 is the squared error of
  /// the vertices the patch answers for, in world units.
  double
  patchErrorWeight (double radius, double vertex_share, int num_samples);

  /// \brief How many atoms each patch keeps so that at most \a budget atoms are kept in all: repeatedly
  /// the patch whose next atom has the largest gain gets it (ties: lower patch index), until the budget
  /// is spent or every code is whole. Deterministic.
  /// \param[in] gains  per patch, the gains of its atoms in code order (patchAtomGains)
  /// \param[in] budget atoms to share (< 0 counts as 0)
  /// \return one count per patch, at most gains[p].size ()
  std::vector<int>
  allocateAtoms (const AtomGains& gains, long budget);

  /// \brief How many atoms each patch keeps so that the atoms left out gain at most \a allowed_loss in all:
  /// allocateAtoms' order, stopped as soon as the gains not yet given add up to no more than the allowance.
  /// Deterministic.
  /// \param[in] gains        per patch, the gains of its atoms in code order (patchAtomGains)
  /// \param[in] allowed_loss weighted squared error the left-out atoms may add (<= 0: only atoms that gain
  ///                          nothing are left out)
  /// \return one count per patch, at most gains[p].size ()
  std::vector<int>
  allocateAtomsWithinLoss (const AtomGains& gains, double allowed_loss);
} // namespace pcl_sparse
