// Files and folders registered with registerRemovalOnSignal are gone when SIGTERM ends the process, also when
// another thread keeps adding files to the folder meanwhile (a rank's spill folder while mpirun stops it), and
// a path registered before it exists does no harm.

#include <pcl_sparse/common/signal_cleanup.h>

#include <gtest/gtest.h>

#include "test_file_helpers.h"

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

using namespace pcl_sparse;

namespace
{
  /// Runs \a body in a child process and returns its wait status. An exception in the child ends it with
  /// exit code 6 (it unwound into a second copy of the test runner, which went on with the other tests).
  template <typename Body>
  int
  inChild (Body body)
  {
    const pid_t child = ::fork ();
    if (child == 0)
    {
      try
      {
        body ();
      }
      catch (...)
      {
        ::_exit (6);
      }
      ::_exit (0);  // not reached when the body raises the signal
    }
    EXPECT_GT (child, 0) << "fork failed";
    int status = 0;
    EXPECT_EQ (::waitpid (child, &status, 0), child);
    return status;
  }
} // namespace

TEST (SignalCleanup, FolderBeingFilledIsRemoved)
{
  const pcl_sparse_test::TempDir dir ("pcl_sparse_signal");
  // Each round: a thread creates files in the folder as fast as it can, the main thread raises SIGTERM. The
  // handler listed the folder once and left it when a file came in before its rmdir; listing it again (100
  // times) still lost to a writer on the other core of an idle machine, so the folder is renamed first.
  for (int round = 0; round < 20; ++round)
  {
    const std::string folder = dir.file ("spill" + std::to_string (round));
    ASSERT_TRUE (std::filesystem::create_directory (folder));
    const int status = inChild ([&] {
      detail::registerRemovalOnSignal (folder, detail::RemovedKind::Folder);
      std::atomic<bool> started{false};
      std::thread writer ([&] {
        for (long i = 0;; ++i)
        {
          std::ofstream out (folder + "/f" + std::to_string (i));
          out << i;
          if (out.good ())  // a file is in the folder: the handler has something to race with
            started = true;
        }
      });
      while (!started)
        std::this_thread::yield ();
      ::usleep (1000);
      // The folder must hold files when the signal comes, else the round tests an empty folder; exit 4 then
      // (the status check below fails on it).
      if (std::filesystem::is_empty (folder))
        ::_exit (4);
      ::raise (SIGTERM);
      writer.join ();  // not reached
    });
    ASSERT_TRUE (WIFSIGNALED (status) && WTERMSIG (status) == SIGTERM) << "round " << round << ": status " << status;
    EXPECT_FALSE (std::filesystem::exists (folder)) << "round " << round << ": the folder stayed";
    EXPECT_FALSE (std::filesystem::exists (folder + ".removed")) << "round " << round << ": the renamed folder stayed";
  }
}

TEST (SignalCleanup, PathRegisteredBeforeItExists)
{
  const pcl_sparse_test::TempDir dir ("pcl_sparse_signal");
  const std::string folder = dir.file ("not_yet");
  const std::string file = dir.file ("made.tmp");
  const std::string other = dir.file ("other.tmp");  // not registered: must stay
  pcl_sparse_test::writeBytes (other, "kept");
  const int status = inChild ([&] {
    detail::registerRemovalOnSignal (folder, detail::RemovedKind::Folder);  // never made
    detail::registerRemovalOnSignal (file, detail::RemovedKind::File);
    std::ofstream (file) << "partial";
    if (!std::filesystem::exists (file))
      ::_exit (4);  // nothing to remove: the check below would pass without the handler
    ::raise (SIGTERM);
  });
  ASSERT_TRUE (WIFSIGNALED (status) && WTERMSIG (status) == SIGTERM) << "status " << status;
  EXPECT_FALSE (std::filesystem::exists (file));
  EXPECT_FALSE (std::filesystem::exists (folder));
  EXPECT_EQ (pcl_sparse_test::readBytes (other), "kept");
}

// A write into a pipe whose reader quit (a cloud piped into head) ends the process by SIGPIPE: the temporary
// goes as on SIGTERM (it stayed, as big as what was written).
TEST (SignalCleanup, BrokenPipe)
{
  const pcl_sparse_test::TempDir dir ("pcl_sparse_signal");
  const std::string file = dir.file ("piped.tmp");
  const int status = inChild ([&] {
    ::signal (SIGPIPE, SIG_DFL);  // as in a shell; a runner that ignores it would hand that on (and it stays ignored)
    detail::registerRemovalOnSignal (file, detail::RemovedKind::File);
    std::ofstream (file) << "partial";
    if (!std::filesystem::exists (file))
      ::_exit (4);  // nothing to remove: the check below would pass without the handler
    int ends[2];
    if (::pipe (ends) != 0)
      ::_exit (2);
    ::close (ends[0]);  // no reader
    const char byte = 'x';
    (void) ::write (ends[1], &byte, 1);
    ::_exit (3);  // not reached: SIGPIPE ends the process
  });
  ASSERT_TRUE (WIFSIGNALED (status) && WTERMSIG (status) == SIGPIPE) << "status " << status;
  EXPECT_FALSE (std::filesystem::exists (file));
}
