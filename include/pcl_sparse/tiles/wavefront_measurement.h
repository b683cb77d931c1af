#pragma once
/// \file wavefront_measurement.h
/// Measuring a tiled model while its tiles come in (issue 16): each tile is measured (its core points'
/// errors, TiledErrorSums::measureTile) as soon as the tiles around it are in, slab by slab along one axis
/// of the grid, and the patches' vertex lists go once every tile around theirs is measured. So the lists
/// are held for a band of tiles, not for the whole model, whoever encodes the tiles: the threads of one
/// process (TiledSurfaceEncoder) or the ranks of an mpirun (pcl_sparse_encode).

#include <pcl_sparse/model/tiled_model.h>
#include <pcl_sparse/tiles/tile_source.h>
#include <pcl_sparse/tiles/tile_statistics.h>

#include <cstddef>
#include <optional>
#include <vector>

namespace pcl_sparse
{
  /// \brief The axis a wavefront runs along: the one with the most tiles (ties: the later axis, z before y
  /// before x, so that the order stays closer to the tiles' numbers).
  /// \param[in] grid the grid
  int
  wavefrontAxis (const TileGrid& grid);

  /// \brief The order a wavefront measures tiles in: slab by slab along wavefrontAxis, ascending within a
  /// slab.
  /// \param[in] grid the grid
  /// \param[in] core core points per tile (tiles with none are left out)
  std::vector<std::size_t>
  wavefrontMeasuringOrder (const TileGrid& grid, const std::vector<std::size_t>& core);

  /// \brief Holds the tiles of a tiled encoding as they come in (add) and measures them in
  /// wavefrontMeasuringOrder, each as soon as the tiles around it are in. The tiles' error sums are added in
  /// ascending tile order, as tiledModelStatistics adds them, so the figures are its bit for bit whatever
  /// order the tiles come in (a tile measured ahead of a lower one keeps its sums, a few numbers, until then).
  /// Not thread-safe: one thread at a time, or a lock around every call; a tile can be measured between
  /// next and finish without the lock (add moves no other tile's patches).
  class WavefrontMeasurement
  {
  public:
    /// \param[in] source        the tiled input (point numbers, core points)
    /// \param[in] drop_vertices clear the patches' vertex lists once no tile left to measure needs them
    WavefrontMeasurement (const TileSource& source, bool drop_vertices);

    /// \brief Measures each tile against the patches of the tiles within \a reach steps (default 1: its
    /// neighbours), for tiles whose patches list points farther (TileEncoding::reach > 1: a mesh's triangles
    /// longer than the margin). Before the first add; throws Error after.
    void
    widen (int reach);

    /// \brief Takes every tile with core points at once (a phase-by-phase encoding), measured against the
    /// tiles as far as any of their patches reach (widen (farthestReach (tiles))). Before any add.
    void
    addAll (std::vector<TileEncoding> tiles);

    /// \brief Takes the encoding of a tile with core points (each such tile once, in any order).
    void
    add (TileEncoding tile);

    /// \brief Whether tile \a t is in.
    bool
    has (std::size_t t) const
    {
      return in_[t];
    }

    /// \brief Whether the tiles with core points around \a t (neighbourTiles) are in; the phase-0 ones only
    /// (tilePhase) if \a phase0_only.
    bool
    hasAround (std::size_t t, bool phase0_only) const;

    /// \brief Tile \a t's encoding as added (empty before).
    const TileEncoding&
    tile (std::size_t t) const
    {
      return tiles_[t];
    }

    /// \brief The next tile to measure, if the tiles around it are in: its number and the patches of the
    /// tiles around it (valid until finish; add does not move them). False when it must wait or all are
    /// measured.
    /// \param[out] t    the tile
    /// \param[out] near its patches and its neighbours', in model order, for TiledErrorSums::measureTile
    bool
    next (std::size_t& t, std::vector<TilePatches>& near) const;

    /// \brief Records the errors of the tile next gave (measured meanwhile, perhaps without the lock), adds
    /// what can be added in tile order and drops the vertex lists no tile left needs (with their tiles'
    /// TileEncoding::moved).
    /// \param[in] errors  TiledErrorSums::measureTile of the tile
    /// \param[in] seconds the time it took
    void
    finish (const TileErrors& errors, double seconds);

    /// \brief Measures every tile it can, in order, on this thread.
    void
    measureReady ();

    /// \brief Whether every tile with core points is measured.
    bool
    measuredAll () const
    {
      return next_ == order_.size ();
    }

    /// \brief The model of the tiles added (mergeTileEncodings), which are moved into it (their vertex lists
    /// dropped if asked and measured).
    TiledModel
    takeModel ();

    /// \brief The errors added so far.
    const TiledErrorSums& sums () const { return sums_; }
    /// \brief Seconds spent measuring (finish's, summed).
    double seconds () const { return seconds_; }
    /// \brief Most tiles holding vertex lists at once.
    std::size_t peakHeldTiles () const { return peak_held_tiles_; }
    /// \brief Most vertex listings held at once.
    std::size_t peakHeldVertices () const { return peak_held_vertices_; }
    /// \brief Most tiles whose error sums waited for a lower tile's at once.
    std::size_t peakPendingTiles () const { return peak_pending_tiles_; }

  private:
    const TileSource& source_;
    const bool drop_;
    std::vector<std::size_t> order_, ascending_, last_use_;  ///< measuring order; tiles in adding order; last user
    std::vector<std::vector<std::size_t>> near_;              ///< tiles with core points around each tile
    std::vector<TileEncoding> tiles_;
    std::vector<unsigned char> in_;                          ///< whether each tile is in (bytes: read unlocked)
    std::vector<std::size_t> held_;                          ///< vertex listings held per tile
    std::vector<std::optional<TileErrors>> pending_;         ///< sums of tiles measured before a lower tile
    TiledErrorSums sums_;
    double seconds_ = 0.0;
    std::size_t next_ = 0, next_add_ = 0;
    std::size_t held_tiles_ = 0, held_vertices_ = 0, pending_tiles_ = 0;
    std::size_t peak_held_tiles_ = 0, peak_held_vertices_ = 0, peak_pending_tiles_ = 0;
  };
} // namespace pcl_sparse
