#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
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

  /// An empty folder for the running test, made once per test.
  fs::path
  freshScratchDirectory ()
  {
    // One folder per test: ctest runs the tests of this file in parallel, and FailureLeavesNoFile checks
    // that no temporary file is left in its folder, which must not see the other test's temporary file
    // (nor one left by an earlier run).
    const fs::path dir =
      fs::path (PCL_SPARSE_BINARY_DIR) / "atomic_write" / ::testing::UnitTest::GetInstance ()->current_test_info ()->name ();
    fs::remove_all (dir);
    fs::create_directories (dir);
    return dir;
  }
} // namespace

TEST (AtomicWrite, BytesAreWrittenExactlyAndReplaceTheFile)
{
  const fs::path path = freshScratchDirectory () / "bytes.bin";
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
  const fs::path dir = freshScratchDirectory ();
  const fs::path path = dir / "no_such_folder" / "bytes.bin";
  EXPECT_THROW (pcl_sparse::writeBytesAtomically (path.string (), "xy", 2), pcl_sparse::Error);
  EXPECT_FALSE (fs::exists (path));
  // A writer that fails or throws half-way, after writing part of its temporary file, leaves the target
  // untouched and no temporary behind.
  const fs::path kept = dir / "kept.bin";
  pcl_sparse::writeBytesAtomically (kept.string (), "old", 3);
  std::string temporary;
  auto writeHalf = [&temporary] (const std::string& path) {
    temporary = path;
    std::ofstream (path, std::ios::binary) << "ne";
    return fs::exists (path);
  };
  EXPECT_THROW (pcl_sparse::writeFileAtomically (kept.string (), [&] (const std::string& path) {
                  writeHalf (path);
                  return false;
                }),
                pcl_sparse::Error);
  ASSERT_FALSE (temporary.empty ());
  EXPECT_FALSE (fs::exists (temporary)) << temporary;
  EXPECT_EQ (readFile (kept), "old");
  temporary.clear ();
  EXPECT_THROW (pcl_sparse::writeFileAtomically (kept.string (), [&] (const std::string& path) -> bool {
                  if (writeHalf (path))
                    throw std::runtime_error ("disk full");
                  return true;
                }),
                std::runtime_error);
  ASSERT_FALSE (temporary.empty ());
  EXPECT_FALSE (fs::exists (temporary)) << temporary;
  EXPECT_EQ (readFile (kept), "old");
  int entries = 0;
  for (const auto& entry : fs::directory_iterator (dir))
  {
    ++entries;
    EXPECT_EQ (entry.path ().string ().find (".tmp"), std::string::npos) << entry.path ();
  }
  EXPECT_EQ (entries, 1);  // kept.bin alone
}
