#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/memory_limit.h>

#include <sstream>

#include <unistd.h>

namespace pcl_sparse
{
  double
  physicalMemoryBytes ()
  {
    const double bytes = static_cast<double> (::sysconf (_SC_PHYS_PAGES)) * static_cast<double> (::sysconf (_SC_PAGE_SIZE));
    return bytes > 0.0 ? bytes : 0.0;
  }

  void
  checkFitsInMemory (double bytes, const std::string& what, const std::string& remedy)
  {
    const double physical = physicalMemoryBytes ();
    if (!(physical > 0.0 && bytes > physical))
      return;
    std::ostringstream message;
    message.precision (3);
    message << what << " need about " << bytes / 1e9 << " GB, more than this machine's " << physical / 1e9 << " GB";
    if (!remedy.empty ())
      message << ": " << remedy;
    throw Error (message.str ());
  }
} // namespace pcl_sparse
