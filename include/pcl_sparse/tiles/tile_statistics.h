#pragma once
/// \file tile_statistics.h
/// The statistics of a tiled model taken tile by tile (issue 16): what SparseSurfaceModel::statistics gives
/// against the whole input, without holding the whole input: each tile's core points are read back from
/// the tile source and compared with their reconstruction by every patch listing them (those of the tile
/// and of its neighbours), so memory is bounded by one tile's input and the model.

#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/tiles/tile_source.h>
#include <pcl_sparse/tiles/tiled_model.h>

namespace pcl_sparse
{
  /// Options of tiledModelStatistics.
  struct TiledStatisticsOptions
  {
    /// Clear each patch's vertex list (PatchCode::vertices, vertex_xy) once every tile that needs it has
    /// been measured (default true): the model then holds no per-input-point data, which on a large input
    /// is most of its memory; keep them (false) to write them (--store-vertices) or to reconstruct the
    /// input vertices.
    bool drop_vertices = true;
  };

  /// \brief Statistics of \a tiled (encoded from \a source) against its input, tile by tile.
  ///
  /// Each point is reconstructed as reconstructVertices does (the mean over the patches listing it, in model
  /// order) from the patches of its own tile and of the 26 tiles around it (a tile's patches list only points
  /// of its margin box), and its error is taken in its own tile (TileGrid::tileOf), so every point counts
  /// once. The sums run tile by tile, then over the tile's points in input order: the figures equal
  /// SparseSurfaceModel::statistics against the whole input up to rounding, and do not depend on the tile
  /// source (MemoryTileSource or a spilled one give the same bits) or on the number of threads.
  /// \param[in] source     the tiled input, with point numbers (TileInput::point_numbers)
  /// \param[in,out] tiled  the tiled model (its patches list point numbers); vertex lists cleared if asked
  /// \param[in] options    options
  /// \return the statistics (num_vertices = source.totalPoints ())
  /// \throws pcl_sparse::Error if a tile with patches has no point numbers or the grids differ
  ModelStatistics
  tiledModelStatistics (const TileSource& source, TiledModel& tiled,
                        const TiledStatisticsOptions& options = TiledStatisticsOptions ());
} // namespace pcl_sparse
