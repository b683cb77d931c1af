/// ScanStreamReader: binary and ascii PCD through PCL's own record layout and ascii parser, binary PLY
/// through the PLY body reader, a chunk at a time; every other file through loadScanCloud, whole.

#include <pcl_sparse/io/scan_stream.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/scan_io.h>

#include "cloud_readers.h"
#include "mesh_readers.h"

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>

namespace pcl_sparse
{
  class ScanStreamReader::Format
  {
  public:
    virtual ~Format () = default;

    /// Reads the points first .. first + n - 1 (the next ones in the file) into \a chunk.
    virtual void
    readPoints (std::size_t first, std::size_t n, ScanCloud& chunk) = 0;

    /// Back to the first point.
    virtual void
    restart () = 0;

    ScanCloud layout;       ///< the scan without points
    std::size_t size = 0;   ///< points in the file
    bool streamed = true;   ///< false: the file is held in memory
    std::size_t next = 0;   ///< the next point to read
    std::size_t max_chunk = std::numeric_limits<std::size_t>::max ();  ///< points a chunk may hold
  };

  namespace
  {
    /// Copies the file's description (not the points) from \a layout to \a chunk.
    void
    copyLayout (const ScanCloud& layout, ScanCloud& chunk)
    {
      chunk.origin.setZero ();
      chunk.width = layout.width;
      chunk.height = layout.height;
      chunk.sensor_origin = layout.sensor_origin;
      chunk.sensor_orientation = layout.sensor_orientation;
      chunk.has_sensor_pose = layout.has_sensor_pose;
      chunk.fields = layout.fields;
      chunk.report = ScanCleaningReport ();
    }

    /// Opens \a path for reading at byte \a offset.
    void
    openAt (std::ifstream& file, const std::string& path, std::size_t offset)
    {
      file.close ();
      file.clear ();
      file.open (path, std::ios::binary);
      file.seekg (static_cast<std::streamoff> (offset));
      if (!file)
        throw Error (path + ": cannot open the file");
    }

    /// Binary or ascii PCD: records in PCL's layout, a chunk at a time.
    class PcdStream : public ScanStreamReader::Format
    {
    public:
      PcdStream (const std::string& path, const io_detail::PcdHeader& header) : path_ (path), header_ (header)
      {
        io_detail::pcdScanLayout (header.layout, header.sensor_origin, header.sensor_orientation, layout);
        size = static_cast<std::size_t> (header.layout.width) * header.layout.height;
        // A chunk's bytes must fit PCLPointCloud2's 32-bit row_step (a point may have 8 MB of fields).
        max_chunk = std::max<std::size_t> (1, (std::size_t (1) << 30) / std::max<std::size_t> (1, header.layout.point_step));
        restart ();
      }

      void
      readPoints (std::size_t first, std::size_t n, ScanCloud& chunk) override
      {
        pcl::PCLPointCloud2 cloud;
        cloud.fields = header_.layout.fields;
        cloud.point_step = header_.layout.point_step;
        cloud.width = static_cast<std::uint32_t> (n);
        cloud.height = 1;
        cloud.row_step = cloud.point_step * cloud.width;
        cloud.data.assign (static_cast<std::size_t> (cloud.row_step), 0);
        if (header_.data_kind == "binary")
        {
          file_.read (reinterpret_cast<char*> (cloud.data.data ()), static_cast<std::streamsize> (cloud.data.size ()));
          if (static_cast<std::size_t> (file_.gcount ()) != cloud.data.size ())
            throw Error (path_ + ": truncated PCD data (the file ends in point " + std::to_string (first) + ")");
        }
        else
        {
          // As loadScanCloud, the lines are checked once before PCL's parser trusts them; on the first read,
          // not at opening, so that a reader made only for its size (the tools' -memory probe) reads the
          // header alone.
          if (!ascii_checked_)
            io_detail::checkPcdAsciiData (path_, header_);
          ascii_checked_ = true;
          // PCL's own ascii parser, n lines at a time: the values are those of a whole-file read.
          io_detail::QuietPclConsole quiet;
          pcl::PCDReader reader;
          if (reader.readBodyASCII (file_, cloud, pcl::PCDReader::PCD_V7) < 0)
            throw Error (path_ + ": truncated or bad ascii PCD data (near point " + std::to_string (first) + ")");
        }
        io_detail::pcdScanPoints (cloud, path_, chunk);
      }

      void
      restart () override
      {
        openAt (file_, path_, header_.data_offset);
      }

    private:
      std::string path_;
      io_detail::PcdHeader header_;
      std::ifstream file_;
      bool ascii_checked_ = false;
    };

    /// Binary PLY whose vertex records come first: a chunk of records at a time.
    class PlyStream : public ScanStreamReader::Format
    {
    public:
      PlyStream (const std::string& path, io_detail::PlyVertexRecords records, std::size_t file_size)
      : path_ (path), records_ (std::move (records))
      {
        const long long remaining = static_cast<long long> (file_size - std::min (file_size, records_.bodyOffset ()));
        const long long record = static_cast<long long> (records_.recordBytes ());
        if (record > 0 && records_.count () > remaining / record)
          throw Error (path + ": truncated or lying header: the PLY element 'vertex' announces " +
                       std::to_string (records_.count ()) + " records, more than the " + std::to_string (remaining) +
                       " remaining bytes can hold");
        if (records_.count () > static_cast<long long> (std::numeric_limits<std::uint32_t>::max ()))
          throw Error (path + ": too many points (" + std::to_string (records_.count ()) + ")");
        size = static_cast<std::size_t> (records_.count ());
        io_detail::PlyPoints none;
        records_.decode (std::string (), io_detail::plyScanProperties (), none);
        io_detail::plyScanPoints (none, path_, layout);
        layout.width = static_cast<std::uint32_t> (size);
        layout.height = 1;
        restart ();
      }

      void
      readPoints (std::size_t first, std::size_t n, ScanCloud& chunk) override
      {
        bytes_.resize (n * records_.recordBytes ());
        file_.read (&bytes_[0], static_cast<std::streamsize> (bytes_.size ()));
        if (static_cast<std::size_t> (file_.gcount ()) != bytes_.size ())
          throw Error (path_ + ": truncated: the file ends in PLY vertex " + std::to_string (first));
        records_.decode (bytes_, io_detail::plyScanProperties (), points_);
        io_detail::plyScanPoints (points_, path_, chunk);
      }

      void
      restart () override
      {
        openAt (file_, path_, records_.bodyOffset ());
      }

    private:
      std::string path_;
      io_detail::PlyVertexRecords records_;
      std::ifstream file_;
      std::string bytes_;
      io_detail::PlyPoints points_;
    };

    /// Any other file: loadScanCloud without cleaning, handed out in chunks.
    class WholeFile : public ScanStreamReader::Format
    {
    public:
      explicit WholeFile (const std::string& path)
      {
        ScanLoadOptions options;
        options.clean = false;
        loadScanCloud (path, scan_, options);
        copyLayout (scan_, layout);
        size = scan_.size ();
        streamed = false;
      }

      void
      readPoints (std::size_t first, std::size_t n, ScanCloud& chunk) override
      {
        const auto slice = [&] (const auto& from, auto& to) {
          if (from.empty ())
            to.clear ();
          else
            to.assign (from.begin () + static_cast<std::ptrdiff_t> (first),
                       from.begin () + static_cast<std::ptrdiff_t> (first + n));
        };
        slice (scan_.normals, chunk.normals);
        slice (scan_.colors, chunk.colors);
        slice (scan_.intensities, chunk.intensities);
        slice (scan_.viewpoints, chunk.viewpoints);
        slice (scan_.indices, chunk.indices);
        chunk.positions.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          chunk.positions[i] = scan_.worldPosition (first + i);  // exact: see localFrameOrigin
      }

      void
      restart () override
      {
      }

    private:
      ScanCloud scan_;
    };

    std::unique_ptr<ScanStreamReader::Format>
    openFormat (const std::string& path)
    {
      const std::string extension = io_detail::lowerCaseExtension (path);
      if (extension == ".pcd")
      {
        io_detail::checkReadableFile (path);
        io_detail::PcdHeader header = io_detail::readPcdHeader (path);
        if (header.data_kind != "binary_compressed")
          return std::make_unique<PcdStream> (path, header);
      }
      else if (extension == ".ply")
      {
        // The header is in the first bytes (1 MiB leaves room for any comments).
        io_detail::checkReadableFile (path);
        std::ifstream file (path, std::ios::binary);
        std::string head (1 << 20, '\0');
        file.read (&head[0], static_cast<std::streamsize> (head.size ()));
        head.resize (static_cast<std::size_t> (file.gcount ()));
        const std::size_t file_size = static_cast<std::size_t> (std::filesystem::file_size (path));
        io_detail::PlyVertexRecords records (head, path);
        if (records.streamable ())
          return std::make_unique<PlyStream> (path, std::move (records), file_size);
      }
      return std::make_unique<WholeFile> (path);
    }
  } // namespace

  ScanStreamReader::ScanStreamReader (const std::string& path) : format_ (openFormat (path)), path_ (path)
  {
    if (format_->size == 0)
      throw Error (path + ": the file has no points");
  }

  ScanStreamReader::~ScanStreamReader () = default;

  const ScanCloud&
  ScanStreamReader::layout () const
  {
    return format_->layout;
  }

  std::size_t
  ScanStreamReader::size () const
  {
    return format_->size;
  }

  bool
  ScanStreamReader::isStreamed () const
  {
    return format_->streamed;
  }

  const std::string&
  ScanStreamReader::path () const
  {
    return path_;
  }

  bool
  ScanStreamReader::read (ScanCloud& chunk, std::size_t max_points)
  {
    if (max_points == 0)
      throw Error ("ScanStreamReader::read: max_points must be positive");
    const std::size_t first = format_->next;
    const std::size_t n = std::min ({max_points, format_->max_chunk, format_->size - first});
    copyLayout (format_->layout, chunk);
    if (n == 0)
    {
      chunk.positions.clear ();
      chunk.normals.clear ();
      chunk.colors.clear ();
      chunk.intensities.clear ();
      chunk.viewpoints.clear ();
      chunk.indices.clear ();
      return false;
    }
    format_->readPoints (first, n, chunk);
    copyLayout (format_->layout, chunk);  // the format's converters set the chunk's own shape
    if (format_->streamed)
    {
      chunk.indices.resize (n);
      std::iota (chunk.indices.begin (), chunk.indices.end (), first);
    }
    format_->next = first + n;
    return true;
  }

  void
  ScanStreamReader::rewind ()
  {
    format_->restart ();
    format_->next = 0;
  }
} // namespace pcl_sparse
