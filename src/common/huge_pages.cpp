#include <pcl_sparse/common/huge_pages.h>

#include <cstdint>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace pcl_sparse
{
  void
  adviseHugePages (const void* data, std::size_t bytes)
  {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::uintptr_t huge = std::uintptr_t (2) << 20;
    if (data == nullptr || bytes < huge)
      return;
    const std::uintptr_t first = reinterpret_cast<std::uintptr_t> (data);
    const std::uintptr_t begin = (first + huge - 1) & ~(huge - 1);
    const std::uintptr_t end = (first + bytes) & ~(huge - 1);
    if (end > begin)
      madvise (reinterpret_cast<void*> (begin), end - begin, MADV_HUGEPAGE);  // a hint: a refusal is harmless
#else
    (void) data;
    (void) bytes;
#endif
  }
} // namespace pcl_sparse
