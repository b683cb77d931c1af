#include <pcl_sparse/format/sparse_code_stream.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    /// \a coefficient in whole steps of \a step (> 0).
    std::int64_t
    coefficientSteps (double coefficient, double step)
    {
      const double steps = std::round (coefficient / step);
      if (!(std::abs (steps) < 9.0e15))
        throw Error ("encodeModel: coefficient too large for the tolerance");
      return static_cast<std::int64_t> (steps);
    }

    /// Bits of a count of at most \a max.
    int
    bitsFor (int max)
    {
      int bits = 1;
      while ((1 << bits) - 1 < max)
        ++bits;
      return bits;
    }
  } // namespace

  int
  shellRank (int atom, int n, int monomials)
  {
    if (atom >= n * n)
      return 1 + atom - n * n;
    const int i = atom / n, j = atom % n, m = std::max (i, j);
    const int rank = m * m + (i == m ? j : m + 1 + i);
    return rank == 0 ? 0 : rank + monomials;
  }

  int
  atomOfShellRank (int rank, int n, int monomials)
  {
    if (rank == 0)
      return 0;
    if (rank <= monomials)
      return n * n + rank - 1;
    rank -= monomials;
    int m = static_cast<int> (std::sqrt (static_cast<double> (rank)));
    while (m * m > rank)
      --m;
    while ((m + 1) * (m + 1) <= rank)
      ++m;
    const int o = rank - m * m;
    return o <= m ? m * n + o : (o - m - 1) * n + m;
  }

  std::vector<std::size_t>
  shellRankOrder (const std::vector<int>& atoms, int frequencies, int monomials)
  {
    std::vector<int> ranks (atoms.size ());
    for (std::size_t k = 0; k < atoms.size (); ++k)
      ranks[k] = shellRank (atoms[k], frequencies, monomials);
    std::vector<std::size_t> order (atoms.size ());
    std::iota (order.begin (), order.end (), 0);
    std::sort (order.begin (), order.end (), [&] (std::size_t a, std::size_t b) { return ranks[a] < ranks[b]; });
    return order;
  }

  RangeDecoder
  rangeDecoderOverRest (ByteReader& in)
  {
    const std::size_t size = in.remaining ();
    return RangeDecoder (in.getBytes (size, "range-coded bytes"), size, in.what ());
  }

  std::vector<std::size_t>
  putCodeAtoms (ByteWriter& out, const std::vector<int>& atoms, bool quantised, int frequencies, int monomials)
  {
    out.putVarint (atoms.size ());
    if (!quantised)
    {
      for (int a : atoms)
        out.putVarint (static_cast<std::uint64_t> (a));
      std::vector<std::size_t> order (atoms.size ());
      std::iota (order.begin (), order.end (), 0);
      return order;
    }
    const std::vector<std::size_t> order = shellRankOrder (atoms, frequencies, monomials);
    int previous_rank = -1;
    for (std::size_t k : order)
    {
      const int rank = shellRank (atoms[k], frequencies, monomials);
      out.putVarint (static_cast<std::uint64_t> (rank - previous_rank - 1));
      previous_rank = rank;
    }
    return order;
  }

  void
  getCodeAtoms (ByteReader& in, bool quantised, int frequencies, const std::string& code, std::vector<int>& atoms,
                int monomials)
  {
    const int basis_size = frequencies * frequencies + monomials;
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
        index = atomOfShellRank (static_cast<int> (index), frequencies, monomials);
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
      const std::int64_t steps = coefficientSteps (coefficients[k], step);
      out.putSignedVarint (steps);
      decoded.push_back (static_cast<double> (steps) * step);
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

  SparseCodeContexts::SparseCodeContexts (int frequencies, int monomials)
    : frequencies_ (frequencies), monomials_ (monomials), count_ (bitsFor (frequencies * frequencies + monomials)),
      present_ (static_cast<std::size_t> (frequencies * frequencies + monomials)),
      coefficient_ (std::min (coefficient_contexts, frequencies * frequencies + monomials))
  {
  }

  std::vector<std::size_t>
  SparseCodeContexts::putAtoms (RangeEncoder& out, const std::vector<int>& atoms)
  {
    const std::vector<std::size_t> order = shellRankOrder (atoms, frequencies_, monomials_);
    count_.put (out, static_cast<std::uint32_t> (atoms.size ()));
    int rank = 0;
    for (std::size_t k : order)
    {
      for (const int next = shellRank (atoms[k], frequencies_, monomials_); rank < next; ++rank)
        out.put (present_[rank], false);
      out.put (present_[rank++], true);
    }
    return order;
  }

  void
  SparseCodeContexts::getAtoms (RangeDecoder& in, const std::string& code, std::vector<int>& atoms)
  {
    const int basis_size = frequencies_ * frequencies_ + monomials_;
    const std::uint32_t n = count_.get (in);
    if (n > static_cast<std::uint32_t> (basis_size))
      in.fail (code + " has " + std::to_string (n) + " atoms, the basis " + std::to_string (basis_size));
    atoms.clear ();
    for (int rank = 0; atoms.size () < n; ++rank)
    {
      // n <= basis_size ranks remain to be found: stop at the basis' end.
      if (rank >= basis_size)
        in.fail (code + " runs past the basis' last atom");
      if (in.get (present_[rank]))
        atoms.push_back (atomOfShellRank (rank, frequencies_, monomials_));
    }
  }

  std::vector<double>
  SparseCodeContexts::putCoefficients (RangeEncoder& out, const std::vector<int>& atoms,
                                       const std::vector<double>& coefficients, const std::vector<std::size_t>& order,
                                       double step)
  {
    std::vector<double> decoded;
    decoded.reserve (order.size ());
    for (std::size_t k : order)
    {
      const std::int64_t steps = coefficientSteps (coefficients[k], step);
      const int rank = shellRank (atoms[k], frequencies_, monomials_);
      coefficient_[std::min<std::size_t> (rank, coefficient_.size () - 1)].put (out, steps);
      decoded.push_back (static_cast<double> (steps) * step);
    }
    return decoded;
  }

  void
  SparseCodeContexts::getCoefficients (RangeDecoder& in, const std::vector<int>& atoms, double step,
                                       std::vector<double>& coefficients)
  {
    coefficients.resize (atoms.size ());
    for (std::size_t i = 0; i < atoms.size (); ++i)
    {
      const int rank = shellRank (atoms[i], frequencies_, monomials_);
      const double c = static_cast<double> (coefficient_[std::min<std::size_t> (rank, coefficient_.size () - 1)].get (in)) * step;
      if (!std::isfinite (c))
        in.fail ("coefficient is not finite");
      coefficients[i] = c;
    }
  }
} // namespace pcl_sparse
