#pragma once
/// \file spilled_tile_source.h
/// Tiles of a scan file larger than memory (issue 16): the file is streamed twice, once for its bounding box
/// and point count, once to append every point to a temporary file per tile; a tile's points are read back
/// from its file when asked for. Memory stays bounded by the write buffers, one chunk of the file and one
/// tile's points (counting its duplicates, or loading it), not by the number of points in the file (for the
/// formats ScanStreamReader streams; the others are read whole first).

#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/io/scan_cleaning.h>
#include <pcl_sparse/tiles/tile_source.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  namespace tiles_detail
  {
    class SpillDirectory;
  } // namespace tiles_detail

  /// Options of SpilledTileSource / spillIntoTiles.
  struct SpillOptions
  {
    /// How the grid is chosen (from the bounding box and number of the cleaned points).
    TileGridOptions grid;
    /// Cleaning, as loadScanCloud's (non-finite points are always dropped).
    ScanCleaningOptions cleaning;
    /// Folder in which the temporary spill directory is made ("": the system's, $TMPDIR or /tmp). The spill
    /// files take about (1 + overlap of the margins) x points x (32 bytes + the attributes) on disk.
    std::string directory;
    /// Bytes of the write buffers of all tiles together (each tile gets an equal share, at least one point).
    std::size_t buffer_bytes = std::size_t (64) << 20;
    /// Points read from the input file at a time.
    std::size_t chunk_points = 1 << 16;
    /// Called with "spill: reading" (pass 1), "spill: binning" (pass 2) and "spill: counting" (the tiles'
    /// duplicates), or for a mesh "spill: vertices", and the fraction done; may be empty.
    ProgressCallback progress;
  };

  /// \brief A TileSource backed by one temporary file per tile, made from a scan file by streaming it.
  ///
  /// Construction reads the file twice with ScanStreamReader: pass 1 drops what cleaning drops point by point
  /// (non-finite, at the sensor) and takes the bounding box and count of the rest, from which makeTileGrid
  /// (options.grid) makes the grid, in the file's frame; pass 2 appends each such point to the file of every
  /// tile tilesHolding gives (its margin boxes and its owner; up to 8), in file order. Then each tile's file
  /// is read once to count exact duplicates among the points it owns (for totalPoints and corePoints); if the
  /// true count changes the grid makeTileGrid gives, the file is binned again on the new grid, so the grid is
  /// makeTileGrid (box, totalPoints ()) as for the same input cleaned in memory.
  ///
  /// loadTile (t) reads tile t's file back, cleans it with cleanScan (which merges the duplicates) and moves
  /// it to its own local frame (centreScan). It equals the cut of the whole input cleaned by loadScanCloud:
  /// cleaning point by point commutes with cutting, and exact duplicates have one position, hence the same
  /// tiles, so each tile keeps the first of them in file order, as whole-input cleaning does. Its
  /// point_numbers are the points' ranks in the cleaned input, as MemoryTileSource's: pass 1 notes the runs
  /// of file indices it drops and the counting pass the file indices of the duplicates merging removes
  /// (memory in the number of such runs and duplicates, not of points).
  ///
  /// The spill directory is removed by the destructor, and when construction throws.
  class SpilledTileSource : public TileSource
  {
  public:
    using Ptr = std::shared_ptr<SpilledTileSource>;
    using ConstPtr = std::shared_ptr<const SpilledTileSource>;

    /// Spills the scan file \a path (any file ScanStreamReader reads) into tiles. Throws pcl_sparse::Error
    /// for a file ScanStreamReader refuses (missing, truncated, bad header), a file with no point left
    /// after cleaning, bad options, or a spill file that cannot be written (full disk); no spill file is
    /// left behind then.
    explicit SpilledTileSource (const std::string& path, const SpillOptions& options = SpillOptions ());
    ~SpilledTileSource () override;
    SpilledTileSource (const SpilledTileSource&) = delete;
    SpilledTileSource& operator= (const SpilledTileSource&) = delete;

    const TileGrid&
    grid () const override
    {
      return grid_;
    }

    /// Points of the whole input after cleaning (cleaningReport ().kept).
    std::size_t
    totalPoints () const override
    {
      return report_.kept;
    }

    /// Points after cleaning that tile \a t owns (grid ().tileOf (p) == t; a point on a border between core
    /// boxes is counted once, for the higher tile): the corePoints of all tiles add up to totalPoints ().
    std::size_t
    corePoints (std::size_t t) const override;

    /// Tile \a t's points in file order (see the class comment); an empty TileInput for a tile nothing falls
    /// in. The scan has the input's fields and sensor pose, indices into the input file, width = its size,
    /// height = 1, and report.input_points = report.kept = its size (a cut of the cleaned input; what
    /// cleaning removed is in cleaningReport ()). Safe to call from several threads.
    TileInput
    loadTile (std::size_t t) const override;

    /// What cleaning removed from the whole input (as loadScanCloud's report for the same file).
    const ScanCleaningReport&
    cleaningReport () const
    {
      return report_;
    }

    /// Points written to tile \a t's spill file (margin copies included, duplicates not yet merged).
    std::size_t
    spilledPoints (std::size_t t) const;

    /// Bytes in all spill files.
    std::size_t
    spilledBytes () const;

    /// False if the input's format could not be streamed and was read whole (ScanStreamReader::isStreamed).
    bool
    wasStreamed () const
    {
      return streamed_;
    }

    /// The temporary directory holding the spill files.
    const std::string&
    directory () const;

  private:
    struct Impl;
    std::unique_ptr<tiles_detail::SpillDirectory> directory_;
    std::unique_ptr<const Impl> impl_;
    TileGrid grid_;
    ScanCleaningReport report_;
    std::vector<std::size_t> core_points_;
    bool streamed_ = true;
  };

  /// SpilledTileSource (path, options) as a shared pointer: the file-backed TileSource of a scan file.
  SpilledTileSource::Ptr
  spillIntoTiles (const std::string& path, const SpillOptions& options = SpillOptions ());
} // namespace pcl_sparse
