#pragma once
/// \file huge_pages.h
/// Large buffers that are written once from end to end (a resampled cloud; in the tools, every allocation
/// through operator new, apps/huge_page_new.cpp) are faulted in 2 MB pages instead of 4 KB ones.

#include <cstddef>

namespace pcl_sparse
{
  /// \brief Asks the kernel to back [data, data + bytes) with transparent huge pages (2 MB) where the buffer
  /// holds whole ones, before it is first written. A resampled cloud of millions of points is otherwise
  /// faulted in 4 KB at a time: a fifth of a single-threaded resampling went to those faults and to the
  /// points' construction (perf on horse, 4 M points; bench/results/resample_speed.md). Only a hint, and
  /// only on the whole huge pages inside the buffer: buffers holding none (under 2 MB, or 2-4 MB off the
  /// 2 MB grid), systems without transparent huge pages, or a refusal leave the buffer as it was.
  /// Where memory is fragmented, the kernel's defrag setting decides whether the first write waits for it
  /// to compact memory into a huge page (the Debian default for advised buffers) or takes small pages.
  void
  adviseHugePages (const void* data, std::size_t bytes);

  /// \brief vector.resize (n), with its new storage advised as huge pages before resize writes it.
  template <typename Vector>
  void
  resizeOnHugePages (Vector& vector, std::size_t n)
  {
    if (n > vector.capacity ())
    {
      vector.reserve (n);
      adviseHugePages (vector.data (), n * sizeof (typename Vector::value_type));
    }
    vector.resize (n);
  }
} // namespace pcl_sparse
