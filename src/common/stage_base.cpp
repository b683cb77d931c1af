#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/stage_base.h>

#include <omp.h>

namespace pcl_sparse
{
  void
  StageBase::fail (const std::string& message) const
  {
    throw Error ("[" + name_ + "::compute] " + message);
  }

  int
  StageBase::threadsToUse () const
  {
    return num_threads_ > 0 ? num_threads_ : omp_get_max_threads ();
  }
} // namespace pcl_sparse
