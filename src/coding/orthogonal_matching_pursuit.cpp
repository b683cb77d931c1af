#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  OmpResult
  orthogonalMatchingPursuit (const Eigen::VectorXd& signal, const Eigen::MatrixXd& dictionary,
                             const std::vector<char>& allowed, double tolerance, int max_atoms)
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
    for (Eigen::Index k = 0; k < num_atoms; ++k)
      candidate[k] = (allowed.empty () || allowed[k]) && squared_norms[k] > 1e-24 * largest;

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
    while (size < capacity && result.residual_norm > target)
    {
      correlation.noalias () = dictionary.transpose () * residual;
      int best = -1;
      double best_score = 0.0;
      for (Eigen::Index k = 0; k < num_atoms; ++k)
      {
        if (!candidate[k])
          continue;
        const double score = correlation[k] * correlation[k] / squared_norms[k];
        if (score > best_score)
        {
          best_score = score;
          best = static_cast<int> (k);
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
        w = support.leftCols (size).transpose () * column;
        cholesky.topLeftCorner (size, size).triangularView<Eigen::Lower> ().solveInPlace (w);
        pivot -= w.squaredNorm ();
      }
      // Numerically in the span of the support: skip this atom, keep the factor well conditioned.
      if (pivot <= 1e-10 * squared_norms[best])
        continue;
      if (size > 0)
        cholesky.block (size, 0, 1, size) = w.transpose ();
      cholesky (size, size) = std::sqrt (pivot);
      support.col (size) = column;
      rhs[size] = column.dot (signal);
      result.atoms.push_back (best);
      ++size;

      // Least squares on the support: L L^T alpha = D_S^T y.
      const auto factor = cholesky.topLeftCorner (size, size).triangularView<Eigen::Lower> ();
      coefficients = factor.solve (rhs.head (size));
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
} // namespace pcl_sparse
