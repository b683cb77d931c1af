/// \file huge_page_new.cpp
/// The global operator new of the executables that link this file (the tools and the ROS nodes; CMake's
/// pcl_sparse_use_huge_page_new), never of the library, whose users pick their own. Each allocation of
/// a whole transparent huge page or more is advised as huge pages before it is first written
/// (common/huge_pages.h): a stage's buffers of tens of megabytes (a scan's neighbour lists, a mesh's
/// topology) are then faulted in 2 MB at a time instead of 4 KB, which took a tenth of a tool's run on a
/// large scan or mesh (bench/results/allocator.md). The memory is malloc's as before, so delete, the
/// resident set and the memory-bounded paths are unchanged; new[] and the nothrow forms call this one.

#include <pcl_sparse/common/huge_pages.h>

#include <cstdlib>
#include <new>

void*
operator new (std::size_t bytes)
{
  for (;;)
  {
    if (void* data = std::malloc (bytes > 0 ? bytes : 1))
    {
      pcl_sparse::adviseHugePages (data, bytes);
      return data;
    }
    const std::new_handler handler = std::get_new_handler ();
    if (!handler)
      throw std::bad_alloc ();
    handler ();
  }
}
