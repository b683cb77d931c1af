#pragma once
/// \file signal_cleanup.h
/// Internal to the library (namespace detail, not API): files and folders that must not outlive this process (spill folders of
/// tiles, the temporaries of atomic writes and streamed clouds) are removed when it is ended by SIGINT,
/// SIGTERM, SIGHUP, SIGQUIT, SIGPIPE or SIGXFSZ (Ctrl-C, kill, mpirun stopping the other ranks after one
/// failed, a pipe whose reader quit, a file over `ulimit -f`), where no destructor
/// runs: they stayed behind, up to a copy of a large input or a streamed cloud of tens of GB. The handler
/// uses only async-signal-safe calls, then gives the signal to the handler that was there before (or
/// the default). A signal the process ignores (nohup) stays ignored.

#include <string>

namespace pcl_sparse
{
  namespace detail
  {
    /// What is removed: one file, or a folder of files (no subfolders) and the folder.
    enum class RemovedKind { File, Folder };

    /// Registers \a path for removal on those signals (at most 32 at once; beyond, left to their owners).
    void registerRemovalOnSignal (const std::string& path, RemovedKind kind);
    /// Forgets \a path (its owner removes or keeps it).
    void unregisterRemovalOnSignal (const std::string& path);

    /// Registers a path for the lifetime of the guard.
    class RemovedOnSignal
    {
    public:
      RemovedOnSignal (std::string path, RemovedKind kind) : path_ (std::move (path)) { registerRemovalOnSignal (path_, kind); }
      ~RemovedOnSignal () { unregisterRemovalOnSignal (path_); }
      RemovedOnSignal (const RemovedOnSignal&) = delete;
      RemovedOnSignal& operator= (const RemovedOnSignal&) = delete;

    private:
      std::string path_;
    };
  } // namespace detail
} // namespace pcl_sparse
