#include <pcl_sparse/common/thread_count.h>

#include <omp.h>

namespace pcl_sparse
{
  int
  resolveThreadCount (int num_threads)
  {
    return num_threads > 0 ? num_threads : omp_get_max_threads ();
  }
} // namespace pcl_sparse
