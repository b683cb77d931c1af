// Tiled models (issue 16): tiles cut from an input in memory, the tiled encoding (ownership, coverage,
// seams, determinism), the tiled file (index, loadModel compatibility, region decode equal to the same
// region of a full decode, bytes read) and, on a shared mesh, tiled against untiled figures.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/file_tolerance.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/format/tile_encoding_bytes.h>
#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/format/zstd_codec.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>
#include <pcl_sparse/tiles/memory_tile_source.h>
#include <pcl_sparse/tiles/tile_encoding.h>
#include <pcl_sparse/tiles/tile_statistics.h>

#include <pcl/kdtree/kdtree_flann.h>

#include <gtest/gtest.h>

#include "generated_clouds.h"
#include "test_file_helpers.h"
#include "shared_data.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

using namespace pcl_sparse;

namespace
{
  /// A wavy terrain over [-1, 1]^2 (a height field: seams are easy to look at from above).
  TriangleMesh::Ptr
  terrain (int cells)
  {
    return std::make_shared<TriangleMesh> (makeHeightFieldGrid (cells, cells, 1.0, 1.0, [] (double x, double y) {
      return 0.06 * std::sin (9.0 * x) * std::cos (8.0 * y) + 0.05 * x * y;
    }));
  }

  /// \a n points drawn uniformly over [-1, 1]^2 (seed \a seed) at heights height (x, y, draw), draw () giving
  /// the next uniform number in [-1, 1] (for noise).
  template <typename Height>
  std::vector<Eigen::Vector3d>
  squarePoints (int n, unsigned seed, Height height)
  {
    std::mt19937 mt (seed);
    std::uniform_real_distribution<double> u (-1.0, 1.0);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < n; ++i)
    {
      const double x = u (mt), y = u (mt);
      points.emplace_back (x, y, height (x, y, [&] { return u (mt); }));
    }
    return points;
  }

  /// An unorganized scan of \a points (local frame = file frame, no sensor pose unless set after).
  std::shared_ptr<ScanCloud>
  listScan (const std::vector<Eigen::Vector3d>& points)
  {
    auto scan = std::make_shared<ScanCloud> ();
    scan->positions = points;
    scan->width = static_cast<std::uint32_t> (points.size ());
    scan->height = 1;
    return scan;
  }

  /// \a scan encoded in tiles (TiledSurfaceEncoder over a MemoryTileSource, default options).
  TiledModel
  encodeInTiles (const std::shared_ptr<ScanCloud>& scan, int tiles_along_longest)
  {
    TileGridOptions grid;
    grid.tiles_along_longest = tiles_along_longest;
    TiledSurfaceEncoder encoder;
    encoder.setTileSource (std::make_shared<MemoryTileSource> (scan, grid));
    TiledModel tiled;
    encoder.compute (tiled);
    return tiled;
  }

  /// Every tile with core points encoded with \a options, written out here (not encodeTilesByPhase, the
  /// encoder's own fallback): phase 0, then phase 1 knowing what phase 0 covers. TiledSurfaceEncoder encodes
  /// without the compression bound first and applies it only when the whole model exceeds it; a tile that
  /// exceeds it on its own is trimmed here with default options and not there.
  std::vector<TileEncoding>
  encodeTilesPhaseByPhase (const TileSource& source, const SparseSurfaceEncoderOptions& options = SparseSurfaceEncoderOptions ())
  {
    std::vector<TileEncoding> tiles;
    std::vector<std::size_t> covered;
    for (int phase = 0; phase < 2; ++phase)
    {
      if (phase == 1)
        covered = coveredPoints (tiles);
      for (std::size_t t = 0; t < source.grid ().size (); ++t)
        if (tilePhase (source.grid (), t) == phase && source.corePoints (t) > 0)
          tiles.push_back (encodeTile (source, t, options, 1, covered));
    }
    return tiles;
  }

  /// The farthest TileEncoding::reach among the tiles of \a phase.
  int
  farthestReachOfPhase (const TileGrid& grid, const std::vector<TileEncoding>& tiles, int phase)
  {
    int farthest = 0;
    for (const TileEncoding& tile : tiles)
      if (tilePhase (grid, tile.tile) == phase)
        farthest = std::max (farthest, tile.reach);
    return farthest;
  }

  /// \a source encoded by the measuring TiledSurfaceEncoder (2 threads) into \a tiled; returns its statistics.
  ModelStatistics
  encodeMeasuring (const TileSource& source, const SparseSurfaceEncoderOptions& options, TiledModel& tiled)
  {
    TiledSurfaceEncoder encoder;
    encoder.setTileSource (std::shared_ptr<const TileSource> (&source, [] (const TileSource*) {}));
    encoder.setOptions (options);
    encoder.setNumberOfThreads (2);
    encoder.setMeasurement (true);
    encoder.compute (tiled);
    return encoder.getStatistics ();
  }

  /// Expects the measuring TiledSurfaceEncoder (2 threads) to give \a expected's file and the statistics of
  /// \a expected's patches over \a vertices, the input's; returns its statistics.
  ModelStatistics
  expectMeasuringEncoderGives (const TileSource& source, const std::vector<Eigen::Vector3d>& vertices,
                               const TiledModel& expected)
  {
    TiledModel tiled;
    const ModelStatistics measured = encodeMeasuring (source, SparseSurfaceEncoderOptions (), tiled);
    EXPECT_TRUE (encodeTiledModel (tiled, ModelWriteOptions (), 1) == encodeTiledModel (expected, ModelWriteOptions (), 1));
    const ModelStatistics truth = expected.model.statistics (vertices);
    EXPECT_GT (truth.rmse, 0.0);  // else the relative tolerances below are 0 and NaN passes nothing, but 0 == 0 does
    EXPECT_NEAR (measured.rmse, truth.rmse, 1e-12 * truth.rmse);
    EXPECT_NEAR (measured.max_error, truth.max_error, 1e-12 * truth.max_error);
    EXPECT_EQ (measured.uncovered, truth.uncovered);
    return measured;
  }

  /// The tiled encoding of \a mesh with \a along tiles along its longest side.
  TiledModel
  encodeTiled (const TriangleMesh::Ptr& mesh, int along, int threads = 0)
  {
    TileGridOptions grid;
    grid.tiles_along_longest = along;
    auto source = std::make_shared<MemoryTileSource> (mesh, grid);
    TiledSurfaceEncoder encoder;
    encoder.setTileSource (source);
    encoder.setNumberOfThreads (threads);
    TiledModel tiled;
    encoder.compute (tiled);
    return tiled;
  }

  /// Points of \a model resampled at \a density, with patch numbers \a numbers (empty: their own).
  pcl::PointCloud<pcl::PointNormal>
  resample (const SparseSurfaceModel& model, double density, const std::vector<std::size_t>& numbers = {})
  {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (std::make_shared<const SparseSurfaceModel> (model));
    resampling.setDensity (density);
    resampling.setPatchNumbers (numbers);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    return cloud;
  }

  /// Bytes of the header, shared sections, index and index checksum of a version-3 tiled file.
  std::size_t
  indexBytes (const std::vector<std::uint8_t>& file)
  {
    auto u32 = [&] (std::size_t at) {
      return static_cast<std::size_t> (file[at] | (file[at + 1] << 8) | (file[at + 2] << 16) |
                                       (static_cast<std::uint32_t> (file[at + 3]) << 24));
    };
    return 116 + u32 (104) + u32 (108) + 4;
  }

  /// \a tiled written in the version-2 layout of docs/FORMAT.md (the library writes version 3 only). Each
  /// tile's bytes are its encoded model, or \a tile_bytes given in their place (one per tile).
  std::vector<std::uint8_t>
  version2File (const TiledModel& tiled, const ModelWriteOptions& options,
                std::vector<std::vector<std::uint8_t>> tile_bytes = {})
  {
    auto put = [] (std::vector<std::uint8_t>& out, const void* value, std::size_t size) {
      const auto* bytes = static_cast<const std::uint8_t*> (value);
      out.insert (out.end (), bytes, bytes + size);  // little-endian machine, as the format
    };
    auto crc = [] (const std::uint8_t* data, std::size_t size) {
      std::uint32_t c = 0xffffffffu;
      for (std::size_t i = 0; i < size; ++i)
      {
        c ^= data[i];
        for (int k = 0; k < 8; ++k)
          c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
      }
      return c ^ 0xffffffffu;
    };
    std::vector<std::vector<std::uint8_t>> blobs = std::move (tile_bytes);
    if (blobs.empty ())
      for (const TileRange& range : tiled.tiles)
        blobs.push_back (encodeModel (subModel (tiled.model, range.first_patch, range.num_patches), options));
    std::vector<std::uint8_t> out;
    const std::uint8_t magic[8] = {0x89, 'P', 'S', 'M', '\r', '\n', 0x1a, '\n'};
    put (out, magic, 8);
    const std::uint16_t version = 2, flags = 0;
    put (out, &version, 2);
    put (out, &flags, 2);
    const std::uint32_t count = static_cast<std::uint32_t> (tiled.tiles.size ());
    put (out, &count, 4);
    const std::uint64_t vertices = tiled.model.num_input_vertices, patches = tiled.model.patches.size ();
    put (out, &vertices, 8);
    put (out, &tiled.model.bbox_diagonal, 8);
    put (out, &options.tolerance, 8);
    put (out, tiled.grid.origin.data (), 24);
    put (out, &tiled.grid.edge, 8);
    put (out, &tiled.grid.margin, 8);
    for (int a = 0; a < 3; ++a)
    {
      const std::uint32_t n = static_cast<std::uint32_t> (tiled.grid.counts[a]);
      put (out, &n, 4);
    }
    put (out, &patches, 8);
    const std::uint32_t header_crc = crc (out.data (), out.size ());
    put (out, &header_crc, 4);
    const std::size_t start = out.size ();
    std::uint64_t offset = 104 + 88 * count + 4;
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::uint64_t entry[5] = {tiled.tiles[i].tile, tiled.tiles[i].first_patch, tiled.tiles[i].num_patches, offset,
                                      blobs[i].size ()};
      put (out, entry, sizeof entry);
      offset += blobs[i].size ();
      Eigen::AlignedBox3d reach;
      const SparseSurfaceModel decoded = decodeModel (blobs[i].data (), blobs[i].size ());
      for (const PatchCode& patch : decoded.patches)
        reach.extend (patchReachBox (patch, *decoded.basis));
      const Eigen::Vector3d lo = reach.min ().array () - options.tolerance * tiled.model.bbox_diagonal;
      const Eigen::Vector3d hi = reach.max ().array () + options.tolerance * tiled.model.bbox_diagonal;
      put (out, lo.data (), 24);
      put (out, hi.data (), 24);
    }
    const std::uint32_t index_crc = crc (out.data () + start, out.size () - start);
    put (out, &index_crc, 4);
    for (const std::vector<std::uint8_t>& blob : blobs)
      out.insert (out.end (), blob.begin (), blob.end ());
    return out;
  }

  /// The points of \a cloud inside \a box, in order.
  std::vector<Eigen::Vector3f>
  inside (const pcl::PointCloud<pcl::PointNormal>& cloud, const Eigen::AlignedBox3d& box)
  {
    std::vector<Eigen::Vector3f> points;
    for (const pcl::PointNormal& p : cloud)
      if (box.contains (p.getVector3fMap ().cast<double> ()))
        points.push_back (p.getVector3fMap ());
    return points;
  }
} // namespace

TEST (TileGrid, MinTilesCutsSmallerTilesDownToMinTilePoints)
{
  // A terrain's box: 1000 x 1000 m, 80 m of relief. Its area estimate is 0.5 (1e6 + 1e6 + 2 x 80,000) m^2.
  const Eigen::AlignedBox3d box (Eigen::Vector3d (0.0, 0.0, -40.0), Eigen::Vector3d (1000.0, 1000.0, 40.0));
  TileGridOptions options;
  options.points_per_tile = 250000;  // what -memory 2G gives
  // Without min_tiles: edge sqrt (1.08e6 x 250,000 / 20 M) = 116 m, 9 x 9 x 1 tiles.
  EXPECT_EQ (makeTileGrid (box, 20000000, options).counts, Eigen::Vector3i (9, 9, 1));
  options.min_tiles = 400;
  // 20 M / 400 = 50,000 points a tile: edge 52 m, 20 x 20 tiles (two layers for the relief).
  const TileGrid twenty = makeTileGrid (box, 20000000, options);
  EXPECT_NEAR (twenty.edge, std::sqrt (1.08e6 * 50000.0 / 20e6), 1e-9);
  EXPECT_EQ (twenty.counts, Eigen::Vector3i (20, 20, 2));
  // 5 M / 400 is below min_tile_points: tiles of 50,000 points, 10 x 10.
  EXPECT_EQ (makeTileGrid (box, 5000000, options).counts, Eigen::Vector3i (10, 10, 1));
  // 200 M / 400 is above the budget's tiles: min_tiles changes nothing.
  TileGridOptions budget_only;
  budget_only.points_per_tile = 250000;
  EXPECT_EQ (makeTileGrid (box, 200000000, options).counts, makeTileGrid (box, 200000000, budget_only).counts);
  // Inputs that fit one tile stay one tile.
  EXPECT_EQ (makeTileGrid (box, 40000, options).size (), 1u);
  options.min_tile_points = 0;
  EXPECT_THROW (makeTileGrid (box, 20000000, options), Error);
}

TEST (MemoryTileSource, EveryPointInOneCoreAndItsTileInput)
{
  const TriangleMesh::Ptr mesh = terrain (40);
  TileGridOptions options;
  options.tiles_along_longest = 3;
  const MemoryTileSource source (mesh, options);
  const TileGrid& grid = source.grid ();
  ASSERT_EQ (grid.counts.x (), 3);
  ASSERT_EQ (grid.counts.y (), 3);
  std::size_t total = 0;
  for (std::size_t t = 0; t < grid.size (); ++t)
  {
    total += source.corePoints (t);
    const TileInput input = source.loadTile (t);
    ASSERT_TRUE (input.mesh);
    ASSERT_EQ (input.point_numbers.size (), input.mesh->vertices.size ());
    std::size_t core = 0;
    for (std::size_t i = 0; i < input.point_numbers.size (); ++i)
    {
      // Tile vertices are the input's, and every one lies in the margin box or is a corner of a face there.
      EXPECT_EQ (input.mesh->vertices[i], mesh->vertices[input.point_numbers[i]]);
      core += grid.tileOf (input.mesh->vertices[i]) == t;
    }
    EXPECT_EQ (core, source.corePoints (t)) << "tile " << t;
    // That second half, which the loop above did not check: every face of the tile has a corner in its
    // margin box (or core), and every vertex of the tile is a corner of one of its faces.
    ASSERT_FALSE (input.mesh->triangles.empty ()) << "tile " << t;
    std::vector<bool> used (input.mesh->vertices.size (), false);
    std::size_t faces_outside = 0;
    for (const Eigen::Vector3i& triangle : input.mesh->triangles)
    {
      bool held = false;
      for (int k = 0; k < 3; ++k)
      {
        ASSERT_GE (triangle[k], 0);
        ASSERT_LT (static_cast<std::size_t> (triangle[k]), used.size ());
        used[triangle[k]] = true;
        const Eigen::Vector3d& v = input.mesh->vertices[triangle[k]];
        held = held || grid.marginBox (t).contains (v) || grid.tileOf (v) == t;
      }
      faces_outside += !held;
    }
    EXPECT_EQ (faces_outside, 0u) << "tile " << t;
    EXPECT_EQ (std::count (used.begin (), used.end (), false), 0) << "tile " << t << ": vertices in no face";
  }
  EXPECT_EQ (total, mesh->vertices.size ());
  EXPECT_THROW (source.loadTile (grid.size ()), Error);
}

// Each tile in its own local frame (tile_source.h; the spilled tiles are too), with the same world positions
// and the input's point numbers.
TEST (MemoryTileSource, ScanTilesInTheirOwnFrameWithTheirNumbers)
{
  auto scan = std::make_shared<ScanCloud> ();
  std::mt19937 mt (42);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  scan->origin = Eigen::Vector3d (5e5, 4e6, 100.0);
  for (int i = 0; i < 2000; ++i)
  {
    scan->positions.emplace_back (u (mt), u (mt), 0.1 * u (mt));
    scan->intensities.push_back (static_cast<float> (i));
  }
  scan->width = 2000;
  scan->height = 1;
  TileGridOptions options;
  options.tiles_along_longest = 2;
  const MemoryTileSource source (scan, options);
  std::size_t total = 0;
  for (std::size_t t = 0; t < source.grid ().size (); ++t)
  {
    const TileInput input = source.loadTile (t);
    if (source.corePoints (t) == 0)
      continue;
    ASSERT_TRUE (input.scan);
    EXPECT_EQ (input.scan->origin, localFrameOrigin (worldPositions (*input.scan)));
    EXPECT_LT ((input.scan->origin - scan->origin).norm (), 2.0);
    ASSERT_EQ (input.scan->intensities.size (), input.scan->size ());
    for (std::size_t i = 0; i < input.scan->size (); ++i)
    {
      EXPECT_EQ (input.scan->worldPosition (i), scan->worldPosition (input.point_numbers[i]));
      EXPECT_EQ (input.scan->intensities[i], static_cast<float> (input.point_numbers[i]));
      total += source.grid ().tileOf (input.scan->worldPosition (i)) == t;
    }
  }
  EXPECT_EQ (total, scan->size ());
}

TEST (TiledEncoding, PatchesOwnedBySeedTileAndEveryVertexCovered)
{
  const TriangleMesh::Ptr mesh = terrain (60);
  const TiledModel tiled = encodeTiled (mesh, 3);
  ASSERT_EQ (tiled.tiles.size (), 9u);
  EXPECT_EQ (tiled.model.num_input_vertices, mesh->vertices.size ());
  EXPECT_NEAR (tiled.model.bbox_diagonal, boundingBoxDiagonal (*mesh), 1e-12);
  // The tiles' runs are the model's patches, each once, in order (else the ownership loop skips some).
  std::size_t next_patch = 0;
  for (const TileRange& range : tiled.tiles)
  {
    EXPECT_EQ (range.first_patch, next_patch) << "tile " << range.tile;
    EXPECT_GT (range.num_patches, 0u) << "tile " << range.tile;
    next_patch = range.first_patch + range.num_patches;
    ASSERT_LE (next_patch, tiled.model.patches.size ());
    for (std::size_t p = range.first_patch; p < range.first_patch + range.num_patches; ++p)
      EXPECT_EQ (tiled.grid.tileOf (tiled.model.patches[p].origin), range.tile);
  }
  EXPECT_EQ (next_patch, tiled.model.patches.size ());
  // Completeness across seams: every input vertex lies in a patch (of its own tile).
  const ModelStatistics stats = tiled.model.statistics (mesh->vertices);
  EXPECT_EQ (stats.uncovered, 0u);
  SparseSurfaceEncoder<pcl::PointXYZ> untiled;
  untiled.setInputMesh (mesh);
  SparseSurfaceModel whole;
  untiled.compute (whole);
  const ModelStatistics whole_stats = whole.statistics (mesh->vertices);
  // Measured: RMSE 0.94x the untiled model's (1.90e-4 against 2.03e-4), with 280 patches for its 281 (1.25x
  // before redundant patches were dropped and small ones merged).
  EXPECT_EQ (whole_stats.uncovered, 0u);
  EXPECT_GT (whole_stats.rmse, 0.0);
  EXPECT_LT (stats.rmse, 1.1 * whole_stats.rmse);
  EXPECT_LT (stats.num_patches, 1.1 * whole_stats.num_patches);
}

TEST (TiledEncoding, SameForAnyThreadsAndTileOrder)
{
  const TriangleMesh::Ptr mesh = terrain (40);
  const TiledModel one = encodeTiled (mesh, 2, 1);
  const TiledModel two = encodeTiled (mesh, 2, 2);
  // A model to compare (measured: 4 tiles, 179 patches): two empty models would give equal files too.
  ASSERT_EQ (one.tiles.size (), 4u);
  ASSERT_GT (one.model.patches.size (), 120u);
  const std::vector<std::uint8_t> a = encodeTiledModel (one, ModelWriteOptions (), 1);
  const std::vector<std::uint8_t> b = encodeTiledModel (two, ModelWriteOptions (), 2);
  EXPECT_TRUE (a == b);
  // Tiles encoded apart (as on MPI ranks: phase 0, what it covers, then phase 1), sent as bytes in another
  // order, merge to the same file.
  TileGridOptions grid;
  grid.tiles_along_longest = 2;
  const MemoryTileSource source (mesh, grid);
  std::vector<TileEncoding> received;
  std::vector<std::size_t> covered;
  for (int phase = 0; phase < 2; ++phase)
  {
    std::vector<TileEncoding> first, second;
    for (std::size_t t = source.grid ().size (); t-- > 0;)
      if (tilePhase (source.grid (), t) == phase)
        (t % 3 ? first : second).push_back (encodeTile (source, t, SparseSurfaceEncoderOptions (), 1, covered));
    for (const auto* part : {&second, &first})
    {
      const std::vector<std::uint8_t> bytes = encodeTileEncodings (*part, source.totalPoints ());
      decodeTileEncodings (bytes.data (), bytes.size (), "rank", received);
    }
    covered = coveredPoints (received);
  }
  EXPECT_EQ (received.size (), one.tiles.size ());
  const TiledModel merged = mergeTileEncodings (source.grid (), source.totalPoints (), received);
  EXPECT_TRUE (encodeTiledModel (merged, ModelWriteOptions (), 1) == a);
}

TEST (TiledFile, LoadModelMergesAndRegionsReadOnlyTheirTiles)
{
  const pcl_sparse_test::TempDir dir ("pcl_sparse_tiles");
  const TriangleMesh::Ptr mesh = terrain (80);
  const TiledModel tiled = encodeTiled (mesh, 4);
  ModelWriteOptions options;
  options.tolerance = 1e-5;
  const std::string path = dir.file ("terrain.psm");
  saveTiledModel (path, tiled, options);
  ASSERT_TRUE (isTiledModelFile (path));

  // The old API reads the merged model; inspect sums the tiles' sections.
  const SparseSurfaceModel merged = loadModel (path);
  EXPECT_EQ (merged.patches.size (), tiled.model.patches.size ());
  EXPECT_EQ (merged.num_input_vertices, tiled.model.num_input_vertices);
  EXPECT_EQ (merged.bbox_diagonal, tiled.model.bbox_diagonal);
  EXPECT_GT (merged.footprint_step, 0.0);  // quantised: its extents within a level
  const ModelFileInfo info = inspectModelFile (path);
  EXPECT_EQ (info.version, 3);
  EXPECT_EQ (info.num_tiles, tiled.tiles.size ());
  EXPECT_EQ (info.num_patches, tiled.model.patches.size ());
  EXPECT_EQ (info.file_bytes, std::filesystem::file_size (path));

  // A region: only the tiles reaching into it are read, and its points are the whole model's there.
  const double density = 4.0 * mesh->vertices.size () / 4.0;
  const pcl::PointCloud<pcl::PointNormal> full = resample (merged, density);
  const TiledModelIndex index = readTiledModelIndex (path);
  for (const Eigen::AlignedBox3d& box :
       {Eigen::AlignedBox3d (Eigen::Vector3d (-0.6, -0.55, -1.0), Eigen::Vector3d (-0.35, -0.3, 1.0)),
        Eigen::AlignedBox3d (Eigen::Vector3d (-0.1, -0.1, -1.0), Eigen::Vector3d (0.1, 0.1, 1.0))})
  {
    std::uint64_t bytes_read = 0;
    const TiledModel region = loadTiledModelRegion (path, box, &bytes_read);
    EXPECT_LT (region.tiles.size (), tiled.tiles.size ());
    EXPECT_EQ (region.model.footprint_step, merged.footprint_step);
    EXPECT_LT (bytes_read, std::filesystem::file_size (path) / 2);
    // Exactly the header, shared sections and index (at most 16 bytes an entry) and the tiles it returns: at
    // least those whose reach box meets the box.
    EXPECT_LE (index.index_bytes, 116 + 75 + 4 + 16 * index.entries.size ());
    std::uint64_t needed = index.index_bytes;
    std::size_t meeting = 0, returned_meeting = 0;
    for (const TileIndexEntry& e : index.entries)
    {
      const bool returned = std::any_of (region.tiles.begin (), region.tiles.end (), [&] (const TileRange& r) { return r.tile == e.tile; });
      needed += returned ? e.size : 0;
      meeting += e.reach.intersects (box);
      returned_meeting += returned && e.reach.intersects (box);
    }
    EXPECT_EQ (bytes_read, needed);
    EXPECT_EQ (returned_meeting, meeting);
    const pcl::PointCloud<pcl::PointNormal> part = resample (region.model, density, region.patchNumbers ());
    const std::vector<Eigen::Vector3f> expected = inside (full, box), got = inside (part, box);
    ASSERT_GT (expected.size (), 100u);
    EXPECT_TRUE (expected == got) << expected.size () << " points in the full decode, " << got.size () << " in the region";
    for (std::size_t i = 0; i < std::min (expected.size (), got.size ()); ++i)
      if (expected[i] != got[i])
      {
        std::cout << i << ": " << expected[i].transpose () << " vs " << got[i].transpose () << std::endl;
        break;
      }
  }
}

TEST (TiledFile, RegionReadsWhoOwnsTheRestOfItsPatchesFootprints)
{
  // bench_tiles' terrain at 36 tiles, lossless: a box in the middle of a tile meets the reach boxes of 2 tiles,
  // but a patch of a third tile, 0.049 outside the box, owns places of a patch that reaches into it, and so
  // changes which of that patch's points fall in the box (48 of ~4,200 differed when only the first tiles
  // were read). The region read takes the tiles reaching those patches too, and is exact.
  const pcl_sparse_test::TempDir dir ("pcl_sparse_tiles_region");
  auto mesh = std::make_shared<TriangleMesh> (makeHeightFieldGrid (300, 300, 1.0, 1.0, [] (double x, double y) {
    return 0.06 * std::sin (9.0 * x) * std::cos (8.0 * y) + 0.02 * std::sin (23.0 * x + 17.0 * y) + 0.05 * x * y;
  }));
  SparseSurfaceEncoderOptions options;
  options.patches.rho = 0.0002;
  TileGridOptions grid;
  grid.tiles_along_longest = 6;
  TiledSurfaceEncoder encoder;
  encoder.setTileSource (std::make_shared<MemoryTileSource> (mesh, grid));
  encoder.setOptions (options);
  TiledModel tiled;
  encoder.compute (tiled);
  const std::string path = dir.file ("terrain.psm");
  saveTiledModel (path, tiled, ModelWriteOptions ());
  const Eigen::Vector3d centre = tiled.grid.coreBox (tiled.grid.tileOf (Eigen::Vector3d (-0.4, -0.4, 0.0))).center ();
  const Eigen::Vector3d half (0.1, 0.1, 30.0);
  const Eigen::AlignedBox3d box (Eigen::Vector3d (centre.x (), centre.y (), 0.0) - half,
                                 Eigen::Vector3d (centre.x (), centre.y (), 0.0) + half);
  const double density = static_cast<double> (mesh->vertices.size ()) / 4.0 * 4.0;
  const std::vector<Eigen::Vector3f> expected = inside (resample (loadModel (path), density), box);
  const TiledModel region = loadTiledModelRegion (path, box);
  const std::vector<Eigen::Vector3f> got = inside (resample (region.model, density, region.patchNumbers ()), box);
  ASSERT_GT (expected.size (), 1000u);
  EXPECT_TRUE (expected == got) << expected.size () << " points in the full decode, " << got.size () << " in the region";
  std::size_t meeting = 0;
  for (const TileIndexEntry& e : readTiledModelIndex (path).entries)
    meeting += e.reach.intersects (box);
  EXPECT_GT (region.tiles.size (), meeting) << "the second read took no tile: the case no longer tests it";
}

TEST (TiledFile, RefusesDamage)
{
  const TriangleMesh::Ptr mesh = terrain (24);
  const TiledModel tiled = encodeTiled (mesh, 2);
  const std::vector<std::uint8_t> bytes = encodeTiledModel (tiled);
  ASSERT_GT (tiled.model.patches.size (), 0u);
  // The undamaged file reads back whole, so that the refusals below are the damage's.
  ASSERT_EQ (decodeModel (bytes.data (), bytes.size ()).patches.size (), tiled.model.patches.size ());
  // Every truncation, and a flip of every bit of the header and index.
  for (std::size_t size = 0; size < bytes.size (); size += std::max<std::size_t> (1, size / 50))
    EXPECT_THROW (decodeModel (bytes.data (), size), Error) << size;
  // Version 3 -> 2 or 1 goes to those readers, which refuse it too (checksums).
  const std::size_t index_end = indexBytes (bytes);
  for (std::size_t bit = 0; bit < 8 * index_end; ++bit)
  {
    std::vector<std::uint8_t> bad = bytes;
    bad[bit / 8] ^= static_cast<std::uint8_t> (1u << (bit % 8));
    EXPECT_THROW (decodeModel (bad.data (), bad.size ()), Error) << "bit " << bit;
  }
  // A flipped bit in a tile: its CRC-32.
  for (std::size_t at = index_end; at < bytes.size (); at += 7)
  {
    std::vector<std::uint8_t> bad = bytes;
    bad[at] ^= 0x10;
    EXPECT_THROW (decodeModel (bad.data (), bad.size ()), Error) << "byte " << at;
  }
}

TEST (TiledFile, TilesDecodeAsTheUntiledFileDoes)
{
  // Quantised with the whole model's parameters, the tiles give exactly the patches of the version-1 file
  // of the merged model; lossless, the patches bit for bit.
  const TriangleMesh::Ptr mesh = terrain (60);
  const TiledModel tiled = encodeTiled (mesh, 3);
  for (double tolerance : {0.0, 1e-5})
    for (bool vertices : {false, true})
    {
      ModelWriteOptions options;
      options.tolerance = tolerance;
      options.include_vertices = vertices;
      const std::vector<std::uint8_t> file = encodeTiledModel (tiled, options);
      const SparseSurfaceModel loaded = decodeModel (file.data (), file.size ());
      const std::vector<std::uint8_t> untiled = encodeModel (tiled.model, options);
      const SparseSurfaceModel expected = tolerance > 0.0 ? decodeModel (untiled.data (), untiled.size ()) : tiled.model;
      ASSERT_EQ (loaded.patches.size (), expected.patches.size ());
      ASSERT_GT (loaded.patches.size (), 100u);  // measured 280
      // The vertex lists are in the file only when asked for: with them, every vertex is listed (6615
      // listings of the 3721 vertices measured), so the comparison below compares something.
      std::size_t listed = 0;
      for (const PatchCode& patch : loaded.patches)
        listed += patch.vertices.size ();
      if (vertices)
        EXPECT_GT (listed, mesh->vertices.size ());
      else
        EXPECT_EQ (listed, 0u);
      EXPECT_EQ (loaded.num_input_vertices, expected.num_input_vertices);
      EXPECT_EQ (loaded.bbox_diagonal, expected.bbox_diagonal);
      // One extent level of the shared quantisation (the knife-edge clearance's margin), 0 when lossless.
      EXPECT_EQ (loaded.footprint_step, expected.footprint_step);
      EXPECT_EQ (loaded.footprint_step > 0.0, tolerance > 0.0);
      for (std::size_t p = 0; p < loaded.patches.size (); ++p)
      {
        const PatchCode &a = loaded.patches[p], &b = expected.patches[p];
        ASSERT_TRUE (a.origin == b.origin && a.frame == b.frame && a.radius == b.radius && a.atoms == b.atoms &&
                     a.coefficients == b.coefficients && a.footprint.extent == b.footprint.extent)
          << "patch " << p << " tolerance " << tolerance;
        if (vertices)
          ASSERT_TRUE (a.vertices == b.vertices) << "patch " << p;
      }
      const ModelFileInfo info = inspectModel (file.data (), file.size ());
      EXPECT_EQ (info.version, 3);
      EXPECT_EQ (info.quantised, tolerance > 0.0);
      EXPECT_EQ (info.has_vertices, vertices);
      EXPECT_EQ (info.basis, inspectModel (untiled.data (), untiled.size ()).basis);
      EXPECT_EQ (info.num_tiles, tiled.tiles.size ());
      std::uint64_t stored = 0;
      for (const ModelFileSection& section : info.sections)
        stored += section.stored_bytes;
      EXPECT_EQ (stored, file.size ()) << "TIDX, the shared sections and TILE make up the file";
    }
}

TEST (TiledFile, PerTileFramingIsBounded)
{
  // What the format adds to the tiles' compressed sections: the 116-byte header, the shared QUAN, the index
  // checksum, and per tile an index entry (about 10 bytes), a varint size per section and a CRC-32. Bounded
  // at 32 bytes a tile, so that a regression in the framing fails (version 2 took ~470 bytes a tile and 88 of
  // index). What zstd loses by compressing each tile's sections apart is not framing: printed, not bounded
  // here (small tiles; TiledEncoding.SharedMeshNearTheUntiledModel bounds the whole file on tiles of 50k vertices).
  const TriangleMesh::Ptr mesh = terrain (90);
  for (int along : {2, 4})
  {
    const TiledModel tiled = encodeTiled (mesh, along);
    ModelWriteOptions options;
    options.tolerance = 1e-5;
    const double file = static_cast<double> (encodeTiledModel (tiled, options).size ());
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (const TileRange& range : tiled.tiles)
      runs.emplace_back (range.first_patch, range.num_patches);
    const ModelSections sections = encodeModelSections (tiled.model, options, runs);
    double payloads = 0.0;
    for (const std::vector<std::vector<std::uint8_t>>& run : sections.runs)
      for (const std::vector<std::uint8_t>& section : run)
        payloads += static_cast<double> (
          std::min (section.size (), compressBytes (section.data (), section.size (), options.zstd_level).size ()));
    const double fixed = 116.0 + static_cast<double> (sections.shared.quantisation.size ()) + 4.0;
    const double per_tile = (file - payloads - fixed) / static_cast<double> (tiled.tiles.size ());
    const double untiled = static_cast<double> (encodeModel (tiled.model, options).size ());
    std::printf ("%zu tiles, %zu patches: file %.0f bytes, of which framing %.1f bytes a tile; the same patches as one "
                 "version-1 file %.0f (%+.1f bytes a tile)\n",
                 tiled.tiles.size (), tiled.model.patches.size (), file, per_tile, untiled,
                 (file - untiled) / static_cast<double> (tiled.tiles.size ()));
    EXPECT_GT (per_tile, 4.0);
    EXPECT_LT (per_tile, 32.0);
  }
}

TEST (TiledFile, ReadsTheVersion2Layout)
{
  // Files of the older tiled layout (every tile a complete version-1 model, 88-byte index entries;
  // docs/FORMAT.md) still load, whole and by region.
  const pcl_sparse_test::TempDir dir ("pcl_sparse_tiles_v2");
  const TriangleMesh::Ptr mesh = terrain (50);
  const TiledModel tiled = encodeTiled (mesh, 3);
  ModelWriteOptions options;
  options.tolerance = 1e-5;
  const std::string path = dir.file ("v2.psm");
  const std::vector<std::uint8_t> bytes = version2File (tiled, options);
  {
    std::ofstream out (path, std::ios::binary);
    out.write (reinterpret_cast<const char*> (bytes.data ()), static_cast<std::streamsize> (bytes.size ()));
  }
  ASSERT_TRUE (isTiledModelFile (path));
  const SparseSurfaceModel merged = loadModel (path);
  ASSERT_EQ (merged.patches.size (), tiled.model.patches.size ());
  std::size_t next = 0;
  for (const TileRange& range : tiled.tiles)
  {
    const std::vector<std::uint8_t> tile = encodeModel (subModel (tiled.model, range.first_patch, range.num_patches), options);
    const SparseSurfaceModel expected = decodeModel (tile.data (), tile.size ());
    for (const PatchCode& patch : expected.patches)
    {
      const PatchCode& got = merged.patches[next];
      EXPECT_TRUE (got.origin == patch.origin && got.frame == patch.frame && got.radius == patch.radius &&
                   got.atoms == patch.atoms && got.coefficients == patch.coefficients &&
                   got.footprint.extent == patch.footprint.extent)
        << "patch " << next;
      ++next;
    }
  }
  EXPECT_EQ (next, merged.patches.size ());
  const ModelFileInfo info = inspectModelFile (path);
  EXPECT_EQ (info.version, 2);
  EXPECT_EQ (info.num_tiles, tiled.tiles.size ());
  const TiledModelIndex index = readTiledModelIndex (path);
  EXPECT_EQ (index.version, 2);
  EXPECT_EQ (index.index_bytes, 104 + 88 * tiled.tiles.size () + 4);
  const Eigen::AlignedBox3d box (Eigen::Vector3d (-0.9, -0.9, -1.0), Eigen::Vector3d (-0.8, -0.8, 1.0));
  std::uint64_t bytes_read = 0;
  const TiledModel region = loadTiledModelRegion (path, box, &bytes_read);
  EXPECT_LT (region.tiles.size (), tiled.tiles.size ());
  EXPECT_GT (region.tiles.size (), 0u);
  // Exactly the header, index and the tiles it returns; every tile whose reach meets the box among them.
  std::uint64_t needed = index.index_bytes;
  for (const TileIndexEntry& e : index.entries)
  {
    const bool returned = std::any_of (region.tiles.begin (), region.tiles.end (), [&] (const TileRange& r) { return r.tile == e.tile; });
    needed += returned ? e.size : 0;
    EXPECT_TRUE (returned || !e.reach.intersects (box)) << "tile " << e.tile;
  }
  EXPECT_EQ (bytes_read, needed);
  EXPECT_LT (bytes_read, bytes.size ());
  // And the region resamples to the whole file's points there.
  const double density = static_cast<double> (mesh->vertices.size ()) / 4.0 * 4.0;
  const std::vector<Eigen::Vector3f> whole_points = inside (resample (merged, density), box);
  ASSERT_GT (whole_points.size (), 20u);
  EXPECT_TRUE (whole_points == inside (resample (region.model, density, region.patchNumbers ()), box));

  // Version 2 keeps the basis in its tiles: a region no tile reaches takes it from the first tile, so the
  // empty model can be saved again; a file of no tile has no basis to give and is refused.
  const Eigen::AlignedBox3d nowhere (Eigen::Vector3d::Constant (50.0), Eigen::Vector3d::Constant (51.0));
  const TiledModel empty_region = loadTiledModelRegion (path, nowhere);
  EXPECT_TRUE (empty_region.tiles.empty ());
  ASSERT_TRUE (empty_region.model.basis);
  EXPECT_EQ (empty_region.model.basis->size (), merged.basis->size ());
  EXPECT_NO_THROW (encodeModel (empty_region.model, options));
  TiledModel no_tile = tiled;
  no_tile.tiles.clear ();
  no_tile.model.patches.clear ();
  const std::vector<std::uint8_t> empty = version2File (no_tile, options);
  try
  {
    decodeModel (empty.data (), empty.size (), "empty.psm");
    ADD_FAILURE () << "a version-2 file of no tile was read";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("without a tile, hence without a basis"), std::string::npos) << e.what ();
  }
}

TEST (TiledFile, RefusesATileGridOutOfRange)
{
  // The tile counts of a header, each at most 2^30, multiplied in 64 bits: 137 x 125400505 x 2^30 =
  // 2^64 + 2^30 wrapped to 2^30 tiles and passed; a count over 2^30 (here 2^32 - 1) was cut to 2^30.
  const TriangleMesh::Ptr mesh = terrain (12);
  TiledModel tiled = encodeTiled (mesh, 1);
  ModelWriteOptions options;
  options.tolerance = 1e-5;
  const std::vector<std::uint8_t> good = version2File (tiled, options);
  ASSERT_NO_THROW (decodeModel (good.data (), good.size ()));
  for (const Eigen::Vector3i& counts : {Eigen::Vector3i (137, 125400505, 1 << 30), Eigen::Vector3i (-1, 1, 1)})
  {
    tiled.grid.counts = counts;
    const std::vector<std::uint8_t> bad = version2File (tiled, options);
    try
    {
      decodeModel (bad.data (), bad.size (), "grid.psm");
      ADD_FAILURE () << "tile counts " << counts.transpose () << " were read";
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find ("tile grid out of range"), std::string::npos) << e.what ();
    }
  }
}

TEST (TiledFile, RefusesAVersion2TileThatIsItselfATiledFile)
{
  // A version-2 tile is a version-1 file. One that is a tiled file again was decoded as one, so a file of
  // tiled files nested a few hundred bytes a level ran each reader (loadModel, the region reader, the
  // inspector) out of stack; one level, which passed every count check, is enough to show the refusal.
  const TriangleMesh::Ptr mesh = terrain (12);
  const TiledModel tiled = encodeTiled (mesh, 1);
  ASSERT_EQ (tiled.tiles.size (), 1u);
  ModelWriteOptions options;
  options.tolerance = 1e-5;
  const std::vector<std::uint8_t> inner = version2File (tiled, options);
  ASSERT_EQ (decodeModel (inner.data (), inner.size ()).patches.size (), tiled.model.patches.size ());
  const std::vector<std::uint8_t> nested = version2File (tiled, options, {inner});
  const pcl_sparse_test::TempDir dir ("pcl_sparse_tiles_nested");
  const std::string path = dir.file ("nested.psm");
  {
    std::ofstream out (path, std::ios::binary);
    out.write (reinterpret_cast<const char*> (nested.data ()), static_cast<std::streamsize> (nested.size ()));
  }
  const Eigen::AlignedBox3d everywhere (Eigen::Vector3d::Constant (-100.0), Eigen::Vector3d::Constant (100.0));
  const std::vector<std::function<void ()>> readers = {
    [&] { decodeModel (nested.data (), nested.size (), "nested.psm"); },
    [&] { loadModel (path); },
    [&] { loadTiledModelRegion (path, everywhere); },
    [&] { inspectModelFile (path); }};
  for (std::size_t r = 0; r < readers.size (); ++r)
  {
    try
    {
      readers[r] ();
      ADD_FAILURE () << "reader " << r << " took a tiled file as a version-2 tile";
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find ("is itself a tiled file"), std::string::npos) << e.what ();
    }
  }
}

TEST (TiledEncoding, SeamsLikeTheInside)
{
  // Resampled at a spacing s, the places near tile borders are as complete and as dense as the inside.
  const TriangleMesh::Ptr mesh = terrain (100);
  const TiledModel tiled = encodeTiled (mesh, 3);
  const double spacing = 0.02;
  const pcl::PointCloud<pcl::PointNormal> cloud = resample (tiled.model, 1.0 / (spacing * spacing));
  // About 4 / spacing^2 = 10,000 points (measured 10698): an empty cloud made every gap 0 below.
  ASSERT_GT (cloud.size (), 7000u);
  // Finite points: a NaN distance would vanish in the std::max below (its comparisons are false).
  for (const pcl::PointNormal& p : cloud)
    ASSERT_TRUE (std::isfinite (p.x) && std::isfinite (p.y) && std::isfinite (p.z));
  auto points = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  for (const pcl::PointNormal& p : cloud)
    points->push_back (pcl::PointXYZ (p.x, p.y, p.z));
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud (points);
  auto nearBorder = [&] (double x, double y) {
    for (int a = 0; a < 2; ++a)
      for (int k = 1; k < tiled.grid.counts[a]; ++k)
        if (std::abs ((a == 0 ? x : y) - (tiled.grid.origin[a] + k * tiled.grid.edge)) < 2.0 * spacing)
          return true;
    return false;
  };
  // Completeness: the largest distance from a surface place (a mesh vertex) to the nearest point.
  double gap_border = 0.0, gap_inside = 0.0;
  std::size_t border_vertices = 0, inside_vertices = 0;
  std::vector<int> nn (1);
  std::vector<float> d2 (1);
  for (const Eigen::Vector3d& v : mesh->vertices)
  {
    if (std::abs (v.x ()) > 0.95 || std::abs (v.y ()) > 0.95)
      continue;  // the outer boundary is neither
    ASSERT_EQ (tree.nearestKSearch (pcl::PointXYZ (v.x (), v.y (), v.z ()), 1, nn, d2), 1);
    const bool border = nearBorder (v.x (), v.y ());
    ++(border ? border_vertices : inside_vertices);
    double& gap = border ? gap_border : gap_inside;
    gap = std::max (gap, std::sqrt (static_cast<double> (d2[0])));
  }
  // Both kinds of place are there (with no vertex near the borders, the border gap stayed 0 and passed):
  // measured 1456 of the 9025 vertices inside |x|, |y| <= 0.95 near the 4 inner borders, 7569 elsewhere.
  EXPECT_GT (border_vertices, 970u);
  EXPECT_GT (inside_vertices, 5000u);
  EXPECT_LT (gap_border, 1.25 * gap_inside + 0.1 * spacing) << "border " << gap_border << ", inside " << gap_inside;
  // And the inside itself is complete at the spacing: measured gaps 0.0227 inside, 0.0211 at the borders.
  EXPECT_GT (gap_inside, 0.0);
  EXPECT_GT (gap_border, 0.0);
  EXPECT_LT (gap_inside, 1.7 * spacing);
  // Spacing: points per unit of projected area in the band along the borders and elsewhere.
  std::size_t in_band = 0, elsewhere = 0, band_cells = 0, other_cells = 0;
  for (const pcl::PointNormal& p : cloud)
    if (std::abs (p.x) <= 0.95 && std::abs (p.y) <= 0.95)
      ++(nearBorder (p.x, p.y) ? in_band : elsewhere);
  for (double x = -0.95 + 0.0025; x < 0.95; x += 0.005)
    for (double y = -0.95 + 0.0025; y < 0.95; y += 0.005)
      ++(nearBorder (x, y) ? band_cells : other_cells);
  const double ratio = (static_cast<double> (in_band) / band_cells) / (static_cast<double> (elsewhere) / other_cells);
  EXPECT_GT (ratio, 0.9);  // measured 1.008
  EXPECT_LT (ratio, 1.1);
}

TEST (TiledEncoding, SharedMeshNearTheUntiledModel)
{
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/koala-loop1-200k.ply";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (mesh);
  SparseSurfaceModel whole;
  encoder.compute (whole);
  const ModelStatistics whole_stats = whole.statistics (mesh->vertices);
  ModelWriteOptions options;
  options.tolerance = derivedFileTolerance (whole_stats, 0.1);  // pinned: the per-tile cost's share grows as files shrink
  const std::size_t whole_bytes = encodeModel (whole, options).size ();
  const TiledModel tiled = encodeTiled (mesh, 2);
  const ModelStatistics tiled_stats = tiled.model.statistics (mesh->vertices);
  const std::size_t tiled_bytes = encodeTiledModel (tiled, options).size ();
  std::printf ("untiled: %zu patches, RMSE %.5g, %zu bytes; %zu tiles: %zu patches, RMSE %.5g, %zu bytes\n",
               whole.patches.size (), whole_stats.rmse, whole_bytes, tiled.tiles.size (), tiled.model.patches.size (),
               tiled_stats.rmse, tiled_bytes);
  EXPECT_EQ (whole_stats.uncovered, 0u);
  EXPECT_GT (whole_stats.rmse, 0.0);
  EXPECT_EQ (tiled_stats.uncovered, 0u);
  EXPECT_LT (tiled_stats.rmse, 1.02 * whole_stats.rmse);  // measured 9.20e-4 against 9.63e-4
  // Redundant patches (patches/redundant_patches.h) are dropped, and small ones merged (patch_merging.h),
  // within each tile, which does not see the patches of its neighbours: 3.2 % more patches than untiled here
  // (2119 -> 1721 untiled, 1746 tiled with redundant ones dropped; 1512 and 1561 merged too).
  EXPECT_LE (tiled.model.patches.size (), whole.patches.size () * 104 / 100);
  // Issue 16's target was 2 %: the patches themselves take about what untiled's do, and the tiled file
  // (version 3: shared quantisation, ~20 bytes of framing a tile, each tile's sections coded apart, which
  // loses ~500 bytes a tile here) 1.7 % more than they until 2026-12-01. Since the seeds are coded as steps
  // along the Morton curve (format/seed_coding.h) and the redundant patches are dropped, both files are
  // smaller (untiled 88094 -> 85536 -> 70582 bytes, tiled 89598 -> 87684 -> 73481), but the tiles' framing,
  // about 2.2 kB, is 3.1 % of the smaller file: at this small scale (4 tiles of 50k vertices, 20 kB each)
  // the 2 % is missed; at issue 16's scale (bench/results/tiled_vs_untiled.md) the tiled file was smaller.
  // Merged (2026-12-02): untiled 62953 bytes, the tiled model's patches 64245 (+2.1 %, the patches the tiles
  // could not merge across their borders), the tiled file 66408 (+5.5 %). Measured again in the review of
  // the tests: 62871, 64409 (+2.4 %) and 66592 bytes (+5.9 %); 1512 patches untiled, 1560 tiled. With the radii on
  // their grid (coding/radius_grid.h, 2026-12-06) each patch takes about 15 bits less, the framing the same:
  // 60051, 61767 (+2.9 %) and 63812 bytes (+6.3 %).
  const std::size_t patch_bytes = encodeModel (tiled.model, options).size ();
  std::printf ("the tiled model's patches as one run: %zu bytes\n", patch_bytes);
  EXPECT_LT (static_cast<double> (patch_bytes), 1.035 * whole_bytes);
  EXPECT_LT (static_cast<double> (tiled_bytes), 1.07 * whole_bytes);
  EXPECT_LT (tiled_bytes, 75000u) << "the tiled file of 2026-12-01 was 87684 bytes";
}

TEST (TiledEncoding, StrayScanPointsDoNotFailTheEncoding)
{
  // A plane of scan points and three stray points in a tile of their own, too few to make a surface.
  auto scan = std::make_shared<ScanCloud> ();
  std::mt19937 mt (42);
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  for (int i = 0; i < 3000; ++i)
    scan->positions.emplace_back (u (mt), u (mt), 0.001 * u (mt));
  for (int i = 0; i < 3; ++i)
    scan->positions.emplace_back (0.9 + 0.01 * i, 0.9, 1.9);
  scan->width = static_cast<std::uint32_t> (scan->positions.size ());
  scan->height = 1;
  TiledModel tiled;
  ASSERT_NO_THROW (tiled = encodeInTiles (scan, 4));
  const ModelStatistics stats = tiled.model.statistics (worldPositions (*scan));
  // The three strays are left out, every point of the plane is covered (measured: 3 uncovered, 16 patches).
  EXPECT_EQ (stats.uncovered, 3u);
  EXPECT_GT (tiled.model.patches.size (), 4u);
  // The plane's points are coded to their noise: uniform in +-0.001, RMS 0.001 / sqrt (3) = 5.8e-4
  // (measured RMSE 5.95e-4, largest error 1.57e-3).
  EXPECT_GT (stats.rmse, 0.0);
  EXPECT_LT (stats.rmse, 9e-4);
  EXPECT_LT (stats.max_error, 2.4e-3);
}

// A scan whose left part has no intensity (NaN): the tiles there leave the channel out (fillAttributeGaps
// finds no value in them), the others code it, and the merged model has it for every patch; it failed with
// "mergeTileEncodings: tile 0 has other attribute channels".
TEST (TiledEncoding, TilesWithoutAnAttributeValueMergeWithTheOthers)
{
  const std::vector<Eigen::Vector3d> points = squarePoints (4000, 11, [] (double, double, auto draw) { return 0.001 * draw (); });
  auto scan = listScan (points);
  for (const Eigen::Vector3d& p : points)
    scan->intensities.push_back (p.x () < -0.2 ? std::numeric_limits<float>::quiet_NaN () : static_cast<float> (100.0 + 100.0 * p.x ()));
  TiledModel tiled;
  ASSERT_NO_THROW (tiled = encodeInTiles (scan, 4));
  ASSERT_EQ (tiled.model.attribute_channels.size (), 1u);
  EXPECT_EQ (tiled.model.attribute_channels[0].channel, AttributeChannel::Intensity);
  std::size_t without = 0;
  for (const PatchCode& patch : tiled.model.patches)
  {
    ASSERT_EQ (patch.attributes.size (), 1u);
    without += patch.attributes[0].atoms.empty () ? 1 : 0;
  }
  EXPECT_GT (without, 0u);  // the left tiles' patches
  const double lower = tiled.model.attribute_channels[0].lower;
  EXPECT_GE (lower, 80.0 - 1e-3);  // the values given, not a filler's
  const std::vector<std::uint8_t> bytes = encodeModel (tiled.model);
  const auto model = std::make_shared<const SparseSurfaceModel> (decodeModel (bytes.data (), bytes.size ()));
  SparseSurfaceResampling<pcl::PointXYZINormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (8000);
  pcl::PointCloud<pcl::PointXYZINormal> cloud;
  resampling.compute (cloud);
  ASSERT_GT (cloud.size (), 7000u);
  double worst_right = 0.0, worst_left = 0.0;
  std::size_t right = 0, left = 0;
  for (const auto& p : cloud)
    if (p.x > 0.1)
    {
      ++right;
      worst_right = std::max (worst_right, std::abs (p.intensity - (100.0 + 100.0 * p.x)));
    }
    else if (p.x < -0.6)
    {
      ++left;
      worst_left = std::max (worst_left, std::abs (p.intensity - lower));
    }
  ASSERT_GT (right, 2000u);
  ASSERT_GT (left, 1000u);
  EXPECT_LT (worst_right, 8.0);  // 5.2 measured, of 80 .. 200
  EXPECT_LT (worst_left, 1e-3);
}

// TileSource::setViewPoint reaches each tile's encoder: a plane of scan points seen from above or below gets
// every patch's normal toward the viewpoint (without it, a consistent orientation picks one sign for both).
TEST (TiledEncoding, ViewPointOfTheSourceOrientsEveryTile)
{
  const auto scan = listScan (squarePoints (4000, 7, [] (double x, double y, auto) {
    return 0.05 * std::sin (3.0 * x) * std::cos (2.0 * y);
  }));
  TileGridOptions grid;
  grid.tiles_along_longest = 3;
  for (const float z : {10.0f, -10.0f})
  {
    auto source = std::make_shared<MemoryTileSource> (scan, grid);
    source->setViewPoint (0.2f, -0.1f, z);
    TiledSurfaceEncoder encoder;
    encoder.setTileSource (source);
    TiledModel tiled;
    encoder.compute (tiled);
    ASSERT_GE (tiled.model.patches.size (), 9u);  // one at least in each of the 3 x 3 tiles
    std::size_t facing = 0;
    for (const PatchCode& patch : tiled.model.patches)
      facing += patch.frame.col (2).z () * z > 0.0 ? 1 : 0;
    EXPECT_EQ (facing, tiled.model.patches.size ()) << "viewpoint z " << z;
  }
}

// A scan's encoder may move its points (depth steps taken out, along the lines of sight), so a patch seeded
// just inside its tile's core can have its origin across the border. The tile owns it by where its seed lies
// in the input: judged by the origin, such patches were dropped, and the points only they covered were in no
// patch (office1.pcd -tiles 4: 113 patches, 154 points).
TEST (TiledEncoding, PatchesOfMovedScanPointsStayWithTheirSeedsTile)
{
  const auto scan = std::make_shared<ScanCloud> (pcl_sparse_test::steppedSlantedPlane (144));
  TileGridOptions grid;
  grid.tiles_along_longest = 8;  // 29 tiles
  TiledModel tiled;
  const ModelStatistics stats = encodeMeasuring (MemoryTileSource (scan, grid), SparseSurfaceEncoderOptions (), tiled);
  ASSERT_GE (tiled.tiles.size (), 4u);
  std::size_t across = 0;
  for (const TileRange& range : tiled.tiles)
    for (std::size_t p = range.first_patch; p < range.first_patch + range.num_patches; ++p)
      across += tiled.grid.tileOf (tiled.model.patches[p].origin) != range.tile ? 1 : 0;
  EXPECT_GT (across, 0u) << "no origin crossed a border: the case is not tested";
  EXPECT_EQ (stats.uncovered, 0u);  // 803 when the origin decided
}

// The same wall's statistics: each patch is evaluated where its tile's encoder coded the point (its depth
// steps taken out: TileEncoding::moved) and the error taken to the input's point, as reconstructVertices
// does from the stored (x', y') and the untiled statistics do. Evaluated at the input's point, patches gave
// the distance to the surface here (RMSE 0.033 for 0.045), and on office1.pcd in 4 tiles extrapolated their
// codes beyond their disks (maximum error 49 m; 0.077 untiled). Sent between ranks as bytes, the moved
// points come back.
TEST (TiledEncoding, StatisticsOfMovedScanPointsAreTakenWhereTheyWereCoded)
{
  const auto scan = std::make_shared<ScanCloud> (pcl_sparse_test::steppedSlantedPlane (144));
  TileGridOptions grid;
  grid.tiles_along_longest = 8;
  const MemoryTileSource source (scan, grid);
  std::vector<Eigen::Vector3d> input;
  for (std::size_t i = 0; i < scan->size (); ++i)
    input.push_back (scan->worldPosition (i));
  SparseSurfaceEncoderOptions unbounded;  // as the encoder's first pass: tile 30 alone exceeds CR 1
  unbounded.max_compression_ratio = 0.0;
  const std::vector<TileEncoding> tiles = encodeTilesPhaseByPhase (source, unbounded);
  const ModelStatistics reference =
    mergeTileEncodings (source.grid (), source.totalPoints (), tiles).model.statistics (input);  // (x', y') stored
  EXPECT_EQ (reference.uncovered, 0u);
  EXPECT_GT (reference.rmse, 0.04);  // 0.045: the steps are 0.15 deep
  std::vector<TileEncoding> received;
  std::size_t moved = 0;
  for (const TileEncoding& tile : tiles)
  {
    const std::vector<std::uint8_t> bytes = encodeTileEncodings ({tile}, source.totalPoints ());
    decodeTileEncodings (bytes.data (), bytes.size (), "rank", received);
    EXPECT_EQ (received.back ().moved.numbers, tile.moved.numbers);
    EXPECT_TRUE (received.back ().moved.offsets == tile.moved.offsets);
    moved += tile.moved.numbers.size ();
  }
  EXPECT_GT (moved, scan->size () / 4);
  TiledModel merged = mergeTileEncodings (source.grid (), source.totalPoints (), received);
  const ModelStatistics stats = tiledModelStatistics (source, merged);
  EXPECT_NEAR (stats.rmse, reference.rmse, 1e-6 * reference.rmse);  // the offsets are floats
  EXPECT_NEAR (stats.max_error, reference.max_error, 1e-6 * reference.max_error);
  for (const TileRange& range : merged.tiles)
    EXPECT_TRUE (range.moved.numbers.empty ()) << "tile " << range.tile << " still holds its moved points";
  // The measuring encoder, which drops each tile's moved points with its vertex lists, gives the same.
  TiledModel measured;
  const ModelStatistics measured_stats = encodeMeasuring (source, SparseSurfaceEncoderOptions (), measured);
  EXPECT_EQ (measured_stats.rmse, stats.rmse);
  EXPECT_EQ (measured_stats.max_error, stats.max_error);
}

// PCL's default pose (0, 0, 0) under an airborne-like tile is judged once on the whole input, by the tile
// source: a tile's part of the points lies at too narrow a range of distances to tell, and kept the pose.
TEST (TiledEncoding, DefaultPoseIsJudgedOnTheWholeInput)
{
  std::mt19937 mt (19);
  auto scan = listScan (pcl_sparse_test::airborneTile (50, 20.0, mt));
  scan->has_sensor_pose = true;  // PCL's default pose, as every PCD and PCL cloud states
  TileGridOptions grid;
  grid.tiles_along_longest = 3;
  const auto source = std::make_shared<MemoryTileSource> (scan, grid);
  EXPECT_FALSE (source->loadTile (0).scan->has_sensor_pose);
  TiledSurfaceEncoder encoder;
  encoder.setTileSource (source);
  TiledModel tiled;
  encoder.compute (tiled);
  ASSERT_GE (tiled.model.patches.size (), 9u);
  std::size_t up = 0;
  for (const PatchCode& patch : tiled.model.patches)
    up += patch.frame.col (2).z () > 0.0 ? 1 : 0;
  EXPECT_EQ (up, tiled.model.patches.size ());
}

TEST (TiledEncoding, WavefrontHoldsVertexListsForABandOfTiles)
{
  // 103k vertices in 12 x 12 x 2 tiles; fast options (the order and memory are tested, not the model).
  const TriangleMesh::Ptr mesh = terrain (320);
  TileGridOptions grid;
  grid.tiles_along_longest = 12;
  const auto source = std::make_shared<MemoryTileSource> (mesh, grid);
  ASSERT_EQ (source->grid ().counts, Eigen::Vector3i (12, 12, 2));  // slabs along y, 2 layers
  SparseSurfaceEncoderOptions options;
  options.patches.rho = 0.02;
  options.coding.max_atoms = 4;
  options.coding.tolerance = 0.05;
  options.coding.min_samples = 16;
  // Measured while encoding, vertex lists dropped once every tile around theirs is measured. One thread:
  // with two, how far the encoding runs ahead of the measurement depends on the scheduler, and on a loaded
  // machine the peak grew from 68 to 81 of the 87 tiles the bound allows (ctest -j2 failed it once); the
  // model must not depend on the threads anyway (the whole run below takes two).
  TiledSurfaceEncoder wavefront;
  wavefront.setTileSource (source);
  wavefront.setOptions (options);
  wavefront.setNumberOfThreads (1);
  wavefront.setMeasurement (true);
  TiledModel measured;
  wavefront.compute (measured);
  // Encoded whole (every vertex list held), measured after.
  TiledSurfaceEncoder whole;
  whole.setTileSource (source);
  whole.setOptions (options);
  whole.setNumberOfThreads (2);
  TiledModel after;
  whole.compute (after);
  const std::size_t all_vertices = whole.getPeakHeldVertices ();
  const std::size_t all_tiles = whole.getPeakHeldTiles ();
  const ModelStatistics stats = tiledModelStatistics (*source, after);
  // The same figures, bit for bit (the same sums in the same order), and the same model.
  const ModelStatistics& along = wavefront.getStatistics ();
  // Figures of a real model (measured: 209 patches, RMSE 9.2e-4, none uncovered), so that the equalities
  // below compare something.
  EXPECT_GT (stats.num_patches, 100u);
  EXPECT_GT (stats.rmse, 0.0);
  EXPECT_EQ (stats.uncovered, 0u);
  EXPECT_EQ (along.rmse, stats.rmse);
  EXPECT_EQ (along.mean_error_over_diagonal, stats.mean_error_over_diagonal);
  EXPECT_EQ (along.max_error, stats.max_error);
  EXPECT_EQ (along.uncovered, stats.uncovered);
  EXPECT_EQ (along.num_patches, stats.num_patches);
  EXPECT_EQ (along.compression_ratio, stats.compression_ratio);
  EXPECT_TRUE (encodeTiledModel (measured, ModelWriteOptions (), 1) == encodeTiledModel (after, ModelWriteOptions (), 1));
  for (const PatchCode& patch : measured.model.patches)
    ASSERT_TRUE (patch.vertices.empty () && patch.vertex_xy.empty ());
  // A band: slabs j - 1 to j + 1 of the tile measured and the phase-0 tiles of slab j + 2 (about 3.5 of
  // the 12 slabs), plus the few tiles taken ahead; never more than 5.
  std::cout << "held at once: " << wavefront.getPeakHeldTiles () << " of " << all_tiles << " tiles, "
            << wavefront.getPeakHeldVertices () << " of " << all_vertices << " vertex listings; tiles' error sums waiting: "
            << wavefront.getPeakPendingTiles () << "\n";
  EXPECT_LE (wavefront.getPeakHeldTiles (), all_tiles * 5 / 12);
  EXPECT_LT (wavefront.getPeakHeldVertices (), all_vertices * 5 / 12);
  // The peaks are counted (0 passed the bounds above): the whole run holds every tile with points (measured
  // 209 of the 288, 195470 vertex listings), the wavefront at least the three slabs around the tile measured
  // (measured 65 tiles, 60337 listings; a quarter of all is 52 and 48868).
  EXPECT_GT (all_tiles, 150u);
  EXPECT_LE (all_tiles, 288u);
  EXPECT_GE (wavefront.getPeakHeldTiles (), all_tiles / 4);
  EXPECT_GE (wavefront.getPeakHeldVertices (), all_vertices / 4);
}

TEST (TiledEncoding, FarReachingMeshTilesEncodeAsPhaseByPhase)
{
  // Cells of 0.167 in tiles of 0.167 (margin 0.017): a tile's triangles reach two tiles away, so a phase-1
  // tile may need what a phase-0 tile beyond its neighbours covers (without going phase by phase, the
  // encoder gave another model here).
  const TriangleMesh::Ptr mesh = terrain (12);
  TileGridOptions grid;
  grid.tiles_along_longest = 12;
  const MemoryTileSource source (mesh, grid);
  const std::vector<TileEncoding> tiles = encodeTilesPhaseByPhase (source);
  EXPECT_GT (farthestReachOfPhase (source.grid (), tiles, 0), 1);
  TiledModel by_phases = mergeTileEncodings (source.grid (), source.totalPoints (), tiles);
  TiledStatisticsOptions far;
  far.reach = farthestReach (tiles);
  const ModelStatistics stats = tiledModelStatistics (source, by_phases, far);
  // The figures are the model's: each vertex measured against every patch that lists it, the far ones too
  // (measured against the neighbour tiles' patches alone: RMSE 0.02410 and largest error 0.112 for 0.02264
  // and 0.063).
  const ModelStatistics measured =
    expectMeasuringEncoderGives (source, mesh->vertices, mergeTileEncodings (source.grid (), source.totalPoints (), tiles));
  EXPECT_EQ (measured.rmse, stats.rmse);
  EXPECT_EQ (measured.mean_error_over_diagonal, stats.mean_error_over_diagonal);
}

TEST (TiledEncoding, FarReachingPhaseOneTilesAreMeasuredAgainstEveryTileThatFar)
{
  // A long triangle over a fine terrain joins two phase-1 tiles two apart along x: the patch covering it,
  // seeded in one, lists points of the other, while every phase-0 tile's patches stay within its
  // neighbours. The wavefront encoder measured each tile against its neighbours' patches only and went on.
  const TriangleMesh::Ptr mesh = terrain (72);
  const auto vertex = [] (int i, int j) { return j * 73 + i; };
  mesh->triangles.emplace_back (vertex (18, 6), vertex (42, 6), vertex (18, 7));
  TileGridOptions grid;
  grid.tiles_along_longest = 6;
  const MemoryTileSource source (mesh, grid);
  const std::vector<TileEncoding> tiles = encodeTilesPhaseByPhase (source);
  ASSERT_EQ (farthestReachOfPhase (source.grid (), tiles, 0), 1);
  ASSERT_GT (farthestReachOfPhase (source.grid (), tiles, 1), 1);
  // Measured against the neighbours' patches alone: RMSE 0.000152378 for the model's 0.000152376.
  expectMeasuringEncoderGives (source, mesh->vertices, mergeTileEncodings (source.grid (), source.totalPoints (), tiles));
}

TEST (TiledEncoding, StatisticsNeedOnlyTheVertexNumbers)
{
  // Tiles encoded as the measuring encoder holds them (no (x', y'), sent between ranks as bytes), measured
  // against the statistics of the same tiles with their stored (x', y') (reconstructVertices). A support
  // scale != 1: the stored radius includes it, and (x', y') must be recomputed over it. Two vertices in no
  // face are in no tile: uncovered in both.
  const TriangleMesh::Ptr mesh = terrain (60);
  mesh->vertices.push_back (0.5 * (mesh->vertices[0] + mesh->vertices[100]));
  mesh->vertices.push_back (0.5 * (mesh->vertices[7] + mesh->vertices[2000]));
  TileGridOptions grid;
  grid.tiles_along_longest = 3;
  const MemoryTileSource source (mesh, grid);
  SparseSurfaceEncoderOptions options;
  options.coding.support_scale = 1.25;
  std::vector<TileEncoding> with_xy, numbers_only;
  for (int phase = 0; phase < 2; ++phase)
  {
    const std::vector<std::size_t> covered = phase == 1 ? coveredPoints (with_xy) : std::vector<std::size_t> ();
    std::vector<TileEncoding> these;
    for (std::size_t t = 0; t < source.grid ().size (); ++t)
      if (tilePhase (source.grid (), t) == phase && source.corePoints (t) > 0)
      {
        with_xy.push_back (encodeTile (source, t, options, 1, covered));
        these.push_back (encodeTile (source, t, options, 1, covered, false));
      }
    const std::vector<std::uint8_t> bytes = encodeTileEncodings (these, source.totalPoints ());
    decodeTileEncodings (bytes.data (), bytes.size (), "rank", numbers_only);
  }
  ASSERT_EQ (numbers_only.size (), with_xy.size ());
  std::size_t listings = 0;
  for (std::size_t i = 0; i < with_xy.size (); ++i)
  {
    ASSERT_EQ (numbers_only[i].model.patches.size (), with_xy[i].model.patches.size ());
    for (std::size_t p = 0; p < with_xy[i].model.patches.size (); ++p)
    {
      const PatchCode& held = numbers_only[i].model.patches[p];
      const PatchCode& stored = with_xy[i].model.patches[p];
      ASSERT_EQ (stored.vertex_xy.size (), stored.vertices.size ());
      EXPECT_EQ (held.vertices, stored.vertices);
      EXPECT_TRUE (held.vertex_xy.empty ());
      listings += held.vertices.size ();
    }
  }
  EXPECT_GT (listings, mesh->vertices.size ());
  const TiledModel reference_model = mergeTileEncodings (source.grid (), source.totalPoints (), with_xy);
  const ModelStatistics reference = reference_model.model.statistics (mesh->vertices);
  TiledModel held = mergeTileEncodings (source.grid (), source.totalPoints (), numbers_only);
  const ModelStatistics stats = tiledModelStatistics (source, held);
  EXPECT_EQ (reference.uncovered, 2u);
  EXPECT_EQ (stats.uncovered, reference.uncovered);
  EXPECT_NEAR (stats.rmse, reference.rmse, 1e-9 * reference.rmse);
  EXPECT_NEAR (stats.max_error, reference.max_error, 1e-9 * reference.max_error);
  EXPECT_NEAR (stats.mean_error_over_diagonal, reference.mean_error_over_diagonal, 1e-9 * reference.mean_error_over_diagonal);
  EXPECT_GT (reference.rmse, 0.0);
  // The measuring encoder (which holds its tiles so) gives the same figures and the same model.
  TiledModel tiled;
  const ModelStatistics measured = encodeMeasuring (source, options, tiled);
  EXPECT_EQ (measured.rmse, stats.rmse);
  EXPECT_EQ (measured.max_error, stats.max_error);
  EXPECT_TRUE (encodeTiledModel (tiled, ModelWriteOptions (), 1) == encodeTiledModel (reference_model, ModelWriteOptions (), 1));
}

// Patches list their input points by 32-bit number: an input of 2^31 points or more is refused up front,
// naming the count (the numbers wrapped to negative ones, found by a review).
TEST (TiledEncoding, RefusesMorePointsThanAModelNumbers)
{
  class HugeSource : public TileSource
  {
  public:
    const TileGrid& grid () const override { return grid_; }
    std::size_t totalPoints () const override { return std::size_t (1) << 31; }
    std::size_t corePoints (std::size_t) const override { return std::size_t (1) << 31; }
    TileInput loadTile (std::size_t) const override { throw Error ("not to be loaded"); }

  private:
    TileGrid grid_;
  };
  TiledSurfaceEncoder encoder;
  encoder.setTileSource (std::make_shared<HugeSource> ());
  TiledModel tiled;
  try
  {
    encoder.compute (tiled);
    ADD_FAILURE () << "2^31 points were accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("2147483648 points"), std::string::npos) << e.what ();
  }
}

// The compression bound holds for the whole model, not tile by tile: bounded each over its own points, a
// tile of a lidar frame's sparse far field (more surface than its share of the points) coded an atom a
// patch, and the frame in 2 x 2 tiles was 1.5x less accurate than untiled. Unbounded first, the tiles
// are as accurate as the whole; a model over the bound is still brought under it (cheese-cgal, below).
TEST (TiledEncoding, CompressionBoundHoldsForTheWholeModel)
{
  const std::string scan_path = std::string (PCL_SPARSE_SHARED_CLOUDS) + "/fast_gicp_251370668.pcd";
  const std::string mesh_path = std::string (PCL_SPARSE_SHARED_MESHES) + "/../extra-meshes/cheese-cgal.off";
  PCL_SPARSE_NEED_SHARED_FILE (scan_path);
  PCL_SPARSE_NEED_SHARED_FILE (mesh_path);
  auto scan = std::make_shared<ScanCloud> ();
  loadScanCloud (scan_path, *scan);
  SparseSurfaceEncoder<pcl::PointXYZ> whole;
  whole.setInputScan (scan);
  SparseSurfaceModel model;
  whole.compute (model);
  std::vector<Eigen::Vector3d> positions;
  for (std::size_t i = 0; i < scan->size (); ++i)
    positions.push_back (scan->worldPosition (i));
  const ModelStatistics untiled = model.statistics (positions);

  auto tiledStatistics = [] (const std::shared_ptr<const TileSource>& source) {
    TiledSurfaceEncoder encoder;
    encoder.setTileSource (source);
    encoder.setMeasurement (true);
    TiledModel tiled;
    encoder.compute (tiled);
    return encoder.getStatistics ();
  };
  TileGridOptions grid;
  grid.tiles_along_longest = 2;
  const ModelStatistics tiled = tiledStatistics (std::make_shared<MemoryTileSource> (scan, grid));
  std::cout << "fast_gicp RMSE/diag untiled " << untiled.rmse_over_diagonal << ", 2 tiles " << tiled.rmse_over_diagonal
            << " (CR " << tiled.compression_ratio << ")" << std::endl;
  // Measured 1.45e-4 against 1.93e-4 (1.27e-4 against 1.79e-4 earlier; 2.15e-4 before the fix).
  EXPECT_GT (untiled.rmse_over_diagonal, 0.0);
  EXPECT_LT (tiled.rmse_over_diagonal, 1.1 * untiled.rmse_over_diagonal);
  // Uncovered: points in no face next to the faces (PatchOptions::unreferenced_patch_spacings), 4 % of
  // the frame, the tiles' no more than untiled (measured 2564 and 2645).
  EXPECT_LT (untiled.uncovered, positions.size () / 20);
  EXPECT_LE (tiled.uncovered, untiled.uncovered);
  EXPECT_LE (tiled.compression_ratio, 1.0);

  auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (mesh_path));
  const ModelStatistics cheese = tiledStatistics (std::make_shared<MemoryTileSource> (mesh, grid));
  EXPECT_LE (cheese.compression_ratio, 1.0);  // unbounded it is over 1: the tiles were encoded again, bounded
  EXPECT_GT (cheese.compression_ratio, 0.5);  // measured 0.79: a model, not an empty one
  EXPECT_EQ (cheese.uncovered, 0u);
  // Brought under the bound, and still a good model (measured RMSE / diagonal 7.67e-4, 1292 patches).
  EXPECT_GT (cheese.rmse_over_diagonal, 0.0);
  EXPECT_LT (cheese.rmse_over_diagonal, 1.15e-3);
}
