#pragma once
/// \file tile_statistics.h
/// The statistics of a tiled model taken tile by tile (issue 16): what SparseSurfaceModel::statistics gives
/// against the whole input, without holding the whole input: each tile's core points are read back from
/// the tile source and compared with their reconstruction by every patch listing them (those of the tile
/// and of its neighbours), so memory is bounded by one tile's input and the model.

#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/model/tiled_model.h>
#include <pcl_sparse/tiles/tile_source.h>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// Options of tiledModelStatistics.
  struct TiledStatisticsOptions
  {
    /// Clear each patch's vertex list (PatchCode::vertices, vertex_xy) once every tile that needs it has
    /// been measured (default true): the model then holds no per-input-point data, which on a large input
    /// is most of its memory, and an encoder that measures as it goes holds the lists without vertex_xy
    /// till then (encodeTile's keep_xy); keep them (false) to write them (--store-vertices) or to
    /// reconstruct the input vertices.
    bool drop_vertices = true;
    /// How many tiles away a tile's patches may list points (the largest TileEncoding::reach of the tiles):
    /// 1 (default) unless a mesh's triangles are longer than the tiles' margin. Each point is measured
    /// against the patches of the tiles this near; a patch farther that lists it would be left out.
    int reach = 1;
  };

  /// \brief The tiles within \a reach steps of tile \a t along each axis (\a t included), ascending: within
  /// one step, those whose patches can list a point of \a t's core when they list points of their margin
  /// box only (a mesh's long triangles may take them farther: TileEncoding::reach).
  /// \param[in] grid  the grid
  /// \param[in] t     the tile
  /// \param[in] reach steps (default 1: the 26 tiles around \a t and \a t)
  std::vector<std::size_t>
  neighbourTiles (const TileGrid& grid, std::size_t t, int reach = 1);

  /// Some patches of one tile, and the basis they are coded over (a span of a model's patches).
  struct TilePatches
  {
    const PatchCode* first = nullptr;     ///< the first patch
    std::size_t count = 0;                ///< number of patches
    const SurfaceBasis* basis = nullptr;  ///< their basis (null: heights 0)
    /// The points they list that their tile's encoder coded elsewhere (TileEncoding::moved; null: none):
    /// each patch is evaluated where it coded the point, the error taken to the input's point, as the
    /// untiled statistics do. Evaluated at the input's position instead, a patch extrapolated its code
    /// beyond its disk (office1.pcd in 4 tiles, depth steps taken out: a point 2.2 radii out, 49 m off).
    const MovedPoints* moved = nullptr;
  };

  /// The errors of one tile's core points, summed over them in point-number order, to be added to
  /// TiledErrorSums in tile order. A few numbers a tile, whatever its size: a tile measured ahead of a lower
  /// one waits with these, not with an error a point.
  struct TileErrors
  {
    double squares = 0.0;        ///< sum of |v - v^|^2 over its covered core points
    double absolute = 0.0;       ///< sum of |v - v^|
    double largest = 0.0;        ///< largest |v - v^|
    std::size_t covered = 0;     ///< its core points in some patch
    std::size_t uncovered = 0;   ///< its core points in no patch
  };

  /// \brief Running sums of a tiled model's vertex errors, taken tile by tile: what tiledModelStatistics adds
  /// up, for an encoder that measures each tile as soon as the tiles around it are encoded
  /// (TiledSurfaceEncoder). Each tile's errors are summed first, then the tiles' sums in ascending tile
  /// order: so the figures are tiledModelStatistics' bit for bit, whatever order the tiles are measured in.
  class TiledErrorSums
  {
  public:
    /// \brief Adds the errors of tile \a t's core points, each reconstructed as the mean over the patches of
    /// \a near listing it (PatchCode::vertices), at its local (x', y') in each recomputed from the point:
    /// PatchCode::vertex_xy is not read, so vertex lists held for the statistics need only the numbers.
    /// \param[in] source the tiled input, with point numbers
    /// \param[in] t      the tile
    /// \param[in] near   the patches of \a t and of the tiles around it (neighbourTiles), in model order
    /// \throws pcl_sparse::Error if the tile has points but no point numbers
    void
    addTile (const TileSource& source, std::size_t t, const std::vector<TilePatches>& near)
    {
      add (measureTile (source, t, near));
    }

    /// \brief The errors addTile adds, to be added later (add): tiles can be measured in any order, and
    /// added in tile order.
    static TileErrors
    measureTile (const TileSource& source, std::size_t t, const std::vector<TilePatches>& near);

    /// \brief Adds a tile's errors (measureTile).
    void
    add (const TileErrors& tile);

    /// \brief The statistics of \a model (the merged model) from the sums. Uncovered: the points of the whole
    /// input not measured covered, so also those in no tile's input (a mesh's vertices in no face), as the
    /// untiled SparseSurfaceModel::statistics counts them.
    /// \param[in] model        the whole model (patch and coefficient counts, diagonal)
    /// \param[in] total_points points of the whole input
    ModelStatistics
    statistics (const SparseSurfaceModel& model, std::size_t total_points) const;

  private:
    double squares_ = 0.0, absolute_ = 0.0, largest_ = 0.0;
    std::size_t covered_ = 0, uncovered_ = 0;
  };

  /// \brief Statistics of \a tiled (encoded from \a source) against its input, tile by tile.
  ///
  /// Each point is reconstructed as reconstructVertices does (the mean over the patches listing it, in model
  /// order) from the patches of its own tile and of the 26 tiles around it (a tile's patches list only points
  /// of its margin box), and its error is taken in its own tile (TileGrid::tileOf), so every point counts
  /// once; each patch is evaluated where its tile's encoder coded the point (TileRange::moved). Each tile's
  /// points are summed in input order, then the tiles' sums in tile order: the figures equal
  /// SparseSurfaceModel::statistics against the whole input up to rounding, and do not depend on the tile
  /// source (MemoryTileSource or a spilled one give the same bits) or on the number of threads.
  /// \param[in] source     the tiled input, with point numbers (TileInput::point_numbers)
  /// \param[in,out] tiled  the tiled model (its patches list point numbers); vertex lists (and TileRange::moved)
  ///                       cleared if asked
  /// \param[in] options    options
  /// \return the statistics (num_vertices = source.totalPoints ())
  /// \throws pcl_sparse::Error if a tile with patches has no point numbers or the grids differ
  ModelStatistics
  tiledModelStatistics (const TileSource& source, TiledModel& tiled,
                        const TiledStatisticsOptions& options = TiledStatisticsOptions ());
} // namespace pcl_sparse
