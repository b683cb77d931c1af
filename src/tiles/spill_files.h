#pragma once
/// \file spill_files.h
/// Internal to src/tiles: the temporary files a SpilledTileSource writes, one per tile, in a directory of
/// its own that goes away with it; fixed-size point records appended through bounded buffers.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  namespace tiles_detail
  {
    /// A fresh directory made in \a parent ("" for the system's temporary directory, $TMPDIR), removed with
    /// everything in it by the destructor.
    class SpillDirectory
    {
    public:
      explicit SpillDirectory (const std::string& parent);
      ~SpillDirectory ();
      SpillDirectory (const SpillDirectory&) = delete;
      SpillDirectory& operator= (const SpillDirectory&) = delete;

      /// The directory's path.
      const std::string&
      path () const
      {
        return path_;
      }

      /// The path of tile \a t's file in it.
      std::string
      tileFile (std::size_t t) const;

      /// Removes every file in the directory (keeps the directory).
      void
      clear () const;

    private:
      std::string path_;
    };

    /// One point of a scan as a spill record: file index, position, then the attributes the scan has
    /// (normals, viewpoints, colour, intensity), so that a record gives the point back exactly. Compact where
    /// that loses nothing: vectors as float when every value is a float (float fields of the file), the
    /// index in 4 bytes when the file has fewer than 2^32 points.
    class SpillRecord
    {
    public:
      /// The record layout for points with the attributes of \a like (a chunk of the input).
      SpillRecord (const ScanCloud& like, bool float_vectors, bool narrow_index);

      /// True if every coordinate of the vectors of point \a i of \a scan (position, normal, viewpoint)
      /// is a float (or NaN).
      static bool
      isFloat (const ScanCloud& scan, std::size_t i);

      /// Bytes of one record.
      std::size_t
      bytes () const
      {
        return bytes_;
      }

      /// Writes point \a i of \a scan (which has the attributes of the layout) at \a out.
      void
      encode (const ScanCloud& scan, std::size_t i, char* out) const;

      /// Appends the point at \a in to \a scan (positions, attributes, indices).
      void
      decode (const char* in, ScanCloud& scan) const;

      /// The file index of the record at \a in.
      std::size_t
      index (const char* in) const;

      /// The position of the record at \a in.
      Eigen::Vector3d
      position (const char* in) const;

    private:
      void
      putVector (char*& out, const Eigen::Vector3d& v) const;
      Eigen::Vector3d
      getVector (const char*& in) const;

      bool normals_, viewpoints_, colors_, intensities_, float_vectors_, narrow_index_;
      std::size_t bytes_;
    };

    /// Appends records to the tile files through one buffer per tile: each holds about buffer_bytes / tiles
    /// (at least one record) and is written out (the file opened, appended to and closed) when full, so
    /// memory is bounded whatever the number of points and no more than one file is open at a time.
    class SpillWriter
    {
    public:
      SpillWriter (const SpillDirectory& directory, std::size_t tiles, std::size_t record_bytes, std::size_t buffer_bytes);

      /// Appends one record (record_bytes at \a record) to tile \a t.
      void
      append (std::size_t t, const char* record);

      /// Writes out every buffer.
      void
      flush ();

      /// Records appended to tile \a t so far.
      std::size_t
      records (std::size_t t) const
      {
        return records_[t];
      }

    private:
      void
      flush (std::size_t t);

      const SpillDirectory& directory_;
      std::size_t record_bytes_;
      std::size_t capacity_;  ///< bytes of one tile's buffer
      std::vector<std::vector<char>> buffers_;
      std::vector<std::size_t> records_;
    };

    /// Reads the spill file \a path (\a records records of \a record_bytes) a block at a time, calling
    /// visit (const char* record) for each in order. Throws pcl_sparse::Error if the file is short.
    template <typename Visit>
    void
    readSpillFile (const std::string& path, std::size_t records, std::size_t record_bytes, Visit visit)
    {
      if (records == 0)
        return;
      const std::unique_ptr<std::FILE, int (*) (std::FILE*)> file (std::fopen (path.c_str (), "rb"), &std::fclose);
      if (!file)
        throw Error (path + ": cannot open the spill file (" + std::strerror (errno) + ")");
      const std::size_t block = std::max<std::size_t> (1, (std::size_t (1) << 20) / record_bytes);
      std::vector<char> buffer (std::min (block, records) * record_bytes);
      for (std::size_t done = 0; done < records;)
      {
        const std::size_t n = std::min (block, records - done);
        if (std::fread (buffer.data (), record_bytes, n, file.get ()) != n)
          throw Error (path + ": the spill file is shorter than the records written to it");
        for (std::size_t i = 0; i < n; ++i)
          visit (buffer.data () + i * record_bytes);
        done += n;
      }
    }
  } // namespace tiles_detail
} // namespace pcl_sparse
