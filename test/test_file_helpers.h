#pragma once
// Small file helpers shared by the tests that write their own input files.

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>

namespace pcl_sparse_test
{
  /// A fresh temporary directory, removed with its files at the end.
  class TempDir
  {
  public:
    explicit TempDir (const std::string& prefix = "pcl_sparse_test")
    {
      std::string pattern = "/tmp/" + prefix + "_XXXXXX";
      if (!::mkdtemp (pattern.data ()))
        throw std::runtime_error ("mkdtemp failed");
      path_ = pattern;
    }
    ~TempDir () { std::system (("rm -rf '" + path_ + "'").c_str ()); }
    TempDir (const TempDir&) = delete;
    TempDir& operator= (const TempDir&) = delete;

    std::string file (const std::string& name) const { return path_ + "/" + name; }

  private:
    std::string path_;
  };

  inline void
  writeBytes (const std::string& path, const std::string& bytes)
  {
    std::ofstream out (path, std::ios::binary);
    out.write (bytes.data (), static_cast<std::streamsize> (bytes.size ()));
  }

  inline std::string
  readBytes (const std::string& path)
  {
    std::ifstream in (path, std::ios::binary);
    return std::string (std::istreambuf_iterator<char> (in), std::istreambuf_iterator<char> ());
  }

  /// Appends a value in little- or big-endian byte order.
  template <typename T>
  void
  put (std::string& out, T value, bool big_endian = false)
  {
    char bytes[sizeof (T)];
    std::memcpy (bytes, &value, sizeof (T));
    if (big_endian)
      std::reverse (bytes, bytes + sizeof (T));
    out.append (bytes, sizeof (T));
  }

  /// Runs \a shell_command (redirections included) through the shell; returns its exit code (-1 if it did
  /// not exit normally), \a out receives what it writes to stdout.
  inline int
  runShell (const std::string& shell_command, std::string& out)
  {
    out.clear ();
    std::unique_ptr<FILE, int (*) (FILE*)> pipe (popen (shell_command.c_str (), "r"), pclose);
    if (!pipe)
      return -1;
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread (buffer, 1, sizeof (buffer), pipe.get ())) > 0)
      out.append (buffer, n);
    const int status = pclose (pipe.release ());
    return WIFEXITED (status) ? WEXITSTATUS (status) : -1;
  }

  /// Runs \a command through the shell; returns its exit code (-1 if it did not exit normally), \a out
  /// receives its stdout and stderr.
  inline int
  runCommand (const std::string& command, std::string& out)
  {
    return runShell (command + " 2>&1", out);
  }

  /// What interruptOnceReady saw.
  struct InterruptedRun
  {
    bool ready = false;  ///< \a ready held before the program ended or the 20 s ran out
    int status = 0;      ///< waitpid's status
  };

  /// Starts \a argv (program path first) with \a environment added (NAME=VALUE entries), waits until
  /// \a ready () holds (at most 20 s), lets \a settle_us more pass (past the instant between making a
  /// file and registering it for removal), sends SIGINT and waits for the program's end.
  template <typename Ready>
  InterruptedRun
  interruptOnceReady (const std::vector<std::string>& argv, Ready ready, const std::vector<std::string>& environment = {},
                      int settle_us = 20000)
  {
    const pid_t pid = ::fork ();
    if (pid == 0)
    {
      for (const std::string& entry : environment)
        ::putenv (const_cast<char*> (entry.c_str ()));
      std::vector<char*> args;
      for (const std::string& a : argv)
        args.push_back (const_cast<char*> (a.c_str ()));
      args.push_back (nullptr);
      ::execv (args[0], args.data ());
      ::_exit (127);
    }
    InterruptedRun run;
    for (int wait = 0; wait < 2000 && !run.ready; ++wait)
    {
      run.ready = ready ();
      if (!run.ready)
        ::usleep (10000);
    }
    ::usleep (settle_us);
    ::kill (pid, SIGINT);
    ::waitpid (pid, &run.status, 0);
    return run;
  }

  /// Peak resident memory of this process in kB (VmHWM), after \a reset starts it again from the current one;
  /// -1 where /proc cannot do it.
  inline long
  peakResidentKb (bool reset)
  {
    if (reset && !(std::ofstream ("/proc/self/clear_refs") << "5" << std::flush))
      return -1;
    std::ifstream status ("/proc/self/status");
    for (std::string line; std::getline (status, line);)
      if (line.rfind ("VmHWM:", 0) == 0)
        return std::stol (line.substr (6));
    return -1;
  }
} // namespace pcl_sparse_test
