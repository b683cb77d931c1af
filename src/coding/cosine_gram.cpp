#include <pcl_sparse/coding/cosine_gram.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cstdlib>
#include <string>

namespace pcl_sparse
{
  CosineGram::CosineGram (const CosineAtoms& basis, const std::vector<Eigen::Vector2d>& points,
                          const std::vector<int>& atoms)
  {
    const int n = basis.frequencies ();
    int max_x = 0, max_y = 0;
    frequency_x_.reserve (atoms.size ());
    frequency_y_.reserve (atoms.size ());
    for (int a : atoms)
    {
      if (a < 0 || a >= n * n)
        throw Error ("CosineGram: atom " + std::to_string (a) + " is not one of the basis's " +
                     std::to_string (n * n) + " cosine atoms");
      frequency_x_.push_back (basis.frequencyX (a));
      frequency_y_.push_back (basis.frequencyY (a));
      max_x = std::max (max_x, frequency_x_.back ());
      max_y = std::max (max_y, frequency_y_.back ());
    }
    // Frequencies up to twice the largest listed on each axis: the sums of two atoms' frequencies.
    const int count = 2 * std::max (max_x, max_y) + 1;
    Eigen::MatrixXd cx, cy;
    basis.axisCosines (points, count, cx, cy);
    sums_.noalias () = cx.leftCols (2 * max_x + 1).transpose () * cy.leftCols (2 * max_y + 1);
  }

  void
  CosineGram::column (int k, Eigen::Ref<Eigen::VectorXd> values) const
  {
    const int i = frequency_x_[k], j = frequency_y_[k];
    for (std::size_t a = 0; a < frequency_x_.size (); ++a)
    {
      const int u = frequency_x_[a] + i, u_minus = std::abs (frequency_x_[a] - i);
      const int v = frequency_y_[a] + j, v_minus = std::abs (frequency_y_[a] - j);
      values[static_cast<Eigen::Index> (a)] =
        0.25 * ((sums_ (u, v) + sums_ (u, v_minus)) + (sums_ (u_minus, v) + sums_ (u_minus, v_minus)));
    }
  }
} // namespace pcl_sparse
