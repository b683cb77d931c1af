#include <pcl_sparse/cloud/point_neighborhoods.h>
#include <pcl_sparse/common/thread_count.h>

#include <algorithm>
#include <numeric>

namespace pcl_sparse
{
  PointNeighborhoods
  reverseNeighborhoods (const PointNeighborhoods& neighborhoods, const std::vector<int>& sources)
  {
    const std::size_t n = neighborhoods.size ();
    PointNeighborhoods reverse;
    reverse.offsets.assign (n + 1, 0);
    for (const int i : sources)
      for (const int j : neighborhoods.of (i))
        ++reverse.offsets[static_cast<std::size_t> (j) + 1];
    std::partial_sum (reverse.offsets.begin (), reverse.offsets.end (), reverse.offsets.begin ());
    reverse.neighbors.resize (reverse.offsets.back ());
    std::vector<std::size_t> fill (reverse.offsets.begin (), reverse.offsets.end () - 1);
    for (const int i : sources)
      for (const int j : neighborhoods.of (i))
        reverse.neighbors[fill[j]++] = i;
    return reverse;
  }

  PointNeighborhoods
  symmetricNeighborhoods (const PointNeighborhoods& neighborhoods, int num_threads)
  {
    const std::size_t n = neighborhoods.size ();
    // Reverse lists (who lists j), ascending because the sources are.
    std::vector<int> all (n);
    std::iota (all.begin (), all.end (), 0);
    const PointNeighborhoods reverse = reverseNeighborhoods (neighborhoods, all);

    // Each point's own list merged with its reverse list: sizes first, then the lists.
    std::vector<std::vector<int>> merged (n);
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (n); ++i)
    {
      std::vector<int>& list = merged[i];
      const IndexRange own = neighborhoods.of (i), listed_by = reverse.of (i);
      list.assign (own.begin (), own.end ());
      list.insert (list.end (), listed_by.begin (), listed_by.end ());
      std::sort (list.begin (), list.end ());
      list.erase (std::unique (list.begin (), list.end ()), list.end ());
    }
    PointNeighborhoods out;
    out.spacing = neighborhoods.spacing;
    out.offsets.assign (n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      out.offsets[i + 1] = out.offsets[i] + merged[i].size ();
    out.neighbors.resize (out.offsets[n]);
    for (std::size_t i = 0; i < n; ++i)
      std::copy (merged[i].begin (), merged[i].end (), out.neighbors.begin () + static_cast<std::ptrdiff_t> (out.offsets[i]));
    return out;
  }
  void
  packNeighborSlots (const int* slots, std::size_t stride, const std::vector<int>& counts,
                     PointNeighborhoods& neighborhoods, int num_threads)
  {
    const std::size_t n = counts.size ();
    neighborhoods.offsets.assign (n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      neighborhoods.offsets[i + 1] = neighborhoods.offsets[i] + static_cast<std::size_t> (counts[i]);
    neighborhoods.neighbors.resize (neighborhoods.offsets[n]);
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (n); ++i)
      std::copy_n (slots + static_cast<std::size_t> (i) * stride, counts[i],
                   neighborhoods.neighbors.begin () + static_cast<std::ptrdiff_t> (neighborhoods.offsets[i]));
  }
} // namespace pcl_sparse
