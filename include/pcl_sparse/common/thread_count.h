#pragma once
/// \file thread_count.h
/// What a `num_threads` option of 0 means, in one place: every stage and tool takes 0 as "as many threads
/// as OpenMP offers" (OMP_NUM_THREADS, else the cores), any positive count as itself.

namespace pcl_sparse
{
  /// The thread count to run with: \a num_threads if positive, else OpenMP's default team size.
  int
  resolveThreadCount (int num_threads);
} // namespace pcl_sparse
