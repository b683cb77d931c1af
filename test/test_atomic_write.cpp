#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fs = std::filesystem;

namespace
{
  std::string
  readFile (const fs::path& path)
  {
    std::ifstream in (path, std::ios::binary);
    return std::string (std::istreambuf_iterator<char> (in), std::istreambuf_iterator<char> ());
  }

  fs::path
  scratchDirectory ()
  {
    // One folder per test: ctest runs the tests of this file in parallel, and FailureLeavesNoFile checks
    // that no temporary file is left in its folder, which must not see the other test's temporary file.
    const fs::path dir =
      fs::path (PCL_SPARSE_BINARY_DIR) / "atomic_write" / ::testing::UnitTest::GetInstance ()->current_test_info ()->name ();
    fs::create_directories (dir);
    return dir;
  }
} // namespace

TEST (AtomicWrite, BytesAreWrittenExactlyAndReplaceTheFile)
{
  const fs::path path = scratchDirectory () / "bytes.bin";
  const std::string first ("a\0b\nc", 5);
  pcl_sparse::writeBytesAtomically (path.string (), first.data (), first.size ());
  EXPECT_EQ (readFile (path), first);
  pcl_sparse::writeBytesAtomically (path.string (), "xy", 2);
  EXPECT_EQ (readFile (path), "xy");
  pcl_sparse::writeBytesAtomically (path.string (), nullptr, 0);
  EXPECT_TRUE (fs::exists (path));
  EXPECT_EQ (fs::file_size (path), 0u);
}

TEST (AtomicWrite, FailureLeavesNoFile)
{
  const fs::path path = scratchDirectory () / "no_such_folder" / "bytes.bin";
  EXPECT_THROW (pcl_sparse::writeBytesAtomically (path.string (), "xy", 2), pcl_sparse::Error);
  EXPECT_FALSE (fs::exists (path));
  // A failing writer leaves the target untouched.
  const fs::path kept = scratchDirectory () / "kept.bin";
  pcl_sparse::writeBytesAtomically (kept.string (), "old", 3);
  EXPECT_THROW (pcl_sparse::writeFileAtomically (kept.string (), [] (const std::string&) { return false; }),
                pcl_sparse::Error);
  EXPECT_EQ (readFile (kept), "old");
  for (const auto& entry : fs::directory_iterator (scratchDirectory ()))
    EXPECT_EQ (entry.path ().string ().find (".tmp"), std::string::npos) << entry.path ();
}
