#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/signal_cleanup.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace pcl_sparse
{
  void
  writeFileAtomically (const std::string& path, const std::function<bool (const std::string&)>& write)
  {
    // Same directory as the target, so rename() stays within one file system; the pid keeps
    // concurrent writers from sharing a temporary.
    const std::string temporary = path + ".tmp" + std::to_string (::getpid ());
    const detail::RemovedOnSignal on_signal (temporary, detail::RemovedKind::File);  // Ctrl-C left it behind
    bool ok = false;
    try
    {
      ok = write (temporary);
    }
    catch (...)
    {
      std::remove (temporary.c_str ());
      throw;
    }
    if (!ok)
    {
      std::remove (temporary.c_str ());
      throw Error (path + ": could not write the file");
    }
    if (std::rename (temporary.c_str (), path.c_str ()) != 0)
    {
      const std::string reason = std::strerror (errno);
      std::remove (temporary.c_str ());
      throw Error (path + ": could not write the file (" + reason + ")");
    }
  }

  void
  writeBytesAtomically (const std::string& path, const void* data, std::size_t size)
  {
    writeFileAtomically (path, [data, size] (const std::string& temporary) {
      std::FILE* file = std::fopen (temporary.c_str (), "wb");
      if (!file)
        return false;
      const bool written = size == 0 || std::fwrite (data, 1, size, file) == size;
      return std::fclose (file) == 0 && written;
    });
  }
} // namespace pcl_sparse
