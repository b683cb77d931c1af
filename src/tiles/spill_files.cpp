#include "spill_files.h"

#include <pcl_sparse/common/signal_cleanup.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <system_error>

#include <sys/stat.h>  // mkdir
#include <unistd.h>    // getpid

namespace pcl_sparse
{
  namespace tiles_detail
  {
    SpillDirectory::SpillDirectory (const std::string& parent)
    {
      std::string base = parent;
      if (base.empty ())
      {
        std::error_code error;
        base = std::filesystem::temp_directory_path (error).string ();
        if (error)
          base = "/tmp";
      }
      // Registered before it exists, so that a signal never meets a folder it does not know (mkdtemp, then
      // registering, could leave the folder behind when mpirun stopped a rank between the two). The pid and a
      // counter make the name unique among live processes; a taken name (EEXIST: left by a dead process
      // with this pid) tries the next.
      static std::atomic<unsigned> counter{0};
      for (;;)
      {
        path_ = base + "/pcl_sparse_spill_" + std::to_string (::getpid ()) + "_" + std::to_string (counter++);
        detail::registerRemovalOnSignal (path_, detail::RemovedKind::Folder);
        if (::mkdir (path_.c_str (), 0700) == 0)
          return;
        const int error = errno;
        detail::unregisterRemovalOnSignal (path_);
        if (error != EEXIST)
          throw Error (base + ": cannot make a temporary directory for the tiles' spill files (" +
                       std::strerror (error) + ")");
      }
    }

    SpillDirectory::~SpillDirectory ()
    {
      detail::unregisterRemovalOnSignal (path_);
      std::error_code ignored;
      std::filesystem::remove_all (path_, ignored);
    }

    std::string
    SpillDirectory::tileFile (std::size_t t) const
    {
      return path_ + "/tile_" + std::to_string (t) + ".bin";
    }

    void
    SpillDirectory::clear () const
    {
      std::error_code error;
      for (const auto& entry : std::filesystem::directory_iterator (path_, error))
        std::filesystem::remove (entry.path (), error);
    }

    namespace
    {
      template <typename T>
      void
      put (char*& out, const T& value)
      {
        std::memcpy (out, &value, sizeof (T));
        out += sizeof (T);
      }

      template <typename T>
      T
      get (const char*& in)
      {
        T value;
        std::memcpy (&value, in, sizeof (T));
        in += sizeof (T);
        return value;
      }
    } // namespace

    SpillRecord::SpillRecord (const ScanCloud& like, bool float_vectors, bool narrow_index)
    : normals_ (!like.normals.empty ()), viewpoints_ (!like.viewpoints.empty ()), colors_ (!like.colors.empty ()),
      intensities_ (!like.intensities.empty ()), float_vectors_ (float_vectors), narrow_index_ (narrow_index)
    {
      const std::size_t vector = float_vectors ? 3 * sizeof (float) : 3 * sizeof (double);
      bytes_ = (narrow_index ? sizeof (std::uint32_t) : sizeof (std::uint64_t)) + vector + (normals_ ? vector : 0) +
               (viewpoints_ ? vector : 0) + (colors_ ? sizeof (std::uint32_t) : 0) + (intensities_ ? sizeof (float) : 0);
    }

    bool
    SpillRecord::isFloat (const ScanCloud& scan, std::size_t i)
    {
      const auto exact = [] (const Eigen::Vector3d& v) {
        for (int k = 0; k < 3; ++k)
          if (!std::isnan (v[k]) && static_cast<double> (static_cast<float> (v[k])) != v[k])
            return false;
        return true;
      };
      return exact (scan.positions[i]) && (scan.normals.empty () || exact (scan.normals[i])) &&
             (scan.viewpoints.empty () || exact (scan.viewpoints[i]));
    }

    void
    SpillRecord::putVector (char*& out, const Eigen::Vector3d& v) const
    {
      for (int k = 0; k < 3; ++k)
        if (float_vectors_)
          put (out, static_cast<float> (v[k]));
        else
          put (out, v[k]);
    }

    Eigen::Vector3d
    SpillRecord::getVector (const char*& in) const
    {
      Eigen::Vector3d v;
      for (int k = 0; k < 3; ++k)
        v[k] = float_vectors_ ? static_cast<double> (get<float> (in)) : get<double> (in);
      return v;
    }

    void
    SpillRecord::encode (const ScanCloud& scan, std::size_t i, char* out) const
    {
      if (narrow_index_)
        put (out, static_cast<std::uint32_t> (scan.indices[i]));
      else
        put (out, static_cast<std::uint64_t> (scan.indices[i]));
      putVector (out, scan.positions[i]);
      if (normals_)
        putVector (out, scan.normals[i]);
      if (viewpoints_)
        putVector (out, scan.viewpoints[i]);
      if (colors_)
        put (out, scan.colors[i]);
      if (intensities_)
        put (out, scan.intensities[i]);
    }

    void
    SpillRecord::decode (const char* in, ScanCloud& scan) const
    {
      scan.indices.push_back (narrow_index_ ? static_cast<std::size_t> (get<std::uint32_t> (in))
                                            : static_cast<std::size_t> (get<std::uint64_t> (in)));
      scan.positions.push_back (getVector (in));
      if (normals_)
        scan.normals.push_back (getVector (in));
      if (viewpoints_)
        scan.viewpoints.push_back (getVector (in));
      if (colors_)
        scan.colors.push_back (get<std::uint32_t> (in));
      if (intensities_)
        scan.intensities.push_back (get<float> (in));
    }

    std::size_t
    SpillRecord::index (const char* in) const
    {
      return narrow_index_ ? static_cast<std::size_t> (get<std::uint32_t> (in)) : static_cast<std::size_t> (get<std::uint64_t> (in));
    }

    Eigen::Vector3d
    SpillRecord::position (const char* in) const
    {
      in += narrow_index_ ? sizeof (std::uint32_t) : sizeof (std::uint64_t);
      return getVector (in);
    }

    SpillWriter::SpillWriter (const SpillDirectory& directory, std::size_t tiles, std::size_t record_bytes,
                              std::size_t buffer_bytes)
    : directory_ (directory), record_bytes_ (record_bytes), buffers_ (tiles), records_ (tiles, 0)
    {
      capacity_ = std::max<std::size_t> (1, buffer_bytes / std::max<std::size_t> (1, tiles) / record_bytes) * record_bytes;
    }

    void
    SpillWriter::append (std::size_t t, const char* record)
    {
      std::vector<char>& buffer = buffers_[t];
      if (buffer.capacity () < capacity_)
        buffer.reserve (capacity_);  // on first use: tiles that get nothing cost nothing
      buffer.insert (buffer.end (), record, record + record_bytes_);
      ++records_[t];
      if (buffer.size () >= capacity_)
        flush (t);
    }

    void
    SpillWriter::flush ()
    {
      for (std::size_t t = 0; t < buffers_.size (); ++t)
        flush (t);
    }

    void
    SpillWriter::flush (std::size_t t)
    {
      std::vector<char>& buffer = buffers_[t];
      if (buffer.empty ())
        return;
      const std::string path = directory_.tileFile (t);
      std::FILE* file = std::fopen (path.c_str (), "ab");
      if (!file)
        throw Error (path + ": cannot write the spill file (" + std::strerror (errno) + ")");
      const bool written = std::fwrite (buffer.data (), 1, buffer.size (), file) == buffer.size ();
      const int saved = errno;
      const bool closed = std::fclose (file) == 0;
      if (!written || !closed)
        throw Error (path + ": cannot write the spill file (" + std::strerror (written ? errno : saved) + ")");
      buffer.clear ();
    }
  } // namespace tiles_detail
} // namespace pcl_sparse
