#pragma once
/// \file tool_tiling.h
/// How pcl_sparse_encode decides to tile (issue 16): -tiles N forces N tiles along the longest side of
/// the bounding box; otherwise an input whose untiled encoding would not fit the -memory budget (default
/// 2G) is cut into tiles sized to fit it (the encoding itself: tool_tiled_encoding.h).

#include "tool_support.h"

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/tiles/tile_source.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace pcl_sparse
{
  namespace tools
  {
    /// Bytes the untiled encoder needs per input point: the peak resident set of pcl_sparse_encode less its
    /// 35 MB at start, over the points, measured 450 (koala-loop1-200k, a mesh) to 895 (table_scene_mug,
    /// a kNN scan surface), taken as 1.5 KB for room to spare.
    constexpr double kEncoderBytesPerPoint = 1536.0;

    /// Tiles a process encodes side by side when tiling for a -memory budget (its threads are capped at
    /// this): tiles are sized so that this many fit the budget together. A fixed number, so that the tiles
    /// (and the model) do not depend on the number of threads.
    constexpr int kBudgetTilesAtOnce = 2;

    /// Tiles a budget-tiled input is cut into at least (TileGridOptions::min_tiles, tiles of 50,000 points
    /// at the smallest): 20 x 20 on a height field, so that a box of a hundredth of the area decodes from
    /// a few tiles, under 5 % of the file (bench/region_read.sh). The budget's tiles would be fewer below
    /// about 100 M points at -memory 2G (9 x 9 at 20 M points: 6.6 % of the file a region on average).
    constexpr std::size_t kRegionTiles = 400;

    /// A byte count with an optional binary suffix: "2G", "512M", "1.5T", "100000" (K, M, G, T = 2^10 ..
    /// 2^40). Throws Error naming \a option for anything else or a value below 1 MiB.
    std::uint64_t
    parseByteSize (const std::string& option, const std::string& text);

    /// The -memory budget in bytes (default 2G).
    std::uint64_t
    memoryBudget (const CommandLine& args);

    /// \brief Whether \a path is to be encoded without loading it whole (issue 16): a PCD or PLY file that
    /// can be streamed (ScanStreamReader, or MeshStreamReader for a PLY with faces) and whose point count,
    /// read from its header, times kEncoderBytesPerPoint exceeds the -memory budget. Files too small to
    /// hold that many points (12 bytes a point at least) are not opened.
    /// \param[in] args    the command line (-memory)
    /// \param[in] path    the input file
    /// \param[out] mesh   whether it is a mesh (a PLY with faces)
    /// \param[out] points its points (vertices) by its header, when true is returned
    bool
    spillsInput (const CommandLine& args, const std::string& path, bool& mesh, std::size_t& points);

    /// How to tile an input of \a points points from -tiles and -memory: false (not tiled), or true and
    /// \a options set (tiles_along_longest from -tiles, else points_per_tile from the budget and min_tiles
    /// kRegionTiles).
    bool
    chooseTiling (const CommandLine& args, std::size_t points, TileGridOptions& options);
  } // namespace tools
} // namespace pcl_sparse
