#pragma once
/// \file orthogonal_matching_pursuit.h
/// Orthogonal Matching Pursuit over an explicit dictionary matrix, restricted to allowed atoms
/// (docs/METHOD.md step 9; the Nyquist cap of nyquist_cap.h supplies the mask).

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace pcl_sparse
{
  /// A sparse code: atoms in selection order and their coefficients.
  struct OmpResult
  {
    std::vector<int> atoms;             ///< selected columns, in selection order
    std::vector<double> coefficients;   ///< one per atom, for the columns as given (not normalised)
    double residual_norm = 0.0;         ///< ||y - D_S alpha||
    /// ||r|| after 0, 1, ..., atoms.size () atoms (so residual_norms.front () = ||y||): the code's first k
    /// atoms are what OMP with max_atoms = k selects, and these are their residuals (atom_budget.h).
    std::vector<double> residual_norms;
    /// The least-squares coefficients after 1, 2, ..., atoms.size () atoms, one set after another: those
    /// of the first k atoms start at k (k - 1) / 2. OMP with max_atoms = k gives exactly these (the same
    /// steps in the same order), so a code can be cut to fewer atoms without coding it again.
    std::vector<double> prefix_coefficients;
  };

  /// How orthogonalMatchingPursuit chooses among the atoms besides their correlation; the defaults are
  /// plain OMP.
  struct OmpSelection
  {
    /// A step takes the best preferred atom (allowed flag 2) instead of the best atom when its score is at
    /// least this fraction of the best one's (0: preferred atoms first while one still correlates with
    /// the residual; 1: no preference).
    double preference = 1.0;
    /// Atoms whose RMS over the samples is below this are never selected: nearly zero at every sample
    /// (a monomial y on samples along a line y = 0), such an atom fits the signal only with a coefficient
    /// that explodes away from the samples. 0: no floor.
    double min_column_rms = 0.0;
    /// An atom is skipped when the part of its column outside the span of the support holds less than this
    /// fraction of its squared norm (1e-10: only numerically dependent atoms). Larger keeps the least-squares
    /// system well conditioned where atoms are nearly dependent on the samples (x^2 and cos(pi x) on a
    /// small cluster), whose coefficients would otherwise cancel in the thousands.
    double min_new_fraction = 1e-10;
    /// Score each candidate by the residual reduction it would give, <r, d_k>^2 over the squared norm of
    /// d_k's part outside the support's span (orthogonal least squares, "OOMP"), instead of over |d_k|^2
    /// (OMP). With the quadric's monomials OMP undervalued them: after the constant, x^2 correlates with
    /// the residual through its part without the mean only, but its OMP score divides by its whole norm,
    /// and on a sphere's cap cos(pi x) cos(pi y) won (resampled normals up to 17.7 degrees off, 0.26 with
    /// these scores). Each step forms the rows L^-1 D_S^T D for the running norms, and takes the next
    /// correlations and the factor's new row from them instead of from the samples.
    bool orthogonal_scores = false;
  };

  /// Greedy sparse approximation y ~ D alpha.
  /// \param[in] signal      #P values y
  /// \param[in] dictionary  #P by K matrix D (columns need not be normalised)
  /// \param[in] allowed     K flags (non-zero: may be selected; 2: preferred); empty: every atom is allowed
  /// \param[in] tolerance   stop once ||r|| <= tolerance ||y|| (eps of docs/METHOD.md step 9: 0.01)
  /// \param[in] max_atoms   stop after this many atoms (L: 12)
  /// \param[in] selection   preference for the preferred atoms and conditioning floors (OmpSelection)
  /// \return the selected atoms, their coefficients and the residual norm
  ///
  /// Each step selects the allowed atom maximising |<r, d_k>| / ||d_k|| (normalised columns; over the norm of
  /// d_k's part outside the support's span with OmpSelection::orthogonal_scores), then
  /// re-solves least squares on the whole support through an incrementally updated Cholesky factor of
  /// D_S^T D_S (O(#P |S|) per step, no pseudo-inverse). It also stops when no allowed atom correlates
  /// with the residual any more; an atom numerically dependent on the support is skipped, never added.
  /// A zero signal gives the empty code.
  OmpResult
  orthogonalMatchingPursuit (const Eigen::VectorXd& signal, const Eigen::MatrixXd& dictionary,
                             const std::vector<char>& allowed, double tolerance, int max_atoms,
                             const OmpSelection& selection = OmpSelection ());

  /// Fills column j of a dictionary's Gram matrix D^T D (K values) when it can be formed more cheaply than D^T d_j.
  using GramColumnFunction = std::function<void (int j, Eigen::Ref<Eigen::VectorXd> column)>;

  /// OMP of several signals over one dictionary (Batch OMP: Rubinstein, Zibulevsky and Elad, "Efficient
  /// implementation of the K-SVD algorithm using Batch Orthogonal Matching Pursuit", 2008), for the
  /// channels of an attribute (colour), which share their samples.
  /// \param[in] signals     #P by C matrix: one signal per column
  /// \param[in] dictionary  #P by K matrix D, every atom allowed
  /// \param[in] tolerances  C relative tolerances, as orthogonalMatchingPursuit's
  /// \param[in] max_atoms   L, for every signal
  /// \return C codes: orthogonalMatchingPursuit's steps and stopping rules, with the same atoms and
  ///         coefficients up to round-off (prefix_coefficients are not kept)
  ///
  /// orthogonalMatchingPursuit forms D^T r, O(#P K), at every step of every signal. Here the correlations
  /// are D^T y - G_S alpha, from D^T Y (formed once for all signals) and the Gram columns D^T d_j of the atoms
  /// chosen so far, each formed once when some signal first chooses it: channels that choose the same atoms
  /// share them. The Cholesky factor's new row comes from the Gram columns too. The residual is still
  /// formed, O(#P |S|), for the stopping test. With \a gram_column (CosineGram for cosine atoms), a Gram column
  /// comes from it instead of the O(#P K) product D^T d_j.
  /// \param[in] gram_column  empty, or fills D^T d_j for column j (K values)
  std::vector<OmpResult>
  batchOrthogonalMatchingPursuit (const Eigen::MatrixXd& signals, const Eigen::Ref<const Eigen::MatrixXd>& dictionary,
                                  const std::vector<double>& tolerances, int max_atoms,
                                  const GramColumnFunction& gram_column = {});
} // namespace pcl_sparse
