#pragma once
/// \file atomic_write.h
/// Writing output files so that a failed or interrupted write never leaves a partial file behind.

#include <cstddef>
#include <functional>
#include <string>

namespace pcl_sparse
{
  /// Calls \a write with a temporary path next to \a path, then renames it onto \a path (atomic on
  /// POSIX file systems). If \a write throws or returns false, the temporary file is removed and
  /// pcl_sparse::Error is thrown naming \a path; \a path itself is never touched in that case.
  void
  writeFileAtomically (const std::string& path, const std::function<bool (const std::string& temporary_path)>& write);

  /// Writes the \a size bytes at \a data to \a path in one binary write, through writeFileAtomically (so
  /// the same guarantees and errors).
  void
  writeBytesAtomically (const std::string& path, const void* data, std::size_t size);
} // namespace pcl_sparse
