// The bounded-memory reader on large generated clouds (issue 16 points 2 and 5), for bench/tiles_spill.sh:
//
//   bench_tiles_spill terrain N OUT.pcd [-seed S] [-double]   writes a terrain-like height field of N points
//   bench_tiles_spill block MESH COPIES_X COPIES_Y POINTS_PER_COPY OUT.pcd [-seed S]   a city block of mesh copies
//   bench_tiles_spill terrainmesh SIDE OUT.ply [-seed S]      a terrain mesh of SIDE x SIDE vertices (binary PLY)
//   bench_tiles_spill spill IN.pcd [-points_per_tile N] [-buffer_mb B] [-dir D]
//   bench_tiles_spill spillmesh IN.ply [-points_per_tile N] [-buffer_mb B] [-dir D]   the same for a mesh
//   bench_tiles_spill whole IN.pcd     loads the file in one piece (loadScanCloud), for comparison
//   bench_tiles_spill wholemesh IN.ply loads the mesh in one piece (loadTriangleMesh)
//
// spill builds a SpilledTileSource (spillmesh a SpilledMeshTileSource) (two reads of the file, one write and one read of the spill files), then
// loads every tile once, and prints one JSON object: points, tiles, seconds of each step, bytes read and
// spilled, the input's MB/s over the spill. Run it under /usr/bin/time -v for the peak RSS.
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/tiles/spilled_mesh_tile_source.h>
#include <pcl_sparse/tiles/spilled_tile_source.h>

#include <pcl/console/parse.h>

#include "generated_clouds.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

using namespace pcl_sparse;

namespace
{
  double
  secondsSince (std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  }

  int
  spill (int argc, char** argv)
  {
    const std::string path = argv[2];
    SpillOptions options;
    int points_per_tile = static_cast<int> (options.grid.points_per_tile);
    int buffer_mb = static_cast<int> (options.buffer_bytes >> 20);
    pcl::console::parse_argument (argc, argv, "-points_per_tile", points_per_tile);
    pcl::console::parse_argument (argc, argv, "-buffer_mb", buffer_mb);
    pcl::console::parse_argument (argc, argv, "-dir", options.directory);
    options.grid.points_per_tile = static_cast<std::size_t> (points_per_tile);
    options.buffer_bytes = static_cast<std::size_t> (buffer_mb) << 20;

    const bool mesh = std::string (argv[1]) == "spillmesh";
    const auto start = std::chrono::steady_clock::now ();
    TileSource::Ptr source;
    if (mesh)
      source = spillMeshIntoTiles (path, options);
    else
      source = spillIntoTiles (path, options);
    const double spill_seconds = secondsSince (start);
    const auto load_start = std::chrono::steady_clock::now ();
    std::size_t loaded = 0, largest = 0, busy = 0;  // points (vertices of a mesh)
    for (std::size_t t = 0; t < source->grid ().size (); ++t)
    {
      const TileInput tile = source->loadTile (t);
      const std::size_t n = tile.scan ? tile.scan->size () : (tile.mesh ? tile.mesh->vertices.size () : 0);
      loaded += n;
      largest = std::max (largest, n);
      busy += n > 0;
    }
    const double load_seconds = secondsSince (load_start);
    const double file_mb = static_cast<double> (std::filesystem::file_size (path)) / (1 << 20);
    const auto* cloud = dynamic_cast<const SpilledTileSource*> (source.get ());
    const auto* mesh_source = dynamic_cast<const SpilledMeshTileSource*> (source.get ());
    const double spilled_mb = static_cast<double> (cloud ? cloud->spilledBytes () : mesh_source->spilledBytes ()) / (1 << 20);
    std::printf ("{\"kept\": %zu, \"tiles\": %zu, \"tiles_with_points\": %zu, \"largest_tile\": %zu, "
                 "\"points_in_tiles\": %zu, \"file_mb\": %.1f, \"spilled_mb\": %.1f, \"spill_seconds\": %.2f, "
                 "\"load_tiles_seconds\": %.2f, \"input_mb_per_s\": %.1f}\n",
                 source->totalPoints (), source->grid ().size (), busy, largest, loaded, file_mb,
                 spilled_mb, spill_seconds,
                 load_seconds, file_mb / spill_seconds);
    return 0;
  }
} // namespace

int
main (int argc, char** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "";
  try
  {
    int seed = 1;
    pcl::console::parse_argument (argc, argv, "-seed", seed);
    if (mode == "terrain" && argc >= 4)
    {
      pcl_sparse_test::TerrainOptions terrain;
      terrain.points = std::strtoull (argv[2], nullptr, 10);
      terrain.seed = static_cast<std::uint64_t> (seed);
      terrain.double_xyz = pcl::console::find_switch (argc, argv, "-double");
      pcl_sparse_test::writeTerrainPcd (argv[3], terrain);
      return 0;
    }
    if (mode == "block" && argc >= 7)
    {
      pcl_sparse_test::CityBlockOptions block;
      block.copies_x = std::atoi (argv[3]);
      block.copies_y = std::atoi (argv[4]);
      block.points_per_copy = std::strtoull (argv[5], nullptr, 10);
      block.seed = static_cast<std::uint64_t> (seed);
      pcl_sparse_test::writeCityBlockPcd (argv[6], loadTriangleMesh (argv[2]), block);
      return 0;
    }
    if ((mode == "spill" || mode == "spillmesh") && argc >= 3)
      return spill (argc, argv);
    if (mode == "terrainmesh" && argc >= 4)
    {
      pcl_sparse_test::TerrainOptions terrain;
      terrain.seed = static_cast<std::uint64_t> (seed);
      pcl_sparse_test::writeTerrainMeshPly (argv[3], std::strtoull (argv[2], nullptr, 10), terrain);
      return 0;
    }
    if (mode == "wholemesh" && argc >= 3)
    {
      std::printf ("{\"vertices\": %zu}\n", loadTriangleMesh (argv[2]).vertices.size ());
      return 0;
    }
    if (mode == "whole" && argc >= 3)
    {
      ScanCloud scan;
      loadScanCloud (argv[2], scan);
      std::printf ("{\"kept\": %zu}\n", scan.size ());
      return 0;
    }
  }
  catch (const std::exception& error)
  {
    std::cerr << error.what () << "\n";
    return 1;
  }
  std::cerr << "usage: bench_tiles_spill terrain N OUT.pcd [-seed S] [-double]\n"
               "       bench_tiles_spill block MESH COPIES_X COPIES_Y POINTS_PER_COPY OUT.pcd [-seed S]\n"
               "       bench_tiles_spill terrainmesh SIDE OUT.ply [-seed S]\n"
               "       bench_tiles_spill spill IN.pcd [-points_per_tile N] [-buffer_mb B] [-dir D]\n"
               "       bench_tiles_spill spillmesh IN.ply [-points_per_tile N] [-buffer_mb B] [-dir D]\n"
               "       bench_tiles_spill whole IN.pcd\n"
               "       bench_tiles_spill wholemesh IN.ply\n";
  return 2;
}
