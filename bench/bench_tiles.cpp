// Tiled against untiled encoding at a scale where tiles hold many patches (issue 16 targets): a synthetic
// terrain mesh, encoded whole and in tiles; patches, RMSE, file bytes, seconds; then regions of 1 % of the
// area (a tile's middle and a corner where four tiles meet) decoded from the tiled file: bytes read, and
// whether the points equal the full decode's there.
//
//   bench_tiles [CELLS (700)] [TILES_ALONG (8)] [RHO (0.0002)] [THREADS (0)] [HARRIS_RINGS (0: adaptive)]

#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>
#include <pcl_sparse/tiles/memory_tile_source.h>
#include <pcl_sparse/tiles/tile_encoding.h>

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
} // namespace

int
main (int argc, char** argv)
{
  const int cells = argc > 1 ? std::atoi (argv[1]) : 700;
  const int along = argc > 2 ? std::atoi (argv[2]) : 8;
  const double rho = argc > 3 ? std::atof (argv[3]) : 0.0002;
  const int threads = argc > 4 ? std::atoi (argv[4]) : 0;
  auto mesh = std::make_shared<TriangleMesh> (makeHeightFieldGrid (cells, cells, 1.0, 1.0, [] (double x, double y) {
    return 0.06 * std::sin (9.0 * x) * std::cos (8.0 * y) + 0.02 * std::sin (23.0 * x + 17.0 * y) + 0.05 * x * y;
  }));
  SparseSurfaceEncoderOptions options;
  options.patches.rho = rho;
  options.patches.harris_rings = argc > 5 ? std::atoi (argv[5]) : 0;

  auto start = std::chrono::steady_clock::now ();
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (mesh);
  encoder.setOptions (options);
  encoder.setNumberOfThreads (threads);
  SparseSurfaceModel whole;
  encoder.compute (whole);
  const double whole_seconds = secondsSince (start);
  const ModelStatistics whole_stats = whole.statistics (mesh->vertices);
  ModelWriteOptions write;
  write.tolerance = derivedFileTolerance (whole_stats);
  const std::size_t whole_bytes = encodeModel (whole, write).size ();

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
  const std::string path = (std::filesystem::temp_directory_path () / "bench_tiles.psm").string ();
  saveTiledModel (path, tiled, write, threads);
  const double file_bytes = static_cast<double> (std::filesystem::file_size (path));

  std::printf ("| vertices | tiles | rho | patches untiled / tiled | RMSE untiled / tiled | bytes untiled / tiled | "
               "seconds untiled / tiled |\n|---|---|---|---|---|---|---|\n");
  std::printf ("| %zu | %zu | %g | %zu / %zu (%+.1f %%) | %.4g / %.4g (%+.1f %%) | %zu / %.0f (%+.1f %%) | %.1f / %.1f |\n",
               mesh->vertices.size (), tiled.tiles.size (), rho, whole.patches.size (), tiled.model.patches.size (),
               100.0 * (static_cast<double> (tiled.model.patches.size ()) / whole.patches.size () - 1.0), whole_stats.rmse,
               tiled_stats.rmse, 100.0 * (tiled_stats.rmse / whole_stats.rmse - 1.0), whole_bytes, file_bytes,
               100.0 * (file_bytes / whole_bytes - 1.0), whole_seconds, tiled_seconds);

  // Regions of 1 % of the 2 x 2 area: 0.2 x 0.2, centred in a tile, and centred where four tiles meet.
  const double density = 4.0 * mesh->vertices.size () / 4.0;
  const pcl::PointCloud<pcl::PointNormal> full = resample (loadModel (path), density, {}, threads);
  const Eigen::Vector3d middle = tiled.grid.coreBox (tiled.grid.tileOf (Eigen::Vector3d (0.3, 0.3, 0.0))).center ();
  const Eigen::Vector3d corner = tiled.grid.coreBox (tiled.grid.tileOf (Eigen::Vector3d (0.3, 0.3, 0.0))).min ();
  std::printf ("\n| region (1 %% of the area) | tiles read | bytes read | of the file | points | equal to the full decode |\n"
               "|---|---|---|---|---|---|\n");
  for (const auto& [name, centre] : {std::make_pair ("in a tile", middle), std::make_pair ("where 4 tiles meet", corner)})
  {
    const Eigen::Vector3d half (0.1, 0.1, 10.0);
    const Eigen::AlignedBox3d box (centre - half, centre + half);
    std::uint64_t bytes_read = 0;
    const TiledModel region = loadTiledModelRegion (path, box, &bytes_read);
    const pcl::PointCloud<pcl::PointNormal> part = resample (region.model, density, region.patchNumbers (), threads);
    const std::vector<Eigen::Vector3f> expected = inside (full, box), got = inside (part, box);
    std::printf ("| %s | %zu of %zu | %llu | %.2f %% | %zu | %s |\n", name, region.tiles.size (), tiled.tiles.size (),
                 static_cast<unsigned long long> (bytes_read), 100.0 * bytes_read / file_bytes, got.size (),
                 expected == got ? "yes" : "NO");
  }
  std::filesystem::remove (path);
  return 0;
}
