#pragma once
// Tests on the data in ../shared: skipped when a shared folder is absent (a fresh clone on its own), failed when
// a file is missing from a folder that is there (a renamed or lost file must not pass as a skipped test).

#include <gtest/gtest.h>

#include <filesystem>

namespace pcl_sparse_test
{
  enum class SharedFileState
  {
    Present,
    FolderAbsent,      ///< the file's folder is not there: the shared data is absent
    MissingFromFolder  ///< the folder is there, the file is not
  };

  inline SharedFileState
  sharedFileState (const std::filesystem::path& path)
  {
    if (std::filesystem::exists (path))
      return SharedFileState::Present;
    return std::filesystem::is_directory (path.parent_path ()) ? SharedFileState::MissingFromFolder
                                                               : SharedFileState::FolderAbsent;
  }
} // namespace pcl_sparse_test

/// In a test body: skips the test when the folder of the shared file \a file is absent, fails it when the
/// folder is there and \a file is not.
#define PCL_SPARSE_NEED_SHARED_FILE(file)                                                                      \
  do                                                                                                           \
  {                                                                                                            \
    const std::filesystem::path pcl_sparse_shared_path_ (file);                                               \
    switch (::pcl_sparse_test::sharedFileState (pcl_sparse_shared_path_))                                      \
    {                                                                                                          \
    case ::pcl_sparse_test::SharedFileState::FolderAbsent:                                                     \
      GTEST_SKIP () << "the shared data is absent (" << pcl_sparse_shared_path_.parent_path ().string ()      \
                    << " is not a folder)";                                                                    \
    case ::pcl_sparse_test::SharedFileState::MissingFromFolder:                                                \
      FAIL () << pcl_sparse_shared_path_.string () << " is missing from its shared folder, which is there";   \
    case ::pcl_sparse_test::SharedFileState::Present:                                                          \
      break;                                                                                                   \
    }                                                                                                          \
  } while (false)
