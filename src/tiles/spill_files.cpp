#include "spill_files.h"

#include <filesystem>
#include <system_error>

#include <stdlib.h>  // mkdtemp

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
      std::string pattern = base + "/pcl_sparse_spill_XXXXXX";
      if (!::mkdtemp (&pattern[0]))
        throw Error (base + ": cannot make a temporary directory for the tiles' spill files (" +
                     std::strerror (errno) + ")");
      path_ = pattern;
    }

    SpillDirectory::~SpillDirectory ()
    {
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

      void
      putVector (char*& out, const Eigen::Vector3d& v)
      {
        for (int k = 0; k < 3; ++k)
          put (out, v[k]);
      }

      Eigen::Vector3d
      getVector (const char*& in)
      {
        Eigen::Vector3d v;
        for (int k = 0; k < 3; ++k)
          v[k] = get<double> (in);
        return v;
      }
    } // namespace

    SpillRecord::SpillRecord (const ScanCloud& like)
    : normals_ (!like.normals.empty ()), viewpoints_ (!like.viewpoints.empty ()), colors_ (!like.colors.empty ()),
      intensities_ (!like.intensities.empty ())
    {
      bytes_ = sizeof (std::uint64_t) + 3 * sizeof (double) + (normals_ ? 3 * sizeof (double) : 0) +
               (viewpoints_ ? 3 * sizeof (double) : 0) + (colors_ ? sizeof (std::uint32_t) : 0) +
               (intensities_ ? sizeof (float) : 0);
    }

    void
    SpillRecord::encode (const ScanCloud& scan, std::size_t i, char* out) const
    {
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
      scan.indices.push_back (static_cast<std::size_t> (get<std::uint64_t> (in)));
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

    Eigen::Vector3d
    SpillRecord::position (const char* in)
    {
      in += sizeof (std::uint64_t);
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
