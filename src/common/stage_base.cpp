#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/stage_base.h>
#include <pcl_sparse/common/thread_count.h>

#include <string>

namespace pcl_sparse
{
  void
  StageBase::fail (const std::string& message) const
  {
    throw Error ("[" + name_ + "::compute] " + message);
  }

  void
  StageBase::setNumberOfThreads (int threads)
  {
    if (threads < 0 || threads > 1024)
      throw Error ("[" + name_ + "::setNumberOfThreads] the thread count must be in [0, 1024], got " + std::to_string (threads));
    num_threads_ = threads;
  }

  int
  StageBase::threadsToUse () const
  {
    return resolveThreadCount (num_threads_);
  }
} // namespace pcl_sparse
