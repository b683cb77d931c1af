#pragma once
/// \file spill_cleanup.h
/// Internal to src/tiles: the spill directories alive in this process are removed when it is ended by
/// SIGINT, SIGTERM or SIGHUP (Ctrl-C, kill, mpirun stopping the other ranks after one failed), where no
/// destructor runs and they would stay in $TMPDIR, up to a copy of a large input. The handler uses only
/// async-signal-safe calls, then gives the signal to the handler that was there before (or the default).

#include <string>

namespace pcl_sparse
{
  namespace tiles_detail
  {
    /// Registers \a path (a directory of files, no subdirectories) for removal on those signals.
    void registerSpillDirectory (const std::string& path);
    /// Forgets \a path (the destructor removes it).
    void unregisterSpillDirectory (const std::string& path);
  } // namespace tiles_detail
} // namespace pcl_sparse
