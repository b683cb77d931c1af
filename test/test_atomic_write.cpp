#include "error_message.h"

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/cloud_stream_writer.h>

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

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

TEST (AtomicWrite, AFullDiskFailsEveryCloudFormat)
{
  // pcl::PCDWriter::writeASCII never checks its stream: with the disk full it returned success and the tool
  // renamed a truncated file into place and exited 0. A file size limit stands in for a full disk.
  const fs::path dir = freshScratchDirectory ();
  pcl::PointCloud<pcl::PointNormal> cloud;
  for (int i = 0; i < 5000; ++i)
  {
    pcl::PointNormal p;
    p.x = 0.001f * static_cast<float> (i);
    p.y = 1.0f / static_cast<float> (i + 1);
    p.z = 0.5f;
    p.normal_x = p.normal_y = 0.0f;
    p.normal_z = 1.0f;
    p.curvature = 0.0f;
    cloud.push_back (p);
  }
  struct rlimit saved;
  ASSERT_EQ (getrlimit (RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = std::signal (SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead of killing us
  struct rlimit small = saved;
  small.rlim_cur = 4096;
  ASSERT_EQ (setrlimit (RLIMIT_FSIZE, &small), 0);
  for (const char* name : {"cloud.pcd", "cloud.ply"})
    for (const bool binary : {true, false})
    {
      SCOPED_TRACE (std::string (name) + (binary ? " binary" : " ascii"));
      const fs::path path = dir / name;
      // The cause is named (the streamed writer named it; the whole-cloud writers said only "could not write").
      const std::string message =
        pcl_sparse_test::errorMessage ([&] { pcl_sparse::savePointNormalCloud (path.string (), cloud, binary); });
      // PCL's PCD writers leave no errno: the ascii one's cut is found by reading the file back, the binary one
      // is refused without a cause.
      const bool pcd = path.extension () == ".pcd";
      const std::string cause = !pcd    ? std::string (" (") + std::strerror (EFBIG) + ")"
                                : binary ? ""
                                         : " (it came out short: the disk is full or the file over a size limit)";
      EXPECT_EQ (message, path.string () + ": could not write the file" + cause);
      EXPECT_FALSE (fs::exists (path));
    }
  setrlimit (RLIMIT_FSIZE, &saved);
  std::signal (SIGXFSZ, old_handler);
  EXPECT_TRUE (fs::is_empty (dir)) << "a temporary file was left behind";
  // Without the limit every format writes (the check does not refuse complete files).
  for (const char* name : {"cloud.pcd", "cloud.ply"})
    for (const bool binary : {true, false})
    {
      const fs::path path = dir / name;
      pcl_sparse::savePointNormalCloud (path.string (), cloud, binary);
      pcl::PointCloud<pcl::PointXYZ> back;
      pcl_sparse::loadPointCloud (path.string (), back);
      EXPECT_EQ (back.size (), cloud.size ()) << name << (binary ? " binary" : " ascii");
    }
}

TEST (AtomicWrite, LongFileNamesAreWritten)
{
  // The temporary was the name + ".tmp" + the pid: a file name of 250 bytes, which the file system takes
  // (it allows 255), was refused with "could not write the file".
  const fs::path dir = freshScratchDirectory ();
  const std::string pid = std::to_string (::getpid ());
  const std::string short_path = (dir / "a.bin").string ();
  EXPECT_EQ (pcl_sparse::temporaryPathFor (short_path), short_path + ".tmp" + pid);
  EXPECT_EQ (pcl_sparse::temporaryPathFor ("a.bin"), "a.bin.tmp" + pid);  // no folder: the working one
  const std::string long_a = (dir / (std::string (246, 'x') + "a.bin")).string ();
  const std::string long_b = (dir / (std::string (246, 'x') + "b.bin")).string ();
  const fs::path temporary_a = pcl_sparse::temporaryPathFor (long_a);
  EXPECT_EQ (temporary_a.parent_path (), dir);
  EXPECT_LE (temporary_a.filename ().string ().size (), 255u);
  EXPECT_EQ (temporary_a.filename ().string ().substr (0, 200), std::string (200, 'x'));
  EXPECT_NE (temporary_a, fs::path (pcl_sparse::temporaryPathFor (long_b)));  // same start, other names
  for (const std::size_t length : {250u, 255u})
  {
    const fs::path path = dir / (std::string (length - 4, 'y') + ".bin");
    ASSERT_EQ (path.filename ().string ().size (), length);
    pcl_sparse::writeBytesAtomically (path.string (), "xy", 2);
    EXPECT_EQ (readFile (path), "xy") << length;
  }
  pcl::PointCloud<pcl::PointNormal> cloud;
  cloud.resize (3);
  for (const char* extension : {".pcd", ".ply"})
  {
    const fs::path saved = dir / (std::string (246, 's') + extension);
    pcl_sparse::savePointNormalCloud (saved.string (), cloud, true);
    const fs::path streamed = dir / (std::string (246, 'w') + extension);
    pcl_sparse::PointNormalStreamWriter writer (streamed.string (), cloud.size ());
    writer.write (cloud);
    writer.finish ();
    for (const fs::path& path : {saved, streamed})
    {
      pcl::PointCloud<pcl::PointXYZ> back;
      pcl_sparse::loadPointCloud (path.string (), back);
      EXPECT_EQ (back.size (), 3u) << path.filename ().string ().substr (240);
    }
  }
  for (const auto& entry : fs::directory_iterator (dir))
    EXPECT_EQ (entry.path ().filename ().string ().find (".tmp"), std::string::npos) << "left behind";
}
