#pragma once
// Internal to src/cloud: a set of directed edges (a, b) with open addressing, for the sequential passes
// that ask "is this half-edge used?" hundreds of thousands of times (std::unordered_set allocates a node
// per edge and was a tenth of the kNN surface's time).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  class EdgeSet
  {
  public:
    /// Room for about \a expected edges before the table grows.
    explicit EdgeSet (std::size_t expected = 0) { rehash (expected); }

    bool
    contains (int a, int b) const
    {
      const std::uint64_t k = key (a, b);
      for (std::size_t s = slot (k);; s = (s + 1) & mask_)
      {
        if (table_[s] == k)
          return true;
        if (table_[s] == kEmpty)
          return false;
      }
    }

    /// Inserts (a, b); returns false if it was there.
    bool
    insert (int a, int b)
    {
      if (2 * (size_ + 1) > table_.size ())
        rehash (2 * size_ + 2);
      return place (key (a, b));
    }

  private:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t (0);

    static std::uint64_t key (int a, int b) { return (static_cast<std::uint64_t> (static_cast<std::uint32_t> (a)) << 32) | static_cast<std::uint32_t> (b); }

    std::size_t
    slot (std::uint64_t k) const
    {
      k ^= k >> 33;
      k *= 0xff51afd7ed558ccdull;
      k ^= k >> 33;
      return static_cast<std::size_t> (k) & mask_;
    }

    bool
    place (std::uint64_t k)
    {
      for (std::size_t s = slot (k);; s = (s + 1) & mask_)
      {
        if (table_[s] == k)
          return false;
        if (table_[s] == kEmpty)
        {
          table_[s] = k;
          ++size_;
          return true;
        }
      }
    }

    void
    rehash (std::size_t expected)
    {
      std::size_t capacity = 16;
      while (capacity < 2 * expected)
        capacity *= 2;
      std::vector<std::uint64_t> old;
      old.swap (table_);
      table_.assign (capacity, kEmpty);
      mask_ = capacity - 1;
      size_ = 0;
      for (const std::uint64_t k : old)
        if (k != kEmpty)
          place (k);
    }

    std::vector<std::uint64_t> table_;
    std::size_t mask_ = 0;
    std::size_t size_ = 0;
  };
} // namespace pcl_sparse
