#include <pcl_sparse/coding/atom_budget.h>

#include <algorithm>
#include <queue>
#include <utility>

namespace pcl_sparse
{
  std::vector<double>
  patchAtomGains (const std::vector<double>& residual_norms, double radius, double vertex_share, int num_samples)
  {
    std::vector<double> gains;
    if (residual_norms.size () < 2)
      return gains;
    const double scale = radius * radius * vertex_share / std::max (1, num_samples);
    gains.reserve (residual_norms.size () - 1);
    for (std::size_t k = 0; k + 1 < residual_norms.size (); ++k)
    {
      const double before = residual_norms[k], after = residual_norms[k + 1];
      gains.push_back (std::max (0.0, (before - after) * (before + after)) * scale);
    }
    return gains;
  }

  std::vector<int>
  allocateAtoms (const AtomGains& gains, long budget)
  {
    std::vector<int> counts (gains.size (), 0);
    // Max-heap on (gain of the patch's next atom, -patch): the lower index wins ties.
    using Entry = std::pair<double, long>;
    std::priority_queue<Entry> next;
    for (std::size_t p = 0; p < gains.size (); ++p)
      if (!gains[p].empty ())
        next.emplace (gains[p][0], -static_cast<long> (p));
    for (long spent = 0; spent < budget && !next.empty (); ++spent)
    {
      const std::size_t p = static_cast<std::size_t> (-next.top ().second);
      next.pop ();
      const std::size_t k = static_cast<std::size_t> (++counts[p]);
      if (k < gains[p].size ())
        next.emplace (gains[p][k], -static_cast<long> (p));
    }
    return counts;
  }
} // namespace pcl_sparse
