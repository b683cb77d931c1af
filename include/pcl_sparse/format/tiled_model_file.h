#pragma once
/// \file tiled_model_file.h
/// The tiled .psm file (format version 3, docs/FORMAT.md "Tiled files"; issue 16): a header with the tile grid and
/// what every tile shares (basis, quantisation parameters, attribute channels), a compact tile index (tile -> patch
/// range, byte range and the box its patches can reach), then each tile's per-patch sections (a zstd frame each). A
/// region is decoded by reading the header, the index and only the tiles whose patches reach into it; loadModel /
/// decodeModel read a tiled file as the merged model. Files of the older tiled layout (version 2: every tile a
/// complete version-1 model) are still read.

#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/model/tiled_model.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// One entry of the tile index.
  struct TileIndexEntry
  {
    std::size_t tile = 0;            ///< tile number in the grid
    std::size_t first_patch = 0;     ///< number of its first patch in the whole model
    std::size_t num_patches = 0;     ///< its patches
    std::uint64_t offset = 0;        ///< byte offset of its bytes from the start of the file
    std::uint64_t size = 0;          ///< its bytes (version 3: its sections and their CRC-32)
    Eigen::AlignedBox3d reach;       ///< every surface point its patches can give (patchReachBox, + tolerance; rounded outward)
  };

  /// The header and tile index of a tiled file.
  struct TiledModelIndex
  {
    TileGrid grid;                          ///< the grid
    std::uint64_t num_input_vertices = 0;   ///< of the whole input
    double bbox_diagonal = 0.0;             ///< of the whole input
    double tolerance = 0.0;                 ///< as written (fraction of bbox_diagonal)
    std::size_t total_patches = 0;          ///< of the whole model
    std::vector<TileIndexEntry> entries;    ///< tiles with patches, ascending
    std::uint64_t index_bytes = 0;          ///< bytes of the header, the shared sections and the index
    std::uint16_t version = 3;              ///< tiled format version (2 or 3)
    SharedModelFields shared;               ///< version 3: what the tiles share (basis, flags, QUAN, ACHN)
  };

  /// Whether \a data starts like a tiled model file (magic and version 2 or 3).
  bool
  isTiledModelData (const std::uint8_t* data, std::size_t size);

  /// Whether the file at \a path starts like a tiled model file (false if it cannot be read).
  bool
  isTiledModelFile (const std::string& path);

  /// \brief The bytes of a tiled file; tiles are encoded in parallel (\a num_threads, 0 = default), the bytes
  /// do not depend on it.
  /// \param[in] tiled        the tiled model
  /// \param[in] options      as for encodeModel (quantisation is chosen over the whole model)
  /// \param[in] num_threads  OpenMP threads
  /// \return the file's bytes
  /// \throws pcl_sparse::Error as encodeModel, or for tile ranges that do not fit the model
  std::vector<std::uint8_t>
  encodeTiledModel (const TiledModel& tiled, const ModelWriteOptions& options = ModelWriteOptions (), int num_threads = 0);

  /// \brief encodeTiledModel, written atomically.
  /// \param[in] path         the file
  /// \param[in] tiled        the tiled model
  /// \param[in] options      as for encodeModel
  /// \param[in] num_threads  OpenMP threads
  void
  saveTiledModel (const std::string& path, const TiledModel& tiled, const ModelWriteOptions& options = ModelWriteOptions (),
                  int num_threads = 0);

  /// \brief Decodes the whole bytes of a tiled file.
  /// \param[in] data  first byte
  /// \param[in] size  number of bytes
  /// \param[in] name  names the data in error messages
  /// \return every tile
  /// \throws pcl_sparse::Error for anything malformed
  TiledModel
  decodeTiledModel (const std::uint8_t* data, std::size_t size, const std::string& name = "model");

  /// \brief Reads the header and tile index of a tiled file (and nothing else).
  /// \param[in] path the file
  /// \return the index
  /// \throws pcl_sparse::Error naming the file if it is not a tiled model file or is malformed
  TiledModelIndex
  readTiledModelIndex (const std::string& path);

  /// \brief Loads the tiles whose patches can reach into \a box (every patch that can give a point in the
  /// box or compete for one, resampling ownership), then the tiles whose patches can compete anywhere in the
  /// footprint of such a patch (a patch keeps its points by systematic sampling over all the places it owns,
  /// so which of them fall in the box depends on who owns the others); with the patch numbers of the whole
  /// model (TiledModel::patchNumbers), it resamples as the whole model does inside the box.
  /// \param[in]  path        the file
  /// \param[in]  box         the region, in the model's frame
  /// \param[out] bytes_read  if not null: bytes read from the file (header, index and the tiles)
  /// \return the tiles touching the region
  /// \throws pcl_sparse::Error naming the file if it is not a tiled model file or is malformed
  TiledModel
  loadTiledModelRegion (const std::string& path, const Eigen::AlignedBox3d& box, std::uint64_t* bytes_read = nullptr);

  /// \brief Header, index and the tiles' section sizes (summed by tag, after a "TIDX" entry for the header
  /// and index) of the bytes of a tiled file, without decoding patches (inspectModel calls it).
  /// \param[in] data  first byte
  /// \param[in] size  number of bytes
  /// \param[in] name  names the data in error messages
  /// \return what the file holds (num_tiles set; version 3: TIDX the header, index and their checksums, the
  ///         shared QUAN / ACHN, the tiles' sections summed by tag, and TILE the tiles' own framing: their
  ///         section sizes and checksums; the sizes add up to the file's)
  ModelFileInfo
  inspectTiledModel (const std::uint8_t* data, std::size_t size, const std::string& name = "model");

  /// \brief loadTiledModelRegion for several regions at once: the tiles reaching into any of \a boxes.
  /// \param[in]  path        the file
  /// \param[in]  boxes       the regions, in the model's frame
  /// \param[out] bytes_read  if not null: bytes read from the file
  /// \return the tiles touching the regions
  TiledModel
  loadTiledModelRegions (const std::string& path, const std::vector<Eigen::AlignedBox3d>& boxes,
                         std::uint64_t* bytes_read = nullptr);

  /// \brief Loads a tiled file whole (a version-1 file: one tile covering everything).
  /// \param[in] path the file
  /// \return the tiled model
  TiledModel
  loadTiledModel (const std::string& path);
} // namespace pcl_sparse
