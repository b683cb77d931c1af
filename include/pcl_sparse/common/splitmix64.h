#pragma once
/// \file splitmix64.h
/// The one 64-bit mixing function behind the library's seeded, order-independent random numbers.

#include <cstdint>

namespace pcl_sparse
{
  /// \brief splitmix64's finaliser (Steele, Lea and Flood 2014): a stateless, well-mixed hash of \a x.
  /// A random number made as a function of (seed, item, draw) does not depend on the order or the thread
  /// that asks for it, and costs nothing to seed; the same numbers on every platform.
  /// \param[in] x  the value to mix (a counter, an index, a seed)
  /// \return its hash
  constexpr std::uint64_t
  splitmix64 (std::uint64_t x)
  {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  }
} // namespace pcl_sparse
