// Tiled against untiled encoding at a scale where tiles hold many patches (issue 16 targets): a synthetic
// terrain mesh (or a mesh file), encoded whole and in tiles; patches, RMSE, file bytes (untiled; the tiled
// file; the older version-2 tiled layout; the tiled patches as one version-1 file, which isolates the
// format's per-tile cost), seconds. Then where the per-tile cost goes (each section compressed whole and
// tile by tile) and what other framings of the tiles would take (one zstd stream a tile; zstd dictionaries
// stored once: one trained on the tiles, one per section kind). For the terrain, regions of 1 % of the area
// (centred in a tile, and on a tile corner) decoded from the tiled file: bytes read, and whether the points
// equal the full decode's there.
//
//   bench_tiles [CELLS (700) | MESH] [TILES_ALONG (8)] [RHO (0.0002)] [THREADS (0)] [HARRIS_RINGS (0: adaptive)]
//               [TOLERANCE_FRACTION (3; 0: lossless)] [UNTILED (1; 0 skips the untiled encoding)]

#include "bench_main.h"

#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/file_tolerance.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/format/zstd_codec.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>
#include <pcl_sparse/tiles/memory_tile_source.h>
#include <pcl_sparse/tiles/tile_encoding.h>

#include <zdict.h>
#include <zstd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace pcl_sparse;

namespace
{
  double
  secondsSince (std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  }

  pcl::PointCloud<pcl::PointNormal>
  resample (const SparseSurfaceModel& model, double density, const std::vector<std::size_t>& numbers, int threads)
  {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (std::make_shared<const SparseSurfaceModel> (model));
    resampling.setDensity (density);
    resampling.setPatchNumbers (numbers);
    resampling.setNumberOfThreads (threads);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    return cloud;
  }

  std::vector<Eigen::Vector3f>
  inside (const pcl::PointCloud<pcl::PointNormal>& cloud, const Eigen::AlignedBox3d& box)
  {
    std::vector<Eigen::Vector3f> points;
    for (const pcl::PointNormal& p : cloud)
      if (box.contains (p.getVector3fMap ().cast<double> ()))
        points.push_back (p.getVector3fMap ());
    return points;
  }

  std::size_t
  varintBytes (std::uint64_t v)
  {
    std::size_t n = 1;
    while (v >= 128)
    {
      v >>= 7;
      ++n;
    }
    return n;
  }

  /// Bytes of the tiles framed other ways than the file's (a zstd frame per section), each with the tile's
  /// CRC-32 (the header and index are the file's): all of a tile's sections as one zstd stream; that
  /// stream compressed with a dictionary trained on the tiles and stored once (of \a dictionary_capacity
  /// bytes at most; 0 if training failed).
  struct FramingBytes
  {
    std::size_t one_stream = 0, with_dictionary = 0, dictionary = 0;
  };

  FramingBytes
  framingBytes (const TiledModel& tiled, const ModelWriteOptions& options, std::size_t dictionary_capacity)
  {
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (const TileRange& range : tiled.tiles)
      runs.emplace_back (range.first_patch, range.num_patches);
    const ModelSections sections = encodeModelSections (tiled.model, options, runs);
    FramingBytes bytes;
    std::vector<std::uint8_t> samples;
    std::vector<std::size_t> sizes;
    for (const std::vector<std::vector<std::uint8_t>>& run : sections.runs)
    {
      ByteWriter lengths;  // the sections' sizes but the last, then the sections
      for (std::size_t i = 0; i + 1 < run.size (); ++i)
        lengths.putVarint (run[i].size ());
      std::vector<std::uint8_t> content = lengths.bytes ();
      for (const std::vector<std::uint8_t>& section : run)
        content.insert (content.end (), section.begin (), section.end ());
      bytes.one_stream += compressBytes (content.data (), content.size (), options.zstd_level).size () + 4;
      samples.insert (samples.end (), content.begin (), content.end ());
      sizes.push_back (content.size ());
    }
    // Where splitting costs: each section compressed whole against compressed tile by tile.
    const ModelSections whole = encodeModelSections (tiled.model, options, {{0, tiled.model.patches.size ()}});
    const std::vector<std::string> tags = runSectionTags (whole.shared.flags);
    for (std::size_t t = 0; t < tags.size (); ++t)
    {
      const std::vector<std::uint8_t>& section = whole.runs[0][t];
      std::size_t split = 0, raw = 0;
      for (const std::vector<std::vector<std::uint8_t>>& run : sections.runs)
      {
        split += compressBytes (run[t].data (), run[t].size (), options.zstd_level).size ();
        raw += run[t].size ();
      }
      const std::size_t together = compressBytes (section.data (), section.size (), options.zstd_level).size ();
      std::printf ("  %s: raw %zu (tiles %zu), zstd whole %zu, tile by tile %zu (%+.1f bytes a tile)\n", tags[t].c_str (),
                   section.size (), raw, together, split,
                   (static_cast<double> (split) - static_cast<double> (together)) / sections.runs.size ());
    }
    // A dictionary per section kind (entropy tables from the tiles' sections and the last \a content
    // bytes of the whole model's section), stored once; each tile's sections in frames of their own with it.
    for (std::size_t content : {std::size_t (128), std::size_t (1024), std::size_t (4096)})
    {
      std::size_t total = 0, dictionaries = 0;
      for (std::size_t t = 0; t < tags.size (); ++t)
      {
        std::vector<std::uint8_t> kind_samples;
        std::vector<std::size_t> kind_sizes;
        for (const std::vector<std::vector<std::uint8_t>>& run : sections.runs)
        {
          kind_samples.insert (kind_samples.end (), run[t].begin (), run[t].end ());
          kind_sizes.push_back (run[t].size ());
        }
        const std::vector<std::uint8_t>& section = whole.runs[0][t];
        const std::size_t take = std::min (content, section.size ());
        std::vector<std::uint8_t> dictionary (std::max<std::size_t> (take + 2048, 256));
        ZDICT_params_t params = {};
        params.compressionLevel = options.zstd_level;
        const std::size_t made =
          take < 128 ? 1
                     : ZDICT_finalizeDictionary (dictionary.data (), dictionary.size (), section.data () + section.size () - take,
                                                 take, kind_samples.data (), kind_sizes.data (),
                                                 static_cast<unsigned> (kind_sizes.size ()), params);
        if (take < 128 || ZDICT_isError (made))
        {
          for (const std::vector<std::vector<std::uint8_t>>& run : sections.runs)
            total += compressBytes (run[t].data (), run[t].size (), options.zstd_level).size () + 2;
          continue;
        }
        dictionaries += made;
        ZSTD_CCtx* context = ZSTD_createCCtx ();
        ZSTD_CCtx_setParameter (context, ZSTD_c_compressionLevel, options.zstd_level);
        ZSTD_CCtx_setParameter (context, ZSTD_c_dictIDFlag, 0);
        ZSTD_CCtx_loadDictionary (context, dictionary.data (), made);
        for (const std::vector<std::vector<std::uint8_t>>& run : sections.runs)
        {
          std::vector<std::uint8_t> out (ZSTD_compressBound (run[t].size ()));
          total += ZSTD_compress2 (context, out.data (), out.size (), run[t].data (), run[t].size ()) + 2;
        }
        ZSTD_freeCCtx (context);
      }
      std::printf ("  per section kind a dictionary (%zu bytes of content), each section a frame: %zu bytes of "
                   "dictionaries + %zu of tiles = %zu (+ header and index)\n",
                   content,
                   dictionaries, total + 4 * sections.runs.size (), dictionaries + total + 4 * sections.runs.size ());
    }
    std::vector<std::uint8_t> dictionary (dictionary_capacity);
    const std::size_t trained =
      ZDICT_trainFromBuffer (dictionary.data (), dictionary.size (), samples.data (), sizes.data (),
                             static_cast<unsigned> (sizes.size ()));
    if (ZDICT_isError (trained))
      return bytes;
    dictionary.resize (trained);
    bytes.dictionary = trained;
    ZSTD_CCtx* context = ZSTD_createCCtx ();
    std::size_t at = 0;
    for (std::size_t size : sizes)
    {
      std::vector<std::uint8_t> out (ZSTD_compressBound (size));
      const std::size_t n = ZSTD_compress_usingDict (context, out.data (), out.size (), samples.data () + at, size,
                                                     dictionary.data (), dictionary.size (), options.zstd_level);
      bytes.with_dictionary += n + 4;
      at += size;
    }
    ZSTD_freeCCtx (context);
    bytes.with_dictionary += trained;
    return bytes;
  }
} // namespace

static int
run (int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : "700";
  const int along = argc > 2 ? std::atoi (argv[2]) : 8;
  const double rho = argc > 3 ? std::atof (argv[3]) : 0.0002;
  const int threads = argc > 4 ? std::atoi (argv[4]) : 0;
  const double fraction = argc > 6 ? std::atof (argv[6]) : 3.0;
  const bool untiled = argc > 7 ? std::atoi (argv[7]) != 0 : true;
  const bool synthetic = input.find_first_not_of ("0123456789") == std::string::npos;
  TriangleMesh::Ptr mesh;
  if (synthetic)
  {
    const int cells = std::atoi (input.c_str ());
    mesh = std::make_shared<TriangleMesh> (makeHeightFieldGrid (cells, cells, 1.0, 1.0, [] (double x, double y) {
      return 0.06 * std::sin (9.0 * x) * std::cos (8.0 * y) + 0.02 * std::sin (23.0 * x + 17.0 * y) + 0.05 * x * y;
    }));
  }
  else
    mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (input));
  SparseSurfaceEncoderOptions options;
  options.patches.rho = rho;
  options.patches.harris_rings = argc > 5 ? std::atoi (argv[5]) : 0;

  auto start = std::chrono::steady_clock::now ();
  SparseSurfaceModel whole;
  double whole_seconds = 0.0;
  ModelStatistics whole_stats;
  if (untiled)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (mesh);
    encoder.setOptions (options);
    encoder.setNumberOfThreads (threads);
    encoder.compute (whole);
    whole_seconds = secondsSince (start);
    whole_stats = whole.statistics (mesh->vertices);
  }

  start = std::chrono::steady_clock::now ();
  TileGridOptions grid;
  grid.tiles_along_longest = along;
  TiledSurfaceEncoder tiled_encoder;
  tiled_encoder.setTileSource (std::make_shared<MemoryTileSource> (mesh, grid));
  tiled_encoder.setOptions (options);
  tiled_encoder.setNumberOfThreads (threads);
  TiledModel tiled;
  tiled_encoder.compute (tiled);
  const double tiled_seconds = secondsSince (start);
  const ModelStatistics tiled_stats = tiled.model.statistics (mesh->vertices);
  ModelWriteOptions write;
  write.tolerance = fraction > 0.0 ? derivedFileTolerance (untiled ? whole_stats : tiled_stats, fraction) : 0.0;
  const std::size_t whole_bytes = untiled ? encodeModel (whole, write).size () : 0;
  const std::size_t same_patches_bytes = encodeModel (tiled.model, write).size ();
  // The version-2 layout: a 104-byte header, 88 bytes of index a tile and its checksum, each tile a version-1 model.
  std::size_t version2_bytes = 104 + 88 * tiled.tiles.size () + 4;
  for (const TileRange& range : tiled.tiles)
    version2_bytes += encodeModel (subModel (tiled.model, range.first_patch, range.num_patches), write).size ();
  const std::string path = (std::filesystem::temp_directory_path () / "bench_tiles.psm").string ();
  saveTiledModel (path, tiled, write, threads);
  const double file_bytes = static_cast<double> (std::filesystem::file_size (path));
  const TiledModelIndex index = readTiledModelIndex (path);

  std::printf ("| vertices | tiles | rho | patches untiled / tiled | RMSE untiled / tiled | bytes untiled / tiled | "
               "seconds untiled / tiled |\n|---|---|---|---|---|---|---|\n");
  if (untiled)
    std::printf ("| %zu | %zu | %g | %zu / %zu (%+.1f %%) | %.4g / %.4g (%+.1f %%) | %zu / %.0f (%+.2f %%) | %.1f / %.1f |\n",
                 mesh->vertices.size (), tiled.tiles.size (), rho, whole.patches.size (), tiled.model.patches.size (),
                 100.0 * (static_cast<double> (tiled.model.patches.size ()) / whole.patches.size () - 1.0), whole_stats.rmse,
                 tiled_stats.rmse, 100.0 * (tiled_stats.rmse / whole_stats.rmse - 1.0), whole_bytes, file_bytes,
                 100.0 * (file_bytes / whole_bytes - 1.0), whole_seconds, tiled_seconds);
  else
    std::printf ("| %zu | %zu | %g | - / %zu | - / %.4g | - / %.0f | - / %.1f |\n", mesh->vertices.size (), tiled.tiles.size (),
                 rho, tiled.model.patches.size (), tiled_stats.rmse, file_bytes, tiled_seconds);
  std::printf ("\nfile tolerance %.3g (%g x the mean error); tiled patches as one version-1 file: %zu bytes; tiled file "
               "%.0f (%+.2f %%: %+.1f bytes a tile; header and index %llu); version-2 layout %zu (%+.2f %%)\n",
               write.tolerance, fraction, same_patches_bytes, file_bytes, 100.0 * (file_bytes / same_patches_bytes - 1.0),
               (file_bytes - same_patches_bytes) / tiled.tiles.size (), static_cast<unsigned long long> (index.index_bytes),
               version2_bytes, 100.0 * (static_cast<double> (version2_bytes) / same_patches_bytes - 1.0));
  {
    const std::size_t capacity = 2048;
    const FramingBytes framing = framingBytes (tiled, write, capacity);
    const double fixed = static_cast<double> (index.index_bytes);
    std::printf ("tiles framed other ways: one zstd stream each %.0f; one stream each with a %zu-byte dictionary "
                 "(capacity %zu) %.0f\n",
                 fixed + framing.one_stream, framing.dictionary, capacity,
                 framing.dictionary ? fixed + framing.with_dictionary : 0.0);
  }

  if (!synthetic)
  {
    std::filesystem::remove (path);
    return 0;
  }
  // Regions of 1 % of the area (a tenth of the x and y sides of the bounding box), centred in a tile, and
  // centred on a corner of that tile.
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3d& v : mesh->vertices)
    bounds.extend (v);
  const Eigen::Vector3d at = bounds.min () + 0.3 * bounds.sizes ();
  const double density = 4.0 * mesh->vertices.size () / 4.0 / (bounds.sizes ().x () * bounds.sizes ().y () / 4.0);
  const pcl::PointCloud<pcl::PointNormal> full = resample (loadModel (path), density, {}, threads);
  const Eigen::Vector3d middle = tiled.grid.coreBox (tiled.grid.tileOf (at)).center ();
  const Eigen::Vector3d corner = tiled.grid.coreBox (tiled.grid.tileOf (at)).min ();
  std::printf ("\n| region (1 %% of the area) | tiles read | bytes read | of the file | points | equal to the full decode |\n"
               "|---|---|---|---|---|---|\n");
  for (const auto& [name, centre] : {std::make_pair ("in a tile", middle), std::make_pair ("at a tile corner", corner)})
  {
    const Eigen::Vector3d half (0.05 * bounds.sizes ().x (), 0.05 * bounds.sizes ().y (), 10.0 * bounds.sizes ().norm ());
    const Eigen::AlignedBox3d box (Eigen::Vector3d (centre.x (), centre.y (), 0.0) - half,
                                   Eigen::Vector3d (centre.x (), centre.y (), 0.0) + half);
    std::uint64_t bytes_read = 0;
    const TiledModel region = loadTiledModelRegion (path, box, &bytes_read);
    const pcl::PointCloud<pcl::PointNormal> part = region.model.patches.empty ()
                                                     ? pcl::PointCloud<pcl::PointNormal> ()
                                                     : resample (region.model, density, region.patchNumbers (), threads);
    const std::vector<Eigen::Vector3f> expected = inside (full, box), got = inside (part, box);
    std::printf ("| %s | %zu of %zu | %llu | %.2f %% | %zu | %s |\n", name, region.tiles.size (), tiled.tiles.size (),
                 static_cast<unsigned long long> (bytes_read), 100.0 * bytes_read / file_bytes, got.size (),
                 expected == got ? "yes" : "NO");
  }
  std::filesystem::remove (path);
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
