#pragma once
/// \file tiled_model.h
/// A model encoded tile by tile (issue 16): the whole model (the tiles' patches concatenated in tile
/// order, with the whole input's vertex count, bounding-box diagonal and attribute ranges), the grid, and
/// which patches each tile owns. The tiled .psm file (format/tiled_model_file.h) stores each tile apart.

#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/model/tile_grid.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Input points an encoder coded elsewhere than the input holds them: a scan whose depth steps it took out
  /// (depth_steps_removal.h) moves them along their lines of sight, by up to half a step.
  struct MovedPoints
  {
    std::vector<std::size_t> numbers;     ///< their numbers in the whole input, ascending
    std::vector<Eigen::Vector3f> offsets; ///< coded world position - input world position (a few cm: float)
  };

  /// The patches one tile owns: model.patches[first_patch, first_patch + num_patches).
  struct TileRange
  {
    std::size_t tile = 0;         ///< tile number in the grid
    std::size_t first_patch = 0;  ///< number of its first patch in the whole model
    std::size_t num_patches = 0;  ///< patches whose seed lies in the tile's core box
    /// The points they list that the tile's encoder coded elsewhere (TileEncoding::moved), for
    /// tiledModelStatistics, which drops them with the vertex lists; empty in a loaded model.
    MovedPoints moved;
  };

  /// One encoded tile (tile_encoding.h).
  struct TileEncoding
  {
    std::size_t tile = 0;                 ///< tile number
    SparseSurfaceModel model;             ///< its patches (vertices numbered in the whole input, which
                                          ///< num_input_vertices counts)
    Eigen::AlignedBox3d core_bounds;      ///< bounding box of its core points (empty if none)
    double seconds = 0.0;                 ///< wall-clock seconds the encoding took
    /// Tiles, along any axis, from this tile to the farthest one whose core holds a point its patches list:
    /// 1 (its neighbours) unless a mesh's triangles are longer than the margin; 0 when not known (decoded).
    int reach = 0;
    /// The points its patches list that its encoder coded elsewhere than the input holds them (with point
    /// numbers only), for the statistics, which evaluate each patch where it coded them, as an untiled
    /// encoding does (TilePatches::moved); dropped with the vertex lists.
    MovedPoints moved;
  };

  /// A tiled model, or the part of one that was loaded (a region: some tiles only).
  struct TiledModel
  {
    TileGrid grid;                   ///< the grid the input was cut along
    SparseSurfaceModel model;        ///< the patches of the tiles below, in their order
    std::vector<TileRange> tiles;    ///< tiles with patches, ascending; ranges into the whole model
    std::size_t total_patches = 0;   ///< patches of the whole model (more than model's for a region)

    /// For each patch of \a model, its number in the whole model (as resampling keys use it,
    /// SparseSurfaceResamplingBase::setPatchNumbers), so a region resamples as the whole model does there.
    std::vector<std::size_t> patchNumbers () const;
  };

  /// \brief The patches of tile range \a range as a model of their own (same basis, vertex count, diagonal,
  /// footprint step and attribute channels as \a model; \a count 0: those alone, to add patches to).
  /// \param[in] model the whole model
  /// \param[in] first first patch
  /// \param[in] count number of patches
  /// \return the sub-model
  SparseSurfaceModel
  subModel (const SparseSurfaceModel& model, std::size_t first, std::size_t count);

  /// \brief A box holding every point patch \a patch can give in resampling and every place it can compete
  /// for there (with the default PatchOwnershipOptions, or any with max_height <= 1 and height_tolerance <=
  /// 0.25): s + r R (x, y, z) with (x, y) in the disk of its largest footprint extent and |z| at most
  /// min (PatchCode::heightBound, 1) + 0.25.
  /// \param[in] patch the patch (frame orthonormal)
  /// \param[in] basis the basis its code is over (the model's)
  /// \return the box
  Eigen::AlignedBox3d
  patchReachBox (const PatchCode& patch, const SurfaceBasis& basis);
} // namespace pcl_sparse
