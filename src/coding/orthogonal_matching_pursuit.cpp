#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>

#include <pcl_sparse/common/error.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// The candidate atom k maximising <r, d_k>^2 / n_k given the correlations <r, d_k> and the norms n_k
    /// (|d_k|^2, or the part outside the support's span), and that score in \a best_score; -1 if no
    /// candidate scores above 0. A norm at most \a floor_k (numerically in the span) is no candidate.
    int
    bestAtom (const Eigen::VectorXd& correlation, const Eigen::VectorXd& norms, const Eigen::VectorXd& floors,
              const std::vector<char>& candidate, double& best_score, char tier = 1)
    {
      int best = -1;
      best_score = 0.0;
      for (Eigen::Index k = 0; k < correlation.size (); ++k)
      {
        if (candidate[k] < tier || !(norms[k] > floors[k]))
          continue;
        const double score = correlation[k] * correlation[k] / norms[k];
        if (score > best_score)
        {
          best_score = score;
          best = static_cast<int> (k);
        }
      }
      return best;
    }

    /// Row \a size of L^-1 D_S^T D for the atom \a column just added, (d_new^T D - w^T rows 0 .. size-1) /
    /// L(size, size) with w = L^-1 D_S^T d_new, into \a spanned; \a outside (|d_k|^2 minus the squares of
    /// the rows so far) loses its square.
    template <typename Column>
    void
    appendSpannedRow (const Eigen::MatrixXd& dictionary, const Column& column, const Eigen::VectorXd& w,
                      double diagonal, int size, Eigen::MatrixXd& spanned, Eigen::VectorXd& outside)
    {
      spanned.row (size).noalias () = column.transpose () * dictionary;
      if (size > 0)
        spanned.row (size).noalias () -= w.transpose () * spanned.topRows (size);
      spanned.row (size) /= diagonal;
      outside -= spanned.row (size).transpose ().cwiseAbs2 ();
    }
  } // namespace

  OmpResult
  orthogonalMatchingPursuit (const Eigen::VectorXd& signal, const Eigen::MatrixXd& dictionary,
                             const std::vector<char>& allowed, double tolerance, int max_atoms,
                             const OmpSelection& selection)
  {
    OmpResult result;
    const Eigen::Index num_points = dictionary.rows ();
    const Eigen::Index num_atoms = dictionary.cols ();
    const double signal_norm = signal.norm ();
    result.residual_norm = signal_norm;
    result.residual_norms.assign (1, signal_norm);
    if (signal_norm == 0.0 || num_points == 0 || num_atoms == 0 || max_atoms < 1 || signal.size () != num_points)
      return result;

    // Candidates: allowed atoms with a non-negligible column.
    const Eigen::VectorXd squared_norms = dictionary.colwise ().squaredNorm ().transpose ();
    const double largest = squared_norms.maxCoeff ();
    std::vector<char> candidate (num_atoms, 0);
    bool preferred = false;
    const double min_squared_norm = std::max (1e-24 * largest, selection.min_column_rms * selection.min_column_rms *
                                                                   static_cast<double> (num_points));
    for (Eigen::Index k = 0; k < num_atoms; ++k)
    {
      const char flag = allowed.empty () ? 1 : allowed[k];
      candidate[k] = squared_norms[k] > min_squared_norm ? flag : 0;
      preferred = preferred || candidate[k] == 2;
    }

    const int capacity = static_cast<int> (std::min<Eigen::Index> (max_atoms, std::min (num_points, num_atoms)));
    Eigen::MatrixXd support (num_points, capacity);    // D_S, the selected columns
    Eigen::MatrixXd cholesky = Eigen::MatrixXd::Zero (capacity, capacity);  // L with L L^T = D_S^T D_S
    Eigen::VectorXd rhs (capacity);                     // D_S^T y
    Eigen::VectorXd coefficients;
    Eigen::VectorXd residual = signal;
    const double target = tolerance * signal_norm;
    int size = 0;

    result.prefix_coefficients.reserve (static_cast<std::size_t> (capacity * (capacity + 1) / 2));
    Eigen::VectorXd correlation (num_atoms);
    // Orthogonal scores: rows t of L^-1 D_S^T D, and |d_k|^2 minus their squares (the part outside the span).
    Eigen::MatrixXd spanned (selection.orthogonal_scores ? capacity : 0, num_atoms);
    Eigen::VectorXd outside = squared_norms;
    const Eigen::VectorXd floors = selection.orthogonal_scores ? Eigen::VectorXd (selection.min_new_fraction * squared_norms)
                                                               : Eigen::VectorXd::Zero (num_atoms);
    // With the rows of L^-1 D_S^T D at hand, D^T r = D^T y - (L^-1 D_S^T D)^T z with z = L^-1 D_S^T y: K x |S|
    // operations instead of the P x K of D^T r (the coding stage of the shared meshes 12-24 % faster).
    const Eigen::VectorXd projections =  // D^T y
      selection.orthogonal_scores ? Eigen::VectorXd (dictionary.transpose () * signal) : Eigen::VectorXd ();
    Eigen::VectorXd projected_signal;  // z
    while (size < capacity && result.residual_norm > target)
    {
      if (!selection.orthogonal_scores)
        correlation.noalias () = dictionary.transpose () * residual;
      else if (size == 0)
        correlation = projections;
      else
        correlation.noalias () = projections - spanned.topRows (size).transpose () * projected_signal;
      double best_score = 0.0;
      int best = bestAtom (correlation, outside, floors, candidate, best_score);
      // A preferred atom wins while it scores at least preference x the best one.
      if (preferred)
      {
        double preferred_score = 0.0;
        const int best_preferred = bestAtom (correlation, outside, floors, candidate, preferred_score, 2);
        if (best_preferred >= 0 && std::sqrt (preferred_score) > 1e-12 * signal_norm &&
            preferred_score >= selection.preference * best_score)
        {
          best = best_preferred;
          best_score = preferred_score;
        }
      }
      // No allowed atom left that can reduce the residual (relative to the signal, beyond round-off).
      if (best < 0 || std::sqrt (best_score) <= 1e-12 * signal_norm)
        break;
      candidate[best] = 0;

      // Extend the Cholesky factor by the new column: [L 0; w^T d], L w = D_S^T d_new, d^2 = |d_new|^2 - |w|^2.
      const auto column = dictionary.col (best);
      Eigen::VectorXd w;
      double pivot = squared_norms[best];
      if (size > 0)
      {
        if (selection.orthogonal_scores)
          w = spanned.col (best).head (size);  // L^-1 D_S^T d_new, already a column of those rows
        else
        {
          w = support.leftCols (size).transpose () * column;
          cholesky.topLeftCorner (size, size).triangularView<Eigen::Lower> ().solveInPlace (w);
        }
        pivot -= w.squaredNorm ();
      }
      // (Nearly) in the span of the support: skip this atom, keep the factor well conditioned.
      if (pivot <= selection.min_new_fraction * squared_norms[best])
        continue;
      if (size > 0)
        cholesky.block (size, 0, 1, size) = w.transpose ();
      cholesky (size, size) = std::sqrt (pivot);
      support.col (size) = column;
      rhs[size] = column.dot (signal);
      if (selection.orthogonal_scores)
        appendSpannedRow (dictionary, column, w, cholesky (size, size), size, spanned, outside);
      result.atoms.push_back (best);
      ++size;

      // Least squares on the support: L L^T alpha = D_S^T y.
      const auto factor = cholesky.topLeftCorner (size, size).triangularView<Eigen::Lower> ();
      coefficients = factor.solve (rhs.head (size));
      if (selection.orthogonal_scores)
        projected_signal = coefficients;
      factor.transpose ().solveInPlace (coefficients);
      residual = signal - support.leftCols (size) * coefficients;
      result.residual_norm = residual.norm ();
      result.residual_norms.push_back (result.residual_norm);
      result.prefix_coefficients.insert (result.prefix_coefficients.end (), coefficients.data (),
                                         coefficients.data () + size);
    }
    result.coefficients.assign (coefficients.data (), coefficients.data () + coefficients.size ());
    return result;
  }

  std::vector<OmpResult>
  batchOrthogonalMatchingPursuit (const Eigen::MatrixXd& signals, const Eigen::Ref<const Eigen::MatrixXd>& dictionary,
                                  const std::vector<double>& tolerances, int max_atoms,
                                  const GramColumnFunction& gram_column)
  {
    const Eigen::Index num_points = dictionary.rows ();
    const Eigen::Index num_atoms = dictionary.cols ();
    const Eigen::Index num_signals = signals.cols ();
    if (static_cast<Eigen::Index> (tolerances.size ()) != num_signals)
      throw Error ("batchOrthogonalMatchingPursuit: " + std::to_string (tolerances.size ()) + " tolerances for " +
                   std::to_string (num_signals) + " signals");
    std::vector<OmpResult> results (static_cast<std::size_t> (num_signals));
    if (num_points == 0 || num_atoms == 0 || max_atoms < 1 || signals.rows () != num_points)
    {
      for (Eigen::Index c = 0; c < num_signals; ++c)
      {
        results[c].residual_norm = signals.col (c).norm ();
        results[c].residual_norms.assign (1, results[c].residual_norm);
      }
      return results;
    }

    const Eigen::VectorXd squared_norms = dictionary.colwise ().squaredNorm ().transpose ();
    const double largest = squared_norms.maxCoeff ();
    std::vector<char> usable (num_atoms);
    for (Eigen::Index k = 0; k < num_atoms; ++k)
      usable[k] = squared_norms[k] > 1e-24 * largest;
    const Eigen::MatrixXd projections = dictionary.transpose () * signals;  // D^T Y

    const int capacity = static_cast<int> (std::min<Eigen::Index> (max_atoms, std::min (num_points, num_atoms)));
    // Gram columns D^T d_j, formed when some signal first chooses atom j: room for signals x L at first,
    // grown when full, since an atom found dependent on a support is skipped after its column was formed
    // (patches with fewer samples than atoms form more).
    Eigen::MatrixXd gram (num_atoms, std::min (num_atoms, num_signals * capacity));
    std::vector<Eigen::Index> gram_index (num_atoms, -1);
    Eigen::Index formed_columns = 0;
    auto gramOf = [&] (int atom) {
      if (gram_index[atom] < 0)
      {
        if (formed_columns == gram.cols ())
          gram.conservativeResize (Eigen::NoChange, std::min (num_atoms, 2 * gram.cols () + 1));
        gram_index[atom] = formed_columns++;
        if (gram_column)
          gram_column (atom, gram.col (gram_index[atom]));
        else
          gram.col (gram_index[atom]).noalias () = dictionary.transpose () * dictionary.col (atom);
      }
      return gram.col (gram_index[atom]);
    };

    Eigen::MatrixXd support (num_points, capacity);
    Eigen::MatrixXd cholesky (capacity, capacity);
    Eigen::VectorXd rhs (capacity), correlation (num_atoms), w (capacity);
    const Eigen::VectorXd no_floors = Eigen::VectorXd::Zero (num_atoms);
    for (Eigen::Index c = 0; c < num_signals; ++c)
    {
      OmpResult& result = results[c];
      const auto signal = signals.col (c);
      const double signal_norm = signal.norm ();
      result.residual_norm = signal_norm;
      result.residual_norms.assign (1, signal_norm);
      if (signal_norm == 0.0)
        continue;
      std::vector<char> candidate (usable);
      const double target = tolerances[c] * signal_norm;
      Eigen::VectorXd coefficients;
      int size = 0;
      cholesky.setZero ();
      while (size < capacity && result.residual_norm > target)
      {
        // D^T r = D^T y - sum over the support of alpha_t D^T d_t.
        correlation = projections.col (c);
        for (int t = 0; t < size; ++t)
          correlation -= coefficients[t] * gram.col (gram_index[result.atoms[t]]);
        double best_score = 0.0;
        const int best = bestAtom (correlation, squared_norms, no_floors, candidate, best_score);
        if (best < 0 || std::sqrt (best_score) <= 1e-12 * signal_norm)
          break;
        candidate[best] = 0;

        // The factor's new row from the Gram column: w = L^-1 D_S^T d_new.
        const auto column_gram = gramOf (best);
        double pivot = squared_norms[best];
        if (size > 0)
        {
          for (int t = 0; t < size; ++t)
            w[t] = column_gram[result.atoms[t]];
          cholesky.topLeftCorner (size, size).triangularView<Eigen::Lower> ().solveInPlace (w.head (size));
          pivot -= w.head (size).squaredNorm ();
        }
        if (pivot <= 1e-10 * squared_norms[best])
          continue;
        if (size > 0)
          cholesky.block (size, 0, 1, size) = w.head (size).transpose ();
        cholesky (size, size) = std::sqrt (pivot);
        support.col (size) = dictionary.col (best);
        rhs[size] = projections (best, c);
        result.atoms.push_back (best);
        ++size;

        const auto factor = cholesky.topLeftCorner (size, size).triangularView<Eigen::Lower> ();
        coefficients = factor.solve (rhs.head (size));
        factor.transpose ().solveInPlace (coefficients);
        result.residual_norm = (signal - support.leftCols (size) * coefficients).norm ();
        result.residual_norms.push_back (result.residual_norm);
      }
      result.coefficients.assign (coefficients.data (), coefficients.data () + coefficients.size ());
    }
    return results;
  }
} // namespace pcl_sparse
