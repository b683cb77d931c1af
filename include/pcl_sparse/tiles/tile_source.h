#pragma once
/// \file tile_source.h
/// Where a tiled encoder gets each tile's input from (issue 16). Two implementations share this
/// interface: one cuts tiles out of an input held in memory, the other reads the per-tile files a
/// streaming pass spilled to disk (for inputs larger than memory). Both give a tile's points in the
/// order of the input file, so a tiled model does not depend on which one was used.
///
/// The rules both follow (tested in test/test_tile_spill.cpp):
/// - The grid is in the input file's frame (ScanCloud::worldPosition), made by makeTileGrid from the bounding
///   box and the number of the points cleaning keeps (of all vertices for a mesh).
/// - A tile holds the points tilesHolding (tile_membership.h) gives it: those in its closed margin box, and
///   those it owns (TileGrid::tileOf), so that rounding at a border loses no point. A mesh tile holds the
///   triangles (after fan triangulation) with a vertex tilesHolding gives it.
/// - A tile's scan is in the local frame centreScan gives its points, with the input's fields and sensor pose,
///   indices into the input file, width = its size, height = 1, report.input_points = report.kept = its size.
/// - Cleaning the whole input and then cutting equals cutting and then cleaning each tile: non-finite points
///   and points at the sensor are dropped one by one, and exact duplicates share one position, hence the
///   same tiles, so each tile keeps the first of them in file order, as cleaning the whole input does.

#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/tile_grid.h>

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  /// The input of one tile: the points (a scan) or the faces (a mesh) of its margin box; exactly one is set.
  /// A scan keeps every point of the margin box (cleaned as the whole input would be), in file order, in
  /// the local frame of its own origin (ScanCloud::origin); a mesh keeps every face with a vertex in the
  /// margin box, in file order, with its vertices renumbered in order of first use.
  struct TileInput
  {
    ScanCloud::Ptr scan;    ///< the scan's points of the margin box, or empty
    TriangleMesh::Ptr mesh; ///< the mesh's faces of the margin box, or empty
    /// Empty, or one per tile point (scan point, mesh vertex): its number in the whole input (the kept
    /// point's rank in the cleaned scan, i.e. its file index less the points cleaning dropped or merged
    /// before it; the mesh's vertex index), so that a tiled model's patches list the whole input's vertices
    /// (statistics, reconstruction). Both sources fill it, with the same numbers. Empty: the tile's patches
    /// list none.
    std::vector<std::size_t> point_numbers;

    /// Whether the tile has nothing to encode.
    bool empty () const { return !(scan && scan->size () > 0) && !(mesh && !mesh->triangles.empty ()); }
  };

  /// \brief A tiled input: its grid, and each tile's input on demand.
  class TileSource
  {
  public:
    using Ptr = std::shared_ptr<TileSource>;
    virtual ~TileSource () = default;

    /// The grid the input is cut along.
    virtual const TileGrid& grid () const = 0;
    /// Points of the whole input (after cleaning), for statistics and the grid's choice.
    virtual std::size_t totalPoints () const = 0;
    /// Points whose position lies in tile \a t's core box (0: the tile has nothing to encode); a point on a
    /// border between core boxes counts for the tile that owns it (TileGrid::tileOf), so the counts of all
    /// tiles add up to totalPoints ().
    virtual std::size_t corePoints (std::size_t t) const = 0;
    /// The input of tile \a t's margin box. Safe to call from several threads for different tiles.
    virtual TileInput loadTile (std::size_t t) const = 0;

    /// \brief The position a scan's normals face, in the input file's frame, for every tile (encodeTile gives
    /// it to each tile's encoder: SparseSurfaceEncoder::setViewPoint, as the untiled encoding of the same
    /// input would get it). Without it a tile's normals face the input's sensor pose (a PCD's VIEWPOINT) when
    /// plausible, else they are oriented consistently. Meshes ignore it (their normals follow the faces).
    void
    setViewPoint (float vpx, float vpy, float vpz)
    {
      has_viewpoint_ = true;
      viewpoint_ = Eigen::Vector3f (vpx, vpy, vpz);
    }
    bool hasViewPoint () const { return has_viewpoint_; }
    const Eigen::Vector3f& getViewPoint () const { return viewpoint_; }

  private:
    bool has_viewpoint_ = false;
    Eigen::Vector3f viewpoint_ = Eigen::Vector3f::Zero ();
  };
} // namespace pcl_sparse
