/// Huge-page advice for the resampled cloud's buffers (common/huge_pages.h): the vector's contract is
/// kept, and where the kernel offers transparent huge pages on request, a large buffer gets them.
#include <pcl_sparse/common/huge_pages.h>

#include <gtest/gtest.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <fstream>
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
