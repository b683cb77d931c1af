#include <pcl_sparse/common/signal_cleanup.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>

#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace pcl_sparse
{
  namespace detail
  {
    namespace
    {
      constexpr std::size_t kSlots = 32;       // paths registered at once
      constexpr std::size_t kPathBytes = 4096;
      // SIGPIPE (a cloud piped into a reader that quit), SIGXFSZ (ulimit -f) and SIGQUIT end a process as surely as
      // Ctrl-C: each left a temporary of the size written so far.
      constexpr std::array<int, 6> kSignals = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ};

      struct Slot
      {
        std::atomic<bool> used{false};
        bool folder = false;
        char path[kPathBytes];
      };
      std::array<Slot, kSlots> slots;
      std::mutex registry;                        // registration only; the handler reads `used`
      std::size_t registered = 0;
      struct sigaction previous[kSignals.size ()];

      /// Unlinks the files of one directory, then the directory (async-signal-safe calls only); false with
      /// errno set when the directory stays.
      bool
      removeDirectory (const char* path)
      {
        const int fd = ::open (path, O_RDONLY | O_DIRECTORY);
        if (fd >= 0)
        {
          alignas (8) char buffer[4096];
          for (;;)
          {
            const long bytes = ::syscall (SYS_getdents64, fd, buffer, sizeof (buffer));
            if (bytes <= 0)
              break;
            for (long at = 0; at < bytes;)
            {
              const auto* entry = reinterpret_cast<const struct dirent64*> (buffer + at);
              if (std::strcmp (entry->d_name, ".") != 0 && std::strcmp (entry->d_name, "..") != 0)
                ::unlinkat (fd, entry->d_name, 0);
              at += entry->d_reclen;
            }
          }
          ::close (fd);
        }
        return ::rmdir (path) == 0;
      }

      /// Removes a folder other threads may still be adding files to (a rank's spill folder when mpirun
      /// stops it): renamed first, so that files opened by its old path can no longer appear in it, then
      /// emptied, listing it again while rmdir finds a file that came in before the rename.
      void
      removeFolderInUse (const char* path)
      {
        constexpr char kSuffix[] = ".removed";
        char moved[kPathBytes + sizeof (kSuffix)];
        const std::size_t length = std::strlen (path);
        std::memcpy (moved, path, length);
        std::memcpy (moved + length, kSuffix, sizeof (kSuffix));
        const char* folder = ::rename (path, moved) == 0 ? moved : path;
        for (int attempt = 0; attempt < 100 && !removeDirectory (folder) && (errno == ENOTEMPTY || errno == EEXIST);
             ++attempt)
          ;
      }

      void
      onSignal (int signal)
      {
        const int saved_errno = errno;  // restored for the previous handler and the interrupted code
        for (Slot& slot : slots)
          if (slot.used.load ())
          {
            if (slot.folder)
              removeFolderInUse (slot.path);
            else
              ::unlink (slot.path);
          }
        // The handler that was there before (the default: the process ends by this signal) takes it.
        for (std::size_t k = 0; k < kSignals.size (); ++k)
          if (kSignals[k] == signal)
            ::sigaction (signal, &previous[k], nullptr);
        errno = saved_errno;
        ::raise (signal);
      }
    } // namespace

    void
    registerRemovalOnSignal (const std::string& path, RemovedKind kind)
    {
      if (path.size () >= kPathBytes)
        return;  // left to the owner
      const std::lock_guard<std::mutex> lock (registry);
      for (Slot& slot : slots)
        if (!slot.used.load ())
        {
          std::memcpy (slot.path, path.c_str (), path.size () + 1);
          slot.folder = kind == RemovedKind::Folder;
          slot.used.store (true);
          if (registered++ == 0)
          {
            struct sigaction action {};
            action.sa_handler = onSignal;
            sigemptyset (&action.sa_mask);
            for (std::size_t k = 0; k < kSignals.size (); ++k)
            {
              ::sigaction (kSignals[k], &action, &previous[k]);
              if (previous[k].sa_handler == SIG_IGN)  // an ignored signal (nohup) stays ignored: the run goes on
                ::sigaction (kSignals[k], &previous[k], nullptr);
            }
          }
          return;
        }
    }

    void
    unregisterRemovalOnSignal (const std::string& path)
    {
      const std::lock_guard<std::mutex> lock (registry);
      for (Slot& slot : slots)
        if (slot.used.load () && path == slot.path)
        {
          slot.used.store (false);
          if (--registered == 0)
            for (std::size_t k = 0; k < kSignals.size (); ++k)
              ::sigaction (kSignals[k], &previous[k], nullptr);
          return;
        }
    }
  } // namespace detail
} // namespace pcl_sparse
