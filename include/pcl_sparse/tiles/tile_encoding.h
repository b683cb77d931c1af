#pragma once
/// \file tile_encoding.h
/// Encoding one tile of a tiled input, and merging the tiles into one model (issue 16).
///
/// A tile is encoded from its margin box's input with the ordinary encoder and the same options, except:
///  - only points of the tile's core (TileGrid::tileOf) seed patches, and the encoder covers every one of
///    them (SparseSurfaceEncoder::setSeedVertices): the tile owns exactly the patches seeded in its core,
///    the margin is surface they may grow over, and every input point is covered by its own tile's
///    patches, so seams have no gap;
///  - tiles are encoded in two phases (a checkerboard, tilePhase): a phase-1 tile knows which of its points
///    the phase-0 tiles' patches cover (those seed nothing and need no patch of its own), so the band along
///    a seam is covered once, as in an untiled encoding;
///  - rho, a fraction of the surface's area, is rescaled to the tile: rho x (points of the whole input) /
///    (points of the tile's input), so patches are as large as in an untiled encoding of the same density.
/// Per-model fields are the whole input's: the vertex count, the bounding-box diagonal (union of the tiles'
/// core bounds) and each attribute channel's range (union over the tiles), so the file tolerance and the
/// statistics do not depend on the tiling. Each tile's encoding depends only on the tile's input, the
/// options and (phase 1) the phase-0 patches, never on which process or thread encodes it.

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/model/tiled_model.h>
#include <pcl_sparse/tiles/tile_source.h>
#include <pcl_sparse/tiles/tile_statistics.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <functional>
#include <vector>

namespace pcl_sparse
{
  /// \brief The phase of tile \a t, 0 or 1: the parity of i + j + k, so that tiles sharing a face are in
  /// different phases. Phase-1 tiles are encoded knowing which of their points phase-0 tiles' patches cover
  /// (encodeTile's \a covered), so the band along a seam is not covered twice.
  /// \param[in] grid the grid
  /// \param[in] t    the tile
  inline int
  tilePhase (const TileGrid& grid, std::size_t t)
  {
    return grid.coordinates (t).sum () % 2;
  }

  /// \brief Whether \a tile is a phase-0 tile whose patches list points beyond its neighbours
  /// (TileEncoding::reach > 1): then the phase-1 tiles next to it cannot be encoded once only its
  /// neighbours are done, and the encoding falls back to phase by phase (encodeTilesByPhase).
  /// \param[in] grid the grid
  /// \param[in] tile an encoding of a tile of \a grid
  inline bool
  reachesBeyondNeighbours (const TileGrid& grid, const TileEncoding& tile)
  {
    return tilePhase (grid, tile.tile) == 0 && tile.reach > 1;
  }

  /// \brief Whether a wavefront encoding (tiles encoded, and measured, as the tiles around them come in) must
  /// start again phase by phase on meeting \a tile: reachesBeyondNeighbours, or, when the tiles are measured,
  /// any tile whose patches list points beyond its neighbours (a tile is measured against its neighbours'
  /// patches, and a phase-1 tile's far listings were left out of the statistics).
  /// \param[in] grid      the grid
  /// \param[in] tile      an encoding of a tile of \a grid
  /// \param[in] measured  whether the tiles are measured as they come (WavefrontMeasurement)
  inline bool
  wavefrontMustRestart (const TileGrid& grid, const TileEncoding& tile, bool measured)
  {
    return reachesBeyondNeighbours (grid, tile) || (measured && tile.reach > 1);
  }

  /// \brief The input points (their numbers in the whole input, ascending, distinct) the patches of
  /// \a tiles cover.
  /// \param[in] tiles encodings (of phase 0)
  std::vector<std::size_t>
  coveredPoints (const std::vector<TileEncoding>& tiles);

  /// \brief The input points the patches of \a tiles cover, as above.
  /// \param[in] tiles encodings (of phase 0), not null
  std::vector<std::size_t>
  coveredPoints (const std::vector<const TileEncoding*>& tiles);

  /// \brief The largest TileEncoding::reach of \a tiles, at least 1: how far the tiles to measure each point
  /// against lie (WavefrontMeasurement::widen, TiledStatisticsOptions::reach).
  int
  farthestReach (const std::vector<TileEncoding>& tiles);

  /// \brief Encodes tile \a t of \a source (see the file's comment).
  /// \param[in] source       the tiled input
  /// \param[in] t            the tile
  /// \param[in] options      the encoder's options, as for the whole input (validated)
  /// \param[in] num_threads  OpenMP threads (0 = default); the result does not depend on it
  /// \param[in] covered      points (numbers in the whole input, ascending) that patches of other tiles
  ///                         already cover (coveredPoints of phase 0 for a phase-1 tile): they seed no
  ///                         patch and need none; empty (default) for phase 0
  /// \param[in] keep_xy      keep the patches' PatchCode::vertex_xy (default); false where the vertex lists
  ///                         are held for the statistics only, which recompute (x', y') from the points
  ///                         (TiledErrorSums::measureTile): 4 bytes a listing instead of 20
  /// \return the tile's patches (none when its core has no point or its input no surface, or when a scan
  ///         tile of fewer than 256 points makes no surface: a few stray points, left in no patch)
  /// \throws pcl_sparse::Error naming the tile when its encoding fails
  TileEncoding
  encodeTile (const TileSource& source, std::size_t t, const SparseSurfaceEncoderOptions& options, int num_threads = 0,
              const std::vector<std::size_t>& covered = {}, bool keep_xy = true);

  /// \brief Encodes several tiles (encodeTile), in parallel over the tiles when \a num_threads allows
  /// (each tile's encoder then runs on one thread: the sampling loop is sequential, so tiles side by side
  /// use the cores better than threads inside one tile). The result does not depend on \a num_threads.
  /// \param[in] source       the tiled input
  /// \param[in] tiles        the tiles, in the order of the result
  /// \param[in] options      the encoder's options
  /// \param[in] num_threads  OpenMP threads (0 = default)
  /// \param[in] covered      as for encodeTile, for the phase-1 tiles (tilePhase) of \a tiles; phase-0 tiles
  ///                         are encoded without (they cover first), so one call can take both
  /// \param[in] progress     called with the number of tiles done (may be empty)
  /// \param[in] keep_xy      as for encodeTile
  /// \return one encoding per tile
  /// \throws pcl_sparse::Error of the first tile (in \a tiles' order) that fails
  std::vector<TileEncoding>
  encodeTiles (const TileSource& source, const std::vector<std::size_t>& tiles, const SparseSurfaceEncoderOptions& options,
               int num_threads = 0, const std::vector<std::size_t>& covered = {},
               const std::function<void (std::size_t)>& progress = {}, bool keep_xy = true);

  /// \brief Every tile with core points, encoded phase by phase (encodeTiles): the phase-1 tiles knowing what
  /// the whole phase 0 covers. What TiledSurfaceEncoder falls back to when a tile's patches list
  /// points beyond its neighbours (wavefrontMustRestart).
  /// \param[in] source       the tiled input
  /// \param[in] options      the encoder's options
  /// \param[in] num_threads  OpenMP threads (0 = default)
  /// \param[in] progress     called with the fraction of tiles done (may be empty)
  /// \param[in] keep_xy      as for encodeTile
  /// \return one encoding per tile with core points, phase 0 first
  std::vector<TileEncoding>
  encodeTilesByPhase (const TileSource& source, const SparseSurfaceEncoderOptions& options, int num_threads = 0,
                      const std::function<void (double)>& progress = {}, bool keep_xy = true);

  /// \brief The whole model from its tiles' encodings (patches in tile order; whole-input vertex count,
  /// diagonal and attribute ranges). The model's attribute channels are every tile's: a tile whose points
  /// have no value in a channel (left out by fillAttributeGaps) gives its patches codes without atoms there,
  /// which resample as 0 clamped to the channel's range (its lower bound when every value is positive).
  /// \param[in] grid          the grid
  /// \param[in] total_points  points of the whole input (TileSource::totalPoints)
  /// \param[in] tiles         encodings of every tile with core points, in any order
  /// \return the tiled model
  /// \throws pcl_sparse::Error for a tile twice or tiles with different bases
  TiledModel
  mergeTileEncodings (const TileGrid& grid, std::size_t total_points, std::vector<TileEncoding> tiles);

  /// \brief Whether the merged model \a tiled of \a total_points input points exceeds \a options'
  /// compression bound (0: none): then its tiles are encoded again, each bounded over its core points.
  bool
  tiledEncodingOverTheBound (const TiledModel& tiled, std::size_t total_points, const SparseSurfaceEncoderOptions& options);

  /// \brief Tiled encoding as a stage: setTileSource, setOptions, compute (TiledModel&).
  class TiledSurfaceEncoder : public StageBase
  {
  public:
    using Ptr = std::shared_ptr<TiledSurfaceEncoder>;
    using ConstPtr = std::shared_ptr<const TiledSurfaceEncoder>;

    TiledSurfaceEncoder () : StageBase ("TiledSurfaceEncoder") {}

    /// \brief The tiled input (MemoryTileSource, or a file-backed source).
    void setTileSource (const std::shared_ptr<const TileSource>& source) { source_ = source; }
    /// \brief The encoder's options (as for an untiled encoding).
    void setOptions (const SparseSurfaceEncoderOptions& options) { options_ = options; }
    const SparseSurfaceEncoderOptions& getOptions () const { return options_; }

    /// \brief Measure the model against its input while encoding (default false), as tiledModelStatistics
    /// does after it: getStatistics () then has its figures, bit for bit; with \a options.drop_vertices the
    /// patches' vertex lists go as soon as every tile around theirs is measured, so they are held for a band
    /// of tiles at a time (see compute), not for the whole model, and without their (x', y') (encodeTile's
    /// keep_xy).
    /// \param[in] measure whether to measure
    /// \param[in] options what to keep
    void
    setMeasurement (bool measure, const TiledStatisticsOptions& options = TiledStatisticsOptions ())
    {
      measure_ = measure;
      statistics_options_ = options;
    }

    /// \brief Encodes every tile with core points and merges them. Throws pcl_sparse::Error for a missing
    /// source or a tile that fails (the lowest such tile).
    ///
    /// A wavefront: the tiles are measured slab by slab along the grid's axis with the most tiles, each as
    /// soon as the tiles around it are encoded, and encoded just ahead of that: for each tile in turn, the
    /// tiles around it not yet encoded, a phase-1 tile (tilePhase) after the phase-0 tiles around it, whose
    /// patches tell it what they cover (coveredPoints). Up to the stage's threads tiles are encoded side by
    /// side, one thread each, taken from the next few in that order. So vertex lists are held for about
    /// three slabs of tiles plus the phase-0 tiles of a fourth, whatever the grid's length. The errors are
    /// added in tile order, as tiledModelStatistics adds them (a tile measured ahead of a lower one keeps its
    /// errors, a double a point, until then: none when the slabs run along z). The patches do not depend on
    /// the order: a phase-1 tile sees the same covered points as after the whole phase 0 (patches list
    /// points of their tile's neighbours only; a phase-0 tile whose patches reach farther, a mesh with
    /// triangles longer than the margin, makes the encoder start again phase by phase). So the model is the
    /// same for any number of threads.
    ///
    /// The compression bound (SparseSurfaceEncoderOptions::max_compression_ratio) holds for the whole model:
    /// the tiles are encoded unbounded first, and again, each bounded over its own core points, only if the
    /// whole exceeds it (tiledEncodingOverTheBound). Bounded from the start, a sparse tile of a scan (more
    /// surface than its share of the points) coded an atom a patch (docs/TILES.md).
    /// \param[out] model the tiled model
    void compute (TiledModel& model);

    /// \brief Seconds each tile took in the last compute, one per tile of the grid (0: not encoded).
    const std::vector<double>& getTileSeconds () const { return tile_seconds_; }

    /// \brief The statistics of the last compute (with setMeasurement (true)).
    const ModelStatistics& getStatistics () const { return statistics_; }

    /// \brief Seconds the last compute spent measuring (with setMeasurement (true)), over all threads.
    double getMeasurementSeconds () const { return measurement_seconds_; }

    /// \brief Most tiles whose patches' vertex lists were held at once in the last compute (encoded and not
    /// yet dropped; every encoded tile without setMeasurement's drop_vertices).
    std::size_t getPeakHeldTiles () const { return peak_held_tiles_; }

    /// \brief Most vertex listings (entries of PatchCode::vertices; with their (x', y') only without
    /// setMeasurement's drop_vertices) held at once.
    std::size_t getPeakHeldVertices () const { return peak_held_vertices_; }

    /// \brief Most tiles measured ahead of a lower tile at once, their error sums (a few numbers a tile)
    /// waiting to be added in tile order.
    std::size_t getPeakPendingTiles () const { return peak_pending_tiles_; }

  private:
    /// One encoding of every tile with \a options (compute's wavefront, or phase by phase).
    void encodeAll (const SparseSurfaceEncoderOptions& options, TiledModel& model);

    std::shared_ptr<const TileSource> source_;
    SparseSurfaceEncoderOptions options_;
    bool measure_ = false;
    TiledStatisticsOptions statistics_options_;
    std::vector<double> tile_seconds_;
    ModelStatistics statistics_;
    double measurement_seconds_ = 0.0;
    std::size_t peak_held_tiles_ = 0, peak_held_vertices_ = 0, peak_pending_tiles_ = 0;
  };
} // namespace pcl_sparse
