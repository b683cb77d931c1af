#include <pcl_sparse/format/tile_encoding_bytes.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/model_sections.h>

#include <algorithm>
#include <limits>

namespace pcl_sparse
{
  namespace
  {
    /// TileEncoding::moved: the count, then each number's step from the last (ascending) and its offset.
    void
    putMovedPoints (ByteWriter& out, const TileEncoding& tile, std::size_t total_points)
    {
      const MovedPoints& moved = tile.moved;
      out.putVarint (moved.numbers.size ());
      for (std::size_t k = 0; k < moved.numbers.size (); ++k)
      {
        if (moved.numbers[k] >= total_points || (k > 0 && moved.numbers[k] <= moved.numbers[k - 1]) ||
            moved.offsets.size () != moved.numbers.size ())
          throw Error ("encodeTileEncodings: tile " + std::to_string (tile.tile) +
                       "'s moved points are not ascending numbers of the input with an offset each");
        out.putVarint (k == 0 ? moved.numbers[k] : moved.numbers[k] - moved.numbers[k - 1]);
        for (int a = 0; a < 3; ++a)
          out.putF32 (moved.offsets[k][a]);
      }
    }

    void
    getMovedPoints (ByteReader& in, TileEncoding& tile)
    {
      // A tile without patches has no model to bound the numbers; each takes 13 bytes at least.
      const std::uint64_t total = tile.model.patches.empty () ? std::numeric_limits<std::uint64_t>::max ()
                                                              : tile.model.num_input_vertices;
      const std::uint64_t count = in.getCount ("moved points", std::min<std::uint64_t> (total, in.remaining () / 13));
      tile.moved.numbers.reserve (count);
      tile.moved.offsets.reserve (count);
      for (std::uint64_t k = 0; k < count; ++k)
      {
        const std::uint64_t step = in.getVarint ("moved point");
        const std::uint64_t number = k == 0 ? step : tile.moved.numbers.back () + step;
        if ((k > 0 && step == 0) || number >= total || number < step)
          in.fail ("tile " + std::to_string (tile.tile) + ": moved point out of range");
        tile.moved.numbers.push_back (static_cast<std::size_t> (number));
        Eigen::Vector3f offset;
        for (int a = 0; a < 3; ++a)
          offset[a] = in.getF32 ("moved offset");
        tile.moved.offsets.push_back (offset);
      }
    }
  } // namespace

  std::vector<std::uint8_t>
  encodeTileEncodings (const std::vector<TileEncoding>& tiles, std::size_t total_points)
  {
    ByteWriter out;
    out.putVarint (tiles.size ());
    ModelWriteOptions lossless;
    lossless.zstd_level = 1;
    for (const TileEncoding& tile : tiles)
    {
      // Vertex lists held for the statistics only have no (x', y') (encodeTile): their numbers follow the
      // model, which is then written without its vertices.
      const bool numbers_only = std::any_of (tile.model.patches.begin (), tile.model.patches.end (), [] (const PatchCode& p) {
        return p.vertex_xy.size () != p.vertices.size ();
      });
      lossless.include_vertices = !numbers_only;
      out.putU64 (tile.tile);
      out.putU8 (tile.core_bounds.isEmpty () ? 0 : 1);
      for (int a = 0; a < 3; ++a)
        out.putF64 (tile.core_bounds.isEmpty () ? 0.0 : tile.core_bounds.min ()[a]);
      for (int a = 0; a < 3; ++a)
        out.putF64 (tile.core_bounds.isEmpty () ? 0.0 : tile.core_bounds.max ()[a]);
      out.putF64 (tile.seconds);
      out.putVarint (static_cast<std::uint64_t> (std::max (0, tile.reach)));
      out.putVarint (numbers_only ? 1 : 0);
      if (tile.model.patches.empty ())
      {
        out.putVarint (0);
        putMovedPoints (out, tile, total_points);
        continue;
      }
      // The header's count bounds the vertex numbers the receiver reads.
      if (tile.model.num_input_vertices != total_points)
        throw Error ("encodeTileEncodings: tile " + std::to_string (tile.tile) + " counts " +
                     std::to_string (tile.model.num_input_vertices) + " input points, not the whole input's " +
                     std::to_string (total_points) + " (encodeTile)");
      const std::vector<std::uint8_t> bytes = encodeModel (tile.model, lossless);
      out.putVarint (bytes.size ());
      out.putBytes (bytes.data (), bytes.size ());
      if (numbers_only)
        for (const PatchCode& patch : tile.model.patches)
          putVertexNumbers (out, patch.vertices, total_points);
      putMovedPoints (out, tile, total_points);
    }
    return std::move (out.bytes ());
  }

  void
  decodeTileEncodings (const std::uint8_t* data, std::size_t size, const std::string& name, std::vector<TileEncoding>& tiles)
  {
    ByteReader in (data, size, name);
    const std::uint64_t count = in.getCount ("number of tiles", size / 58 + 1);
    for (std::uint64_t i = 0; i < count; ++i)
    {
      TileEncoding tile;
      tile.tile = in.getU64 ("tile");
      const bool has_bounds = in.getU8 ("bounds flag") != 0;
      Eigen::Vector3d lo, hi;
      for (int a = 0; a < 3; ++a)
        lo[a] = in.getF64 ("bounds");
      for (int a = 0; a < 3; ++a)
        hi[a] = in.getF64 ("bounds");
      if (has_bounds)
        tile.core_bounds = Eigen::AlignedBox3d (lo, hi);
      tile.seconds = in.getF64 ("seconds");
      tile.reach = static_cast<int> (in.getCount ("reach", std::uint64_t{1} << 20));
      const bool numbers_only = in.getCount ("vertex list kind", 1) == 1;
      const std::uint64_t bytes = in.getCount ("model bytes", size);
      if (bytes > 0)
        tile.model = decodeModel (in.getBytes (bytes, "model"), bytes, name + ": tile " + std::to_string (tile.tile));
      if (numbers_only)
        for (std::size_t p = 0; p < tile.model.patches.size (); ++p)
          getVertexNumbers (in, tile.model.num_input_vertices, 0, p, tile.model.patches[p].vertices);
      getMovedPoints (in, tile);
      tiles.push_back (std::move (tile));
    }
    in.expectEnd ();
  }
} // namespace pcl_sparse
