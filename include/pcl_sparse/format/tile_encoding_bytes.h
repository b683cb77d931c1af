#pragma once
/// \file tile_encoding_bytes.h
/// One encoded tile as bytes, for sending between processes (pcl_sparse_encode under mpirun): the tile's
/// number, core bounds and seconds, and its model as a lossless version-1 model with its vertices, so the
/// receiver gets every double bit for bit and the merged model does not depend on where a tile was encoded.
/// Vertex lists held for the statistics only (no PatchCode::vertex_xy, encodeTile) go as their numbers
/// alone, after the model, and come back so; then the tile's moved points (TileEncoding::moved).

#include <pcl_sparse/model/tiled_model.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief The bytes of \a tiles (any number of tile encodings).
  /// \param[in] tiles          the encodings
  /// \param[in] total_points   points of the whole input (the models' vertex numbers are below it)
  /// \return the bytes
  /// \throws pcl_sparse::Error for a tile with patches whose model's num_input_vertices is not
  ///         \a total_points (encodeTile sets it so), or a model encodeModel refuses
  std::vector<std::uint8_t>
  encodeTileEncodings (const std::vector<TileEncoding>& tiles, std::size_t total_points);

  /// \brief Decodes encodeTileEncodings' bytes, appending the tiles to \a tiles.
  /// \param[in] data   first byte
  /// \param[in] size   number of bytes
  /// \param[in] name   names the data in error messages
  /// \param[in,out] tiles receives the tiles
  /// \throws pcl_sparse::Error for malformed bytes
  void
  decodeTileEncodings (const std::uint8_t* data, std::size_t size, const std::string& name, std::vector<TileEncoding>& tiles);
} // namespace pcl_sparse
