#include <pcl_sparse/tiles/spilled_mesh_tile_source.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_stream.h>
#include <pcl_sparse/tiles/tile_membership.h>

#include "spill_files.h"

#include <algorithm>
#include <cstdio>

#include <fcntl.h>
#include <unistd.h>

namespace pcl_sparse
{
  namespace
  {
    /// The vertex positions spill file: 3 doubles per vertex, in file order.
    std::string
    vertexFile (const tiles_detail::SpillDirectory& directory)
    {
      return directory.path () + "/vertices.bin";
    }

    /// Positions of the vertices \a ids (ascending, distinct) from the vertex file, read in runs of nearby
    /// records.
    void
    readVertices (const std::string& path, const std::vector<int>& ids, std::vector<Eigen::Vector3d>& positions)
    {
      positions.resize (ids.size ());
      const int fd = ::open (path.c_str (), O_RDONLY);
      if (fd < 0)
        throw Error (path + ": cannot open the vertex spill file");
      std::vector<double> run;
      for (std::size_t i = 0; i < ids.size ();)
      {
        // A run: ids close enough (gaps up to 64 vertices) to read in one go, at most 64k vertices.
        std::size_t j = i + 1;
        while (j < ids.size () && ids[j] - ids[j - 1] <= 64 && ids[j] - ids[i] < 65536)
          ++j;
        const std::size_t count = static_cast<std::size_t> (ids[j - 1] - ids[i]) + 1;
        run.resize (3 * count);
        const ssize_t bytes = static_cast<ssize_t> (run.size () * sizeof (double));
        if (::pread (fd, run.data (), static_cast<std::size_t> (bytes), static_cast<off_t> (ids[i]) * 3 * sizeof (double)) != bytes)
        {
          ::close (fd);
          throw Error (path + ": the vertex spill file is shorter than the vertices written to it");
        }
        for (std::size_t k = i; k < j; ++k)
        {
          const double* v = run.data () + 3 * static_cast<std::size_t> (ids[k] - ids[i]);
          positions[k] = Eigen::Vector3d (v[0], v[1], v[2]);
        }
        i = j;
      }
      ::close (fd);
    }

    /// Pass 1: every vertex to the vertex file; their box; refuses a non-finite one.
    Eigen::AlignedBox3d
    spillVertices (MeshStreamReader& reader, const std::string& path, const std::string& file, const SpillOptions& options)
    {
      const std::unique_ptr<std::FILE, int (*) (std::FILE*)> out (std::fopen (file.c_str (), "wb"), &std::fclose);
      if (!out)
        throw Error (file + ": cannot write the vertex spill file");
      Eigen::AlignedBox3d box;
      std::vector<Eigen::Vector3d> chunk;
      std::size_t first = 0;
      while (reader.readVertices (chunk, options.chunk_points))
      {
        if (options.progress)
          options.progress ("spill: vertices", static_cast<double> (first) / static_cast<double> (reader.numVertices ()));
        for (std::size_t i = 0; i < chunk.size (); ++i)
        {
          if (!chunk[i].allFinite ())
            throw Error (path + ": vertex " + std::to_string (first + i) + " has a non-finite coordinate");
          box.extend (chunk[i]);
        }
        if (std::fwrite (chunk.data (), sizeof (Eigen::Vector3d), chunk.size (), out.get ()) != chunk.size ())
          throw Error (file + ": cannot write the vertex spill file");
        first += chunk.size ();
      }
      if (std::fflush (out.get ()) != 0)
        throw Error (file + ": cannot write the vertex spill file");
      return box;
    }
  } // namespace

  SpilledMeshTileSource::SpilledMeshTileSource (const std::string& path, const SpillOptions& options)
  {
    if (options.chunk_points == 0 || options.buffer_bytes == 0)
      throw Error ("SpilledMeshTileSource: chunk_points and buffer_bytes must be positive");
    makeTileGrid (Eigen::AlignedBox3d (Eigen::Vector3d::Zero (), Eigen::Vector3d::Ones ()), 1, options.grid);
    MeshStreamReader reader (path);
    directory_ = std::make_unique<tiles_detail::SpillDirectory> (options.directory);
    streamed_ = reader.isStreamed ();
    vertices_ = reader.numVertices ();
    const std::string vertex_file = vertexFile (*directory_);
    grid_ = makeTileGrid (spillVertices (reader, path, vertex_file, options), vertices_, options.grid);

    // Pass 2: each triangle to every tile holding one of its vertices, a chunk of triangles at a time.
    tiles_detail::SpillWriter writer (*directory_, grid_.size (), sizeof (Eigen::Vector3i), options.buffer_bytes);
    std::vector<Eigen::Vector3i> chunk;
    std::vector<int> ids;
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::size_t> tiles, holding;
    std::vector<bool> used (vertices_, false);  // a vertex used twice: the faces share vertices, not a soup
    bool shared = false, any = false;
    while (reader.readTriangles (chunk, options.chunk_points))
    {
      ids.clear ();
      for (const Eigen::Vector3i& triangle : chunk)
      {
        ids.insert (ids.end (), triangle.data (), triangle.data () + 3);
        for (int k = 0; k < 3 && !shared; ++k)
        {
          shared = used[triangle[k]];
          used[triangle[k]] = true;
        }
        any = true;
      }
      std::sort (ids.begin (), ids.end ());
      ids.erase (std::unique (ids.begin (), ids.end ()), ids.end ());
      readVertices (vertex_file, ids, positions);
      for (const Eigen::Vector3i& triangle : chunk)
      {
        tiles.clear ();
        for (int k = 0; k < 3; ++k)
        {
          const std::size_t at = static_cast<std::size_t> (std::lower_bound (ids.begin (), ids.end (), triangle[k]) - ids.begin ());
          tilesHolding (grid_, positions[at], holding);
          tiles.insert (tiles.end (), holding.begin (), holding.end ());
        }
        std::sort (tiles.begin (), tiles.end ());
        tiles.erase (std::unique (tiles.begin (), tiles.end ()), tiles.end ());
        for (const std::size_t t : tiles)
          writer.append (t, reinterpret_cast<const char*> (triangle.data ()));
      }
    }
    writer.flush ();
    soup_ = any && !shared;
    triangles_.resize (grid_.size ());
    for (std::size_t t = 0; t < grid_.size (); ++t)
      triangles_[t] = writer.records (t);

    // The vertices each tile owns, from the vertex file.
    core_points_.assign (grid_.size (), 0);
    tiles_detail::readSpillFile (vertex_file, vertices_, sizeof (Eigen::Vector3d), [&] (const char* in) {
      Eigen::Vector3d v;
      std::memcpy (v.data (), in, sizeof (Eigen::Vector3d));
      ++core_points_[grid_.tileOf (v)];
    });
  }

  SpilledMeshTileSource::~SpilledMeshTileSource () = default;

  std::size_t
  SpilledMeshTileSource::corePoints (std::size_t t) const
  {
    if (t >= core_points_.size ())
      throw Error ("SpilledMeshTileSource::corePoints: tile " + std::to_string (t) + " is not in the grid");
    return core_points_[t];
  }

  std::size_t
  SpilledMeshTileSource::spilledTriangles (std::size_t t) const
  {
    if (t >= triangles_.size ())
      throw Error ("SpilledMeshTileSource::spilledTriangles: tile " + std::to_string (t) + " is not in the grid");
    return triangles_[t];
  }

  std::size_t
  SpilledMeshTileSource::spilledBytes () const
  {
    std::size_t triangles = 0;
    for (const std::size_t n : triangles_)
      triangles += n;
    return vertices_ * sizeof (Eigen::Vector3d) + triangles * sizeof (Eigen::Vector3i);
  }

  TileInput
  SpilledMeshTileSource::loadTile (std::size_t t) const
  {
    if (t >= triangles_.size ())
      throw Error ("SpilledMeshTileSource::loadTile: tile " + std::to_string (t) + " is not in the grid");
    TileInput input;
    if (triangles_[t] == 0)
      return input;
    auto mesh = std::make_shared<TriangleMesh> ();
    mesh->triangles.reserve (triangles_[t]);
    tiles_detail::readSpillFile (directory_->tileFile (t), triangles_[t], sizeof (Eigen::Vector3i), [&] (const char* in) {
      Eigen::Vector3i triangle;
      std::memcpy (triangle.data (), in, sizeof (Eigen::Vector3i));
      mesh->triangles.push_back (triangle);
    });
    // Vertices renumbered in order of first use.
    std::vector<int> ids;
    ids.reserve (3 * mesh->triangles.size ());
    for (const Eigen::Vector3i& triangle : mesh->triangles)
      ids.insert (ids.end (), triangle.data (), triangle.data () + 3);
    std::sort (ids.begin (), ids.end ());
    ids.erase (std::unique (ids.begin (), ids.end ()), ids.end ());
    std::vector<Eigen::Vector3d> positions;
    readVertices (vertexFile (*directory_), ids, positions);
    std::vector<int> local (ids.size (), -1);
    for (Eigen::Vector3i& triangle : mesh->triangles)
      for (int k = 0; k < 3; ++k)
      {
        const std::size_t at = static_cast<std::size_t> (std::lower_bound (ids.begin (), ids.end (), triangle[k]) - ids.begin ());
        if (local[at] < 0)
        {
          local[at] = static_cast<int> (mesh->vertices.size ());
          mesh->vertices.push_back (positions[at]);
          input.point_numbers.push_back (static_cast<std::size_t> (ids[at]));
        }
        triangle[k] = local[at];
      }
    input.mesh = std::move (mesh);
    return input;
  }

  SpilledMeshTileSource::Ptr
  spillMeshIntoTiles (const std::string& path, const SpillOptions& options)
  {
    return std::make_shared<SpilledMeshTileSource> (path, options);
  }
} // namespace pcl_sparse
