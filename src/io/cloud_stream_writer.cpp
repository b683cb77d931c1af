#include <pcl_sparse/io/cloud_stream_writer.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/huge_pages.h>
#include <pcl_sparse/common/signal_cleanup.h>

#include "mesh_readers.h"
#include "point_normal_records.h"

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <memory>
#include <fcntl.h>
#include <limits>
#include <mutex>
#include <thread>
#include <unistd.h>
#include <vector>

namespace pcl_sparse
{
  namespace
  {
    /// Writes all of \a bytes to \a fd; returns an empty string or the reason of the failure.
    std::string
    writeAll (int fd, const std::string& bytes)
    {
      const char* data = bytes.data ();
      std::size_t left = bytes.size ();
      while (left > 0)
      {
        const ssize_t n = ::write (fd, data, left);
        if (n < 0 && errno == EINTR)
          continue;
        if (n <= 0)
          return n < 0 ? std::strerror (errno) : "nothing written";
        data += n;
        left -= static_cast<std::size_t> (n);
      }
      return std::string ();
    }

    /// The header savePointNormalCloud's PCD writer (PCL's) gives the whole cloud of \a total points.
    std::string
    pcdHeader (std::size_t total, bool doubles, CloudExtraField extra)
    {
      if (!doubles)
      {
        const int count = static_cast<int> (total);
        const std::string header =
          extra == CloudExtraField::Colour      ? pcl::PCDWriter::generateHeader (pcl::PointCloud<pcl::PointXYZRGBNormal> (), count)
          : extra == CloudExtraField::Intensity ? pcl::PCDWriter::generateHeader (pcl::PointCloud<pcl::PointXYZINormal> (), count)
                                                : pcl::PCDWriter::generateHeader (pcl::PointCloud<pcl::PointNormal> (), count);
        return header + "DATA binary\n";
      }
      // As the double-position blob of savePointNormalCloud, without its data.
      const pcl::PCLPointCloud2 blob = io_detail::doublePositionLayout (total, true, extra);
      pcl::PCDWriter writer;
      return writer.generateHeaderBinary (blob, Eigen::Vector4f::Zero (), Eigen::Quaternionf::Identity ()) +
             "DATA binary\n";
    }
  } // namespace

  struct PointNormalStreamWriter::Impl
  {
    std::string path, temporary;
    std::unique_ptr<detail::RemovedOnSignal> on_signal;  // the temporary, tens of GB, stayed after Ctrl-C
    std::size_t total = 0, count = 0;
    bool binary = true, doubles = false, ply = false;
    CloudExtraField extra = CloudExtraField::None;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero ();
    int fd = -1;
    bool finished = false;
    /// Size of the whole file (0: what was written), for PCL's PCLPointCloud2 writer's zero tail.
    std::size_t file_size = 0;

    // The writing thread takes one formatted block at a time; the caller formats the next meanwhile.
    std::mutex mutex;
    std::condition_variable changed;
    std::string pending;          ///< a block waiting to be written (valid when has_pending)
    bool has_pending = false;
    bool writing = false;         ///< the thread is writing a block
    bool closing = false;
    std::string failure;          ///< the first write failure
    std::vector<std::string> spare;  ///< written buffers, reused for the next blocks
    std::thread thread;

    /// Bytes of the file written so far, and where the block before the last starts and ends.
    std::size_t written_bytes = 0, previous_begin = 0, previous_end = 0;

    /// Files up to this size are left to the page cache, as any writer leaves them (the tool returns
    /// before the disk has them); beyond it the writer flushes behind itself (flushBehind).
    static constexpr std::size_t cached_bytes = std::size_t (256) << 20;

    /// After a block is written at [begin, end) beyond cached_bytes: starts its writeback at once and
    /// waits for the one before, then drops that one from the page cache. The disk is kept busy instead of
    /// waiting for the kernel's dirty threshold, the dirty data stays two blocks (a 200M-point file would
    /// otherwise fill gigabytes of page cache and then throttle every writer on the machine), and the
    /// file is on the disk, bar two blocks, when the tool returns. Advisory: the bytes do not depend on it.
    void
    flushBehind (std::size_t begin, std::size_t end)
    {
      if (end <= cached_bytes)
        return;
#ifdef __linux__
      if (previous_end == 0)
        begin = 0;  // the first flush takes the cached start of the file with it
      ::sync_file_range (fd, static_cast<off64_t> (begin), static_cast<off64_t> (end - begin), SYNC_FILE_RANGE_WRITE);
      if (previous_end > previous_begin)
      {
        ::sync_file_range (fd, static_cast<off64_t> (previous_begin), static_cast<off64_t> (previous_end - previous_begin),
                           SYNC_FILE_RANGE_WAIT_BEFORE | SYNC_FILE_RANGE_WRITE | SYNC_FILE_RANGE_WAIT_AFTER);
        ::posix_fadvise (fd, static_cast<off_t> (previous_begin), static_cast<off_t> (previous_end - previous_begin),
                         POSIX_FADV_DONTNEED);
      }
#endif
      previous_begin = begin;
      previous_end = end;
    }

    void
    run ()
    {
      std::unique_lock<std::mutex> lock (mutex);
      for (;;)
      {
        changed.wait (lock, [&] { return has_pending || closing; });
        if (!has_pending)
          return;
        std::string buffer = std::move (pending);
        has_pending = false;
        writing = true;
        const bool failed = !failure.empty ();
        lock.unlock ();
        const std::string error = failed ? std::string () : writeAll (fd, buffer);
        if (!failed && error.empty ())
        {
          flushBehind (written_bytes, written_bytes + buffer.size ());
          written_bytes += buffer.size ();
        }
        lock.lock ();
        if (!error.empty () && failure.empty ())
          failure = error;
        writing = false;
        buffer.clear ();
        spare.push_back (std::move (buffer));
        changed.notify_all ();
      }
    }

    /// Stops the thread after the blocks given so far are written.
    void
    stop ()
    {
      if (!thread.joinable ())
        return;
      {
        std::lock_guard<std::mutex> lock (mutex);
        closing = true;
      }
      changed.notify_all ();
      thread.join ();
    }

    [[noreturn]] void
    fail (const std::string& reason)
    {
      throw Error (path + ": could not write the file (" + reason + ")");
    }
  };

  bool
  PointNormalStreamWriter::supports (const std::string& path, bool binary)
  {
    const std::string extension = io_detail::lowerCaseExtension (path);
    return extension == ".ply" || (extension == ".pcd" && binary);
  }

  PointNormalStreamWriter::PointNormalStreamWriter (const std::string& path, std::size_t total, bool binary,
                                                    const Eigen::Vector3d& offset, CloudExtraField extra)
    : impl_ (std::make_unique<Impl> ())
  {
    Impl& w = *impl_;
    if (!supports (path, binary))
      throw Error (path + ": a streamed cloud is written as .pcd (binary) or .ply, not '" +
                   io_detail::lowerCaseExtension (path) + (binary ? "'" : "' ascii"));
    if (total > static_cast<std::size_t> (std::numeric_limits<int>::max () - 1))
      throw Error (path + ": too many points for one file (" + std::to_string (total) + ")");
    w.path = path;
    w.temporary = temporaryPathFor (path);
    w.total = total;
    w.binary = binary;
    w.doubles = !offset.isZero (0.0);
    w.offset = offset;
    w.extra = extra;
    const bool pcd = io_detail::lowerCaseExtension (path) == ".pcd";
    w.ply = !pcd;
    const std::string header =
      pcd ? pcdHeader (total, w.doubles, extra) : io_detail::plyHeader (total, binary, w.doubles, extra);
    // Registered before the file exists, so a signal in between does not leave it behind.
    w.on_signal = std::make_unique<detail::RemovedOnSignal> (w.temporary, detail::RemovedKind::File);
    w.fd = ::open (w.temporary.c_str (), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (w.fd < 0)
      w.fail (std::strerror (errno));
    const std::string error = writeAll (w.fd, header);
    w.written_bytes = header.size ();
    if (!error.empty ())
    {
      ::close (w.fd);
      std::remove (w.temporary.c_str ());
      w.fail (error);
    }
    // PCL's writer of a PCLPointCloud2 (double x y z) stretches its file to a page plus the data before
    // mapping it: after a short header, the file ends in zeros up to that size.
    if (pcd && w.doubles)
      w.file_size = std::max (header.size (), static_cast<std::size_t> (::getpagesize ())) +
                    total * io_detail::binaryRecordSize (true, extra);
    w.thread = std::thread ([&w] { w.run (); });
  }

  PointNormalStreamWriter::~PointNormalStreamWriter ()
  {
    Impl& w = *impl_;
    w.stop ();
    if (w.fd >= 0)
      ::close (w.fd);
    if (!w.finished)
      std::remove (w.temporary.c_str ());
  }

  template <typename PointT>
  void
  PointNormalStreamWriter::write (const pcl::PointCloud<PointT>& block)
  {
    Impl& w = *impl_;
    if (cloudExtraFieldOf<PointT> () != w.extra)
      throw Error (w.path + ": the blocks' point type does not match the writer's fields");
    if (w.finished)
      throw Error (w.path + ": the file is already finished");
    if (block.size () > w.total - w.count)
      throw Error (w.path + ": more points than the " + std::to_string (w.total) + " announced");
    std::string buffer;
    {
      // At most one block waits while another is written: memory stays two formatted blocks.
      std::unique_lock<std::mutex> lock (w.mutex);
      w.changed.wait (lock, [&] { return !w.has_pending; });
      if (!w.failure.empty ())
        w.fail (w.failure);
      if (!w.spare.empty ())
      {
        buffer = std::move (w.spare.back ());
        w.spare.pop_back ();
      }
    }
    if (w.binary)
    {
      const std::size_t record = io_detail::binaryRecordSize (w.doubles, w.extra, w.ply);
      resizeOnHugePages (buffer, block.size () * record);  // tens of MB a block, written once through
      char* out = &buffer[0];
      for (const PointT& point : block)
      {
        io_detail::writeBinaryRecord (point, w.doubles, w.offset, out, w.ply);
        out += record;
      }
    }
    else
    {
      buffer.clear ();
      for (const PointT& point : block)
        io_detail::appendPlyVertex (buffer, point, false, w.doubles, w.offset);
    }
    std::unique_lock<std::mutex> lock (w.mutex);
    w.pending = std::move (buffer);
    w.has_pending = true;
    w.count += block.size ();
    lock.unlock ();
    w.changed.notify_all ();
  }

  void
  PointNormalStreamWriter::finish ()
  {
    Impl& w = *impl_;
    if (w.finished)
      return;
    w.stop ();
    const int fd = w.fd;
    w.fd = -1;
    if (w.failure.empty () && w.count == w.total && w.file_size > 0 && ::ftruncate (fd, static_cast<off_t> (w.file_size)) != 0)
      w.failure = std::strerror (errno);
    const bool closed = ::close (fd) == 0;
    const std::string close_error = closed ? std::string () : std::strerror (errno);
    if (!w.failure.empty ())
      w.fail (w.failure);
    if (!closed)
      w.fail (close_error);
    if (w.count != w.total)
      w.fail (std::to_string (w.count) + " points written, " + std::to_string (w.total) + " announced");
    if (std::rename (w.temporary.c_str (), w.path.c_str ()) != 0)
      w.fail (std::strerror (errno));
    w.finished = true;
    w.on_signal.reset ();
  }

  std::size_t
  PointNormalStreamWriter::written () const
  {
    return impl_->count;
  }

  template void PointNormalStreamWriter::write (const pcl::PointCloud<pcl::PointNormal>&);
  template void PointNormalStreamWriter::write (const pcl::PointCloud<pcl::PointXYZRGBNormal>&);
  template void PointNormalStreamWriter::write (const pcl::PointCloud<pcl::PointXYZINormal>&);
} // namespace pcl_sparse
