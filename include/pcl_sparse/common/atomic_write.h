#pragma once
/// \file atomic_write.h
/// Writing output files so that a failed or interrupted write never leaves a partial file behind.

#include <cstddef>
#include <functional>
#include <string>

namespace pcl_sparse
{
  /// \brief The temporary file a write of \a path goes through: in the same folder (so the rename stays on
  /// one file system), named after \a path's file name, ".tmp" and the process id (concurrent writers do
  /// not share it). A file name too long for that suffix (file names end at 255 bytes) keeps its first
  /// bytes and a hash of the whole name instead, so any name the file system takes can be written.
  std::string
  temporaryPathFor (const std::string& path);

  /// Writes a file through a temporary one: calls \a write with a temporary path next to \a path, then
  /// renames it onto \a path (atomic on POSIX file systems).
  /// \param[in] path   the file to write
  /// \param[in] write  writes the content to the path it is given; returns false on failure
  /// \throws pcl_sparse::Error naming \a path if \a write throws or returns false (the temporary file is
  ///         removed and \a path is not touched)
  void
  writeFileAtomically (const std::string& path, const std::function<bool (const std::string& temporary_path)>& write);

  /// Writes the \a size bytes at \a data to \a path in one binary write, through writeFileAtomically (so
  /// the same guarantees and errors).
  void
  writeBytesAtomically (const std::string& path, const void* data, std::size_t size);
} // namespace pcl_sparse
