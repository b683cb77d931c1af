#pragma once
/// \file tool_tiled_encoding.h
/// The tiled encoding across the processes of an mpirun (issue 16), or by one process alone: the model
/// and its statistics on rank 0, byte for byte the same for any number of processes.

#include "tool_processes.h"

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/model/tiled_model.h>
#include <pcl_sparse/tiles/tile_source.h>
#include <pcl_sparse/tiles/tile_statistics.h>

#include <cstddef>

namespace pcl_sparse
{
  namespace tools
  {
    /// What a tiled encoding took.
    struct TiledEncodingReport
    {
      double coding = 0.0;             ///< seconds: the slowest rank's tiles, step by step (one process: all of it)
      double statistics = 0.0;         ///< seconds measuring the model against its input
      std::size_t held_tiles = 0;      ///< most tiles whose vertex lists rank 0 held at once
      std::size_t held_listings = 0;   ///< most vertex listings rank 0 held at once
      std::size_t pending_tiles = 0;   ///< most tiles whose error sums waited to be added in tile order
    };

    /// \brief The tiled encoding of \a source by the processes of \a group, and its statistics against the
    /// input (tiledModelStatistics' figures). One process encodes and measures in a wavefront
    /// (TiledSurfaceEncoder), so the patches' vertex lists are held for a band of tiles only. Several go
    /// slab by slab along the grid's wavefrontAxis, in steps: at step s each rank encodes its share
    /// (tileRanks: static, by points) of the phase-0 tiles of slab s and of the phase-1 tiles of slab s - 2,
    /// with \a threads threads; then each rank sends what its new phase-0 tiles cover to the ranks with
    /// phase-1 tiles around them, and its tiles to rank 0, which measures every tile once the tiles around
    /// it are in and then drops the vertex lists no tile left needs (WavefrontMeasurement). So every rank
    /// holds a few slabs of tiles at a time. When a phase-0 tile's patches reach beyond its neighbours (a
    /// mesh with triangles longer than the margin) the ranks start again phase by phase, every rank
    /// receiving all of phase 0 and rank 0 all of phase 1, as TiledSurfaceEncoder falls back. The result is
    /// the same for any number of processes and threads.
    /// \param[in] group      the processes
    /// \param[in] source     the tiled input (the same on every rank)
    /// \param[in] options    the encoder's options
    /// \param[in] threads    OpenMP threads per process (0 = default)
    /// \param[in] quiet      no progress lines
    /// \param[in] statistics_options whether the vertex lists go once measured
    /// \param[out] tiled     on rank 0: the tiled model (untouched elsewhere)
    /// \param[out] stats     on rank 0: its statistics
    /// \return the seconds taken and the vertex lists held (on rank 0)
    TiledEncodingReport
    encodeTilesAcross (const ProcessGroup& group, const TileSource& source, const SparseSurfaceEncoderOptions& options,
                       int threads, bool quiet, const TiledStatisticsOptions& statistics_options, TiledModel& tiled,
                       ModelStatistics& stats);
  } // namespace tools
} // namespace pcl_sparse
