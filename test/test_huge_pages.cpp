/// Huge-page advice for the resampled cloud's buffers (common/huge_pages.h): the vector's contract is
/// kept, and where the kernel offers transparent huge pages on request, a large buffer gets them. This
/// executable links the tools' operator new (apps/huge_page_new.cpp) when they do: its contract and its
/// advice are checked here too.
#include <pcl_sparse/common/huge_pages.h>

#include <gtest/gtest.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <new>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// The kernel's transparent huge page mode: "always", "madvise", "never" or "" when it has none.
  std::string
  transparentHugePageMode ()
  {
    std::ifstream in ("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline (in, line);
    const std::size_t open = line.find ('['), close = line.find (']');
    return open == std::string::npos || close == std::string::npos ? "" : line.substr (open + 1, close - open - 1);
  }

  /// AnonHugePages (kB) of the mapping of this process that holds address, -1 when not found.
  long
  hugePagesKbAt (const void* address)
  {
    const std::uintptr_t a = reinterpret_cast<std::uintptr_t> (address);
    std::ifstream in ("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline (in, line))
    {
      std::uintptr_t begin = 0, end = 0;
      char dash = 0;
      std::istringstream fields (line);
      if (fields >> std::hex >> begin >> dash >> end && dash == '-' && line.find (':') > line.find (' '))
      {
        inside = begin <= a && a < end;
        continue;
      }
      if (inside && line.rfind ("AnonHugePages:", 0) == 0)
        return std::stol (line.substr (14));
    }
    return -1;
  }
} // namespace

TEST (HugePages, ResizeKeepsTheVectorsContract)
{
  std::vector<int> values = {7, 8, 9};
  resizeOnHugePages (values, 5);
  EXPECT_EQ (values, (std::vector<int>{7, 8, 9, 0, 0}));
  resizeOnHugePages (values, 2);
  EXPECT_EQ (values, (std::vector<int>{7, 8}));
  const std::size_t big = (std::size_t (16) << 20) / sizeof (int);
  resizeOnHugePages (values, big);
  ASSERT_EQ (values.size (), big);
  EXPECT_EQ (values[1], 8);
  EXPECT_EQ (values[big - 1], 0);

  // A cloud's points are constructed as resize constructs them (PointNormal: the padding w = 1).
  pcl::PointCloud<pcl::PointNormal> cloud;
  resizeOnHugePages (cloud.points, 300000);
  ASSERT_EQ (cloud.size (), 300000u);
  EXPECT_EQ (cloud[299999].x, 0.0f);
  EXPECT_EQ (cloud[299999].data[3], 1.0f);

  // Nothing to advise, or too little: no effect, no failure.
  adviseHugePages (nullptr, std::size_t (64) << 20);
  adviseHugePages (values.data (), 3);
}

TEST (HugePages, LargeBufferIsBackedByHugePages)
{
  const std::string mode = transparentHugePageMode ();
  if (mode != "madvise" && mode != "always")
    GTEST_SKIP () << "this kernel offers no transparent huge pages on request (mode '" << mode << "')";
  std::vector<char> buffer;
  const std::size_t bytes = std::size_t (64) << 20;
  resizeOnHugePages (buffer, bytes);  // resize writes every byte: the pages are faulted in here
  const long kb = hugePagesKbAt (buffer.data () + bytes / 2);
  ASSERT_GE (kb, 0) << "the buffer's mapping is not in /proc/self/smaps";
  // Without the advice (mode madvise, this machine's) none of it is; a fragmented memory may refuse some.
  EXPECT_GE (kb, 2048) << "no huge page behind a 64 MB buffer advised as huge pages";
}

#ifdef PCL_SPARSE_HUGE_PAGE_NEW_LINKED
namespace
{
  int new_handler_calls = 0;

  /// Counts its call and stands down, so that operator new then throws.
  void
  countingNewHandler ()
  {
    ++new_handler_calls;
    std::set_new_handler (nullptr);
  }
} // namespace

TEST (HugePageNew, KeepsOperatorNewsContract)
{
  // Zero bytes: a pointer of its own. Calls of the function itself, which the compiler may not elide.
  void* a = ::operator new (0);
  void* b = ::operator new (0);
  EXPECT_NE (a, nullptr);
  EXPECT_NE (a, b);
  ::operator delete (a);
  ::operator delete (b);

  // What malloc cannot give: the new handler is called until it stands down, then std::bad_alloc; the
  // nothrow form (libstdc++'s, calling this one) gives nullptr.
  const std::size_t impossible = std::size_t (1) << 62;
  new_handler_calls = 0;
  std::set_new_handler (countingNewHandler);
  EXPECT_THROW (static_cast<void> (::operator new (impossible)), std::bad_alloc);
  EXPECT_EQ (new_handler_calls, 1);
  EXPECT_EQ (::operator new (impossible, std::nothrow), nullptr);
  EXPECT_THROW (static_cast<void> (::operator new[] (impossible)), std::bad_alloc);

  // A large block holds what is written to it, end to end.
  const std::size_t bytes = std::size_t (24) << 20;
  auto* block = static_cast<unsigned char*> (::operator new (bytes));
  std::memset (block, 0xa5, bytes);
  EXPECT_EQ (block[0], 0xa5);
  EXPECT_EQ (block[bytes - 1], 0xa5);
  ::operator delete (block);
}

TEST (HugePageNew, LargeAllocationIsBackedByHugePages)
{
  const std::string mode = transparentHugePageMode ();
  if (mode != "madvise")
    GTEST_SKIP () << "huge pages on request only tell the advice apart in mode madvise (this kernel: '" << mode
                  << "')";
  // A plain std::vector, as the stages allocate: malloc alone maps it in 4 KB pages in this mode.
  const std::size_t bytes = std::size_t (64) << 20;
  std::vector<char> buffer (bytes, 1);
  const long kb = hugePagesKbAt (buffer.data () + bytes / 2);
  ASSERT_GE (kb, 0) << "the buffer's mapping is not in /proc/self/smaps";
  EXPECT_GE (kb, 2048) << "no huge page behind a 64 MB vector allocated through the tools' operator new";
}
#endif
