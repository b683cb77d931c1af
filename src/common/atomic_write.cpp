#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/signal_cleanup.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <unistd.h>

namespace pcl_sparse
{
  std::string
  temporaryPathFor (const std::string& path)
  {
    constexpr std::size_t kMaxFileName = 255;  // NAME_MAX of Linux's file systems, in bytes
    const std::string suffix = ".tmp" + std::to_string (::getpid ());
    const std::size_t name_start = path.find_last_of ('/') + 1;  // 0 without a folder
    const std::size_t name_length = path.size () - name_start;
    if (name_length + suffix.size () <= kMaxFileName)
      return path + suffix;
    char hash[17];
    std::snprintf (hash, sizeof (hash), "%016zx", std::hash<std::string> () (path.substr (name_start)));
    const std::string tail = std::string (".") + hash + suffix;
    return path.substr (0, name_start + kMaxFileName - tail.size ()) + tail;
  }

  void
  writeFileAtomically (const std::string& path, const std::function<bool (const std::string&)>& write)
  {
    const std::string temporary = temporaryPathFor (path);
    const detail::RemovedOnSignal on_signal (temporary, detail::RemovedKind::File);  // Ctrl-C left it behind
    bool ok = false;
    errno = 0;  // what the writer's last failing call sets (ENOSPC on a full disk) is the cause given below
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
      const int cause = errno;
      std::remove (temporary.c_str ());
      throw Error (path + ": could not write the file" + (cause != 0 ? " (" + std::string (std::strerror (cause)) + ")" : ""));
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
