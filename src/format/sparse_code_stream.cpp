#include <pcl_sparse/format/sparse_code_stream.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace pcl_sparse
{
  int
  shellRank (int atom, int n)
  {
    const int i = atom / n, j = atom % n, m = std::max (i, j);
    return m * m + (i == m ? j : m + 1 + i);
  }

  int
  atomOfShellRank (int rank, int n)
  {
    int m = static_cast<int> (std::sqrt (static_cast<double> (rank)));
    while (m * m > rank)
      --m;
    while ((m + 1) * (m + 1) <= rank)
      ++m;
    const int o = rank - m * m;
    return o <= m ? m * n + o : (o - m - 1) * n + m;
  }

  std::vector<std::size_t>
  putCodeAtoms (ByteWriter& out, const std::vector<int>& atoms, bool quantised, int frequencies)
  {
    std::vector<std::size_t> order (atoms.size ());
    std::iota (order.begin (), order.end (), 0);
    out.putVarint (order.size ());
    if (!quantised)
    {
      for (int a : atoms)
        out.putVarint (static_cast<std::uint64_t> (a));
      return order;
    }
    std::sort (order.begin (), order.end (), [&] (std::size_t a, std::size_t b) {
      return shellRank (atoms[a], frequencies) < shellRank (atoms[b], frequencies);
    });
    int previous_rank = -1;
    for (std::size_t k : order)
    {
      const int rank = shellRank (atoms[k], frequencies);
      out.putVarint (static_cast<std::uint64_t> (rank - previous_rank - 1));
      previous_rank = rank;
    }
    return order;
  }

  void
  getCodeAtoms (ByteReader& in, bool quantised, int frequencies, const std::string& code, std::vector<int>& atoms)
  {
    const int basis_size = frequencies * frequencies;
    const std::size_t n = in.getCount ("atom count", std::min<std::uint64_t> (basis_size, in.remaining ()));
    atoms.resize (n);
    std::int64_t previous = -1;
    std::vector<bool> used (basis_size, false);
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::uint64_t v = in.getCount ("atom index", static_cast<std::uint64_t> (basis_size));
      std::int64_t index = quantised ? previous + 1 + static_cast<std::int64_t> (v) : static_cast<std::int64_t> (v);
      if (index >= basis_size)
        in.fail (code + " atom " + std::to_string (index) + " outside the basis of " + std::to_string (basis_size));
      previous = index;
      if (quantised)
        index = atomOfShellRank (static_cast<int> (index), frequencies);
      if (index >= basis_size)
        in.fail (code + " atom index " + std::to_string (index) + " outside the basis of " + std::to_string (basis_size));
      if (used[index])
        in.fail (code + " repeats atom " + std::to_string (index));
      used[index] = true;
      atoms[i] = static_cast<int> (index);
    }
  }

  std::vector<double>
  putCodeCoefficients (ByteWriter& out, const std::vector<double>& coefficients, const std::vector<std::size_t>& order,
                       double step)
  {
    std::vector<double> decoded;
    decoded.reserve (order.size ());
    for (std::size_t k : order)
    {
      if (step == 0.0)
      {
        out.putF64 (coefficients[k]);
        decoded.push_back (coefficients[k]);
        continue;
      }
      const double steps = std::round (coefficients[k] / step);
      if (!(std::abs (steps) < 9.0e15))
        throw Error ("encodeModel: coefficient too large for the tolerance");
      out.putSignedVarint (static_cast<std::int64_t> (steps));
      decoded.push_back (steps * step);
    }
    return decoded;
  }

  void
  getCodeCoefficients (ByteReader& in, std::size_t count, double step, std::vector<double>& coefficients)
  {
    coefficients.resize (count);
    for (std::size_t i = 0; i < count; ++i)
    {
      const double c = step == 0.0 ? in.getF64 ("coefficient") : static_cast<double> (in.getSignedVarint ("coefficient")) * step;
      if (!std::isfinite (c))
        in.fail ("coefficient is not finite");
      coefficients[i] = c;
    }
  }
} // namespace pcl_sparse
