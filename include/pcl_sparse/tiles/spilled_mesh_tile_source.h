#pragma once
/// \file spilled_mesh_tile_source.h
/// Tiles of a mesh file larger than memory (issue 16): the vertices are streamed once into a spill file of
/// positions, the triangles once into a spill file per tile; a tile's mesh is read back when asked for.

#include <pcl_sparse/tiles/spilled_tile_source.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief A TileSource of a mesh file backed by temporary files, made by streaming it (MeshStreamReader).
  ///
  /// The grid is makeTileGrid (options.grid) of the bounding box and number of all vertices (loadTriangleMesh
  /// keeps unreferenced ones too), in the file's frame. Tile t's mesh holds every triangle (after fan
  /// triangulation) with a vertex v such that tilesHolding (grid, v) contains t, in file order, with its
  /// vertices renumbered in order of first use: what cutting loadTriangleMesh's mesh gives. Vertices are
  /// not cleaned (a NaN/Inf coordinate is refused, as loadTriangleMesh refuses it).
  ///
  /// Memory: one chunk of triangles and the positions of their vertices at a time, the write buffers, and
  /// one tile's mesh in loadTile; the vertices are looked up in their spill file (options.cleaning is
  /// not used). Streamed for binary PLY meshes (vertices first, then faces); other mesh files are read
  /// whole first.
  class SpilledMeshTileSource : public TileSource
  {
  public:
    using Ptr = std::shared_ptr<SpilledMeshTileSource>;
    using ConstPtr = std::shared_ptr<const SpilledMeshTileSource>;

    /// Spills the mesh file \a path into tiles. Throws pcl_sparse::Error for a file loadTriangleMesh
    /// refuses (missing, truncated, no faces, a face index out of range, a non-finite vertex), bad options,
    /// or a spill file that cannot be written; no spill file is left behind then.
    explicit SpilledMeshTileSource (const std::string& path, const SpillOptions& options = SpillOptions ());
    ~SpilledMeshTileSource () override;
    SpilledMeshTileSource (const SpilledMeshTileSource&) = delete;
    SpilledMeshTileSource& operator= (const SpilledMeshTileSource&) = delete;

    const TileGrid&
    grid () const override
    {
      return grid_;
    }

    /// Vertices of the mesh.
    std::size_t
    totalPoints () const override
    {
      return vertices_;
    }

    /// Vertices tile \a t owns (grid ().tileOf (v) == t).
    std::size_t
    corePoints (std::size_t t) const override;

    /// Tile \a t's mesh (see the class comment); an empty TileInput for a tile no triangle reaches. Safe to
    /// call from several threads.
    TileInput
    loadTile (std::size_t t) const override;

    /// Triangles written to tile \a t's spill file.
    std::size_t
    spilledTriangles (std::size_t t) const;

    /// Bytes in all spill files (the vertex positions and every tile's triangles).
    std::size_t
    spilledBytes () const;

    /// False if the mesh's format could not be streamed and was read whole.
    bool
    wasStreamed () const
    {
      return streamed_;
    }

    /// True when no two faces share a vertex (a triangle soup: each face repeats its corners), which no
    /// tile can grow a patch on. Welding the corners needs the whole file (loadTriangleMesh, cleanMesh).
    bool
    isTriangleSoup () const
    {
      return soup_;
    }

  private:
    std::unique_ptr<tiles_detail::SpillDirectory> directory_;
    TileGrid grid_;
    std::size_t vertices_ = 0;
    std::vector<std::size_t> core_points_;
    std::vector<std::size_t> triangles_;
    bool streamed_ = true;
    bool soup_ = false;
  };

  /// SpilledMeshTileSource (path, options) as a shared pointer: the file-backed TileSource of a mesh file.
  SpilledMeshTileSource::Ptr
  spillMeshIntoTiles (const std::string& path, const SpillOptions& options = SpillOptions ());
} // namespace pcl_sparse
