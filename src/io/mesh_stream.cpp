/// MeshStreamReader: binary PLY vertices and faces through the PLY body reader a chunk at a time; other
/// mesh files through loadTriangleMesh, whole.

#include <pcl_sparse/io/mesh_stream.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_io.h>

#include "cloud_readers.h"
#include "mesh_readers.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace pcl_sparse
{
  class MeshStreamReader::Format
  {
  public:
    virtual ~Format () = default;
    virtual void readVertices (std::size_t first, std::size_t n, std::vector<Eigen::Vector3d>& chunk) = 0;
    /// Appends about \a n triangles; false at the end.
    virtual bool readTriangles (std::size_t n, std::vector<Eigen::Vector3i>& chunk) = 0;
    virtual void restart () = 0;

    std::size_t vertices = 0;     ///< vertices in the file
    std::size_t next_vertex = 0;  ///< the next vertex to read
    bool streamed = true;
  };

  namespace
  {
    /// A binary PLY mesh: vertex records, then face records, read in chunks.
    class PlyMeshStream : public MeshStreamReader::Format
    {
    public:
      PlyMeshStream (const std::string& path, io_detail::PlyVertexRecords vertex_records,
                     io_detail::PlyFaceRecords face_records)
      : path_ (path), vertex_records_ (std::move (vertex_records)), face_records_ (std::move (face_records))
      {
        file_size_ = std::filesystem::file_size (path);
        const long long remaining =
          static_cast<long long> (file_size_ - std::min<std::uintmax_t> (file_size_, vertex_records_.bodyOffset ()));
        const long long record = static_cast<long long> (vertex_records_.recordBytes ());
        // Every face record takes at least one byte (its list size). Divided, not multiplied: the counts are
        // the header's, up to 2^63 (2^62 records of 12 bytes wrapped to 0 and passed).
        if ((record > 0 && vertex_records_.count () > remaining / record) ||
            face_records_.count () > remaining - vertex_records_.count () * record)
          throw Error (path + ": truncated or lying header: the PLY vertex and face elements announce more records than the file can hold");
        if (vertex_records_.count () == 0)
          throw Error (path + ": no vertices");
        if (face_records_.count () == 0)
          throw Error (path + ": no faces (a point cloud, not a mesh)");
        vertices = static_cast<std::size_t> (vertex_records_.count ());
        restart ();
      }

      void
      readVertices (std::size_t first, std::size_t n, std::vector<Eigen::Vector3d>& chunk) override
      {
        bytes_.resize (n * vertex_records_.recordBytes ());
        file_.read (&bytes_[0], static_cast<std::streamsize> (bytes_.size ()));
        if (static_cast<std::size_t> (file_.gcount ()) != bytes_.size ())
          throw Error (path_ + ": truncated: the file ends in PLY vertex " + std::to_string (first));
        io_detail::PlyPoints points;
        vertex_records_.decode (bytes_, {}, points);
        chunk = std::move (points.positions);
      }

      bool
      readTriangles (std::size_t n, std::vector<Eigen::Vector3i>& chunk) override
      {
        // Blocks of about n triangles' bytes; a record cut by the block's end waits for the next block.
        const std::size_t block = std::max<std::size_t> (n * 13, 1 << 16);
        while (faces_read_ < face_records_.count ())
        {
          const std::size_t kept = carry_.size ();
          carry_.resize (kept + block);
          file_.read (&carry_[kept], static_cast<std::streamsize> (block));
          carry_.resize (kept + static_cast<std::size_t> (file_.gcount ()));
          long long records = 0;
          std::size_t next_record = 0;
          const std::size_t used =
            face_records_.decode (carry_, face_records_.count () - faces_read_, chunk, records, &next_record);
          faces_read_ += records;
          carry_.erase (0, used);
          // A list size the rest of the file cannot hold is refused now, not after reading the rest into carry_.
          const std::uintmax_t left = carry_.size () + (file_size_ - std::min<std::uintmax_t> (file_size_, offset ()));
          if (next_record > left)
            throw Error (path_ + ": truncated or lying list size: PLY face " + std::to_string (faces_read_) + " takes at least " +
                         std::to_string (next_record) + " bytes, " + std::to_string (left) + " are left in the file");
          if (records == 0 && file_.gcount () == 0)
            throw Error (path_ + ": truncated: the file ends in PLY face " + std::to_string (faces_read_) + " of " +
                         std::to_string (face_records_.count ()));
          if (faces_read_ == face_records_.count ())
            checkEnd ();
          if (!chunk.empty ())
            return true;
        }
        return false;
      }

      void
      restart () override
      {
        file_.close ();
        file_.clear ();
        file_.open (path_, std::ios::binary);
        file_.seekg (static_cast<std::streamoff> (vertex_records_.bodyOffset ()));
        if (!file_)
          throw Error (path_ + ": cannot open the file");
        carry_.clear ();
        faces_read_ = 0;
      }

    private:
      /// After the last face: what is left of the file must be padding (PlyFaceRecords::checkEnd).
      void
      checkEnd ()
      {
        std::string rest = std::move (carry_);
        carry_.clear ();
        char block[1 << 16];
        while (file_.read (block, sizeof (block)) || file_.gcount () > 0)
        {
          rest.append (block, static_cast<std::size_t> (file_.gcount ()));
          face_records_.checkEnd (rest);
          rest.clear ();
        }
        face_records_.checkEnd (rest);
      }

      std::string path_;
      io_detail::PlyVertexRecords vertex_records_;
      io_detail::PlyFaceRecords face_records_;
      std::ifstream file_;
      std::string bytes_;
      std::string carry_;
      long long faces_read_ = 0;
      std::uintmax_t file_size_ = 0;

      /// Bytes of the file read so far.
      std::uintmax_t
      offset ()
      {
        const std::streamoff at = file_.tellg ();
        return at < 0 ? file_size_ : static_cast<std::uintmax_t> (at);
      }
    };

    /// Any other mesh file: loadTriangleMesh, handed out in chunks.
    class WholeMesh : public MeshStreamReader::Format
    {
    public:
      explicit WholeMesh (const std::string& path)
      {
        MeshLoadOptions options;
        options.allow_non_finite = true;
        mesh_ = loadTriangleMesh (path, options);
        vertices = mesh_.vertices.size ();
        streamed = false;
      }

      void
      readVertices (std::size_t first, std::size_t n, std::vector<Eigen::Vector3d>& chunk) override
      {
        chunk.assign (mesh_.vertices.begin () + static_cast<std::ptrdiff_t> (first),
                      mesh_.vertices.begin () + static_cast<std::ptrdiff_t> (first + n));
      }

      bool
      readTriangles (std::size_t n, std::vector<Eigen::Vector3i>& chunk) override
      {
        const std::size_t m = std::min (n, mesh_.triangles.size () - next_triangle_);
        chunk.assign (mesh_.triangles.begin () + static_cast<std::ptrdiff_t> (next_triangle_),
                      mesh_.triangles.begin () + static_cast<std::ptrdiff_t> (next_triangle_ + m));
        next_triangle_ += m;
        return m > 0;
      }

      void
      restart () override
      {
        next_triangle_ = 0;
      }

    private:
      TriangleMesh mesh_;
      std::size_t next_triangle_ = 0;
    };

    std::unique_ptr<MeshStreamReader::Format>
    openMesh (const std::string& path)
    {
      if (!isMeshFileExtension (path))
        throw Error (path + ": unknown mesh file extension (expected .obj, .off, .ply or .stl)");
      if (io_detail::lowerCaseExtension (path) == ".ply")
      {
        io_detail::checkReadableFile (path);
        std::ifstream file (path, std::ios::binary);
        std::string head (1 << 20, '\0');
        file.read (&head[0], static_cast<std::streamsize> (head.size ()));
        head.resize (static_cast<std::size_t> (file.gcount ()));
        io_detail::PlyVertexRecords vertex_records (head, path);
        io_detail::PlyFaceRecords face_records (head, path);
        if (vertex_records.streamable () && face_records.streamable ())
          return std::make_unique<PlyMeshStream> (path, std::move (vertex_records), std::move (face_records));
      }
      return std::make_unique<WholeMesh> (path);
    }
  } // namespace

  MeshStreamReader::MeshStreamReader (const std::string& path) : format_ (openMesh (path)) {}

  MeshStreamReader::~MeshStreamReader () = default;

  std::size_t
  MeshStreamReader::numVertices () const
  {
    return format_->vertices;
  }

  bool
  MeshStreamReader::isStreamed () const
  {
    return format_->streamed;
  }

  bool
  MeshStreamReader::readVertices (std::vector<Eigen::Vector3d>& chunk, std::size_t max_vertices)
  {
    if (max_vertices == 0)
      throw Error ("MeshStreamReader::readVertices: max_vertices must be positive");
    const std::size_t n = std::min (max_vertices, format_->vertices - format_->next_vertex);
    chunk.clear ();
    if (n == 0)
      return false;
    format_->readVertices (format_->next_vertex, n, chunk);
    format_->next_vertex += n;
    return true;
  }

  bool
  MeshStreamReader::readTriangles (std::vector<Eigen::Vector3i>& chunk, std::size_t max_triangles)
  {
    if (max_triangles == 0)
      throw Error ("MeshStreamReader::readTriangles: max_triangles must be positive");
    if (format_->next_vertex != format_->vertices)
      throw Error ("MeshStreamReader::readTriangles: the vertices must be read first");
    chunk.clear ();
    return format_->readTriangles (max_triangles, chunk);
  }

  void
  MeshStreamReader::rewind ()
  {
    format_->restart ();
    format_->next_vertex = 0;
  }
} // namespace pcl_sparse
