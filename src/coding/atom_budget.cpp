#include <pcl_sparse/coding/atom_budget.h>

#include <algorithm>
#include <queue>
#include <utility>

namespace pcl_sparse
{
  double
  patchErrorWeight (double radius, double vertex_share, int num_samples)
  {
    return radius * radius * vertex_share / std::max (1, num_samples);
  }

  std::vector<double>
  patchAtomGains (const std::vector<double>& residual_norms, double radius, double vertex_share, int num_samples)
  {
    std::vector<double> gains;
    if (residual_norms.size () < 2)
      return gains;
    const double scale = patchErrorWeight (radius, vertex_share, num_samples);
    gains.reserve (residual_norms.size () - 1);
    for (std::size_t k = 0; k + 1 < residual_norms.size (); ++k)
    {
      const double before = residual_norms[k], after = residual_norms[k + 1];
      gains.push_back (std::max (0.0, (before - after) * (before + after)) * scale);
    }
    return gains;
  }

  namespace
  {
    /// The greedy order of allocateAtoms: the patch whose next atom gains most gets it (ties: lower patch
    /// index), for as long as \a more (atoms given so far, their gains' sum) says.
    template <typename More>
    std::vector<int>
    allocateGreedily (const AtomGains& gains, More more)
    {
      std::vector<int> counts (gains.size (), 0);
      // Max-heap on (gain of the patch's next atom, -patch): the lower index wins ties.
      using Entry = std::pair<double, long>;
      std::priority_queue<Entry> next;
      for (std::size_t p = 0; p < gains.size (); ++p)
        if (!gains[p].empty ())
          next.emplace (gains[p][0], -static_cast<long> (p));
      long spent = 0;
      double gained = 0.0;
      while (!next.empty () && more (spent, gained))
      {
        const std::size_t p = static_cast<std::size_t> (-next.top ().second);
        gained += next.top ().first;
        next.pop ();
        ++spent;
        const std::size_t k = static_cast<std::size_t> (++counts[p]);
        if (k < gains[p].size ())
          next.emplace (gains[p][k], -static_cast<long> (p));
      }
      return counts;
    }
  } // namespace

  std::vector<int>
  allocateAtoms (const AtomGains& gains, long budget)
  {
    return allocateGreedily (gains, [budget] (long spent, double) { return spent < budget; });
  }

  std::vector<int>
  allocateAtomsWithinLoss (const AtomGains& gains, double allowed_loss)
  {
    double total = 0.0;
    for (const std::vector<double>& patch_gains : gains)
      for (double gain : patch_gains)
        total += gain;
    return allocateGreedily (gains, [total, allowed_loss] (long, double gained) { return total - gained > allowed_loss; });
  }
} // namespace pcl_sparse
