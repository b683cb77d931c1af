#include <pcl_sparse/format/tiled_model_file.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/crc32.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    // ---- constants of format version 2 (docs/FORMAT.md, "Tiled files") --------------------------------
    constexpr std::uint8_t kMagic[8] = {0x89, 'P', 'S', 'M', '\r', '\n', 0x1a, '\n'};
    constexpr std::uint16_t kTiledVersion = 2;
    constexpr std::size_t kHeaderBytes = 104;
    constexpr std::size_t kEntryBytes = 88;
    constexpr std::uint64_t kMaxTiles = 1u << 30;
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    constexpr bool kVerifyChecksums = false;  // as in model_file.cpp: let the fuzzer past the CRCs
#else
    constexpr bool kVerifyChecksums = true;
#endif

    /// The tile index of \a tiled with each tile's bytes.
    std::vector<TileIndexEntry>
    indexEntries (const TiledModel& tiled, const std::vector<std::vector<std::uint8_t>>& blobs, double reach_margin)
    {
      std::vector<TileIndexEntry> entries (tiled.tiles.size ());
      std::uint64_t offset = kHeaderBytes + kEntryBytes * entries.size () + 4;
      for (std::size_t i = 0; i < entries.size (); ++i)
      {
        TileIndexEntry& e = entries[i];
        e.tile = tiled.tiles[i].tile;
        e.first_patch = tiled.tiles[i].first_patch;
        e.num_patches = tiled.tiles[i].num_patches;
        e.offset = offset;
        e.size = blobs[i].size ();
        offset += e.size;
        // The reach of the patches as the reader decodes them, so quantisation is accounted for exactly.
        const SparseSurfaceModel decoded = decodeModel (blobs[i].data (), blobs[i].size (), "tile");
        for (const PatchCode& patch : decoded.patches)
          e.reach.extend (patchReachBox (patch));
        e.reach.min ().array () -= reach_margin;
        e.reach.max ().array () += reach_margin;
      }
      return entries;
    }

    void
    putHeader (ByteWriter& out, const TiledModelIndex& index)
    {
      out.putBytes (kMagic, sizeof kMagic);
      out.putU16 (kTiledVersion);
      out.putU16 (0);
      out.putU32 (static_cast<std::uint32_t> (index.entries.size ()));
      out.putU64 (index.num_input_vertices);
      out.putF64 (index.bbox_diagonal);
      out.putF64 (index.tolerance);
      for (int a = 0; a < 3; ++a)
        out.putF64 (index.grid.origin[a]);
      out.putF64 (index.grid.edge);
      out.putF64 (index.grid.margin);
      for (int a = 0; a < 3; ++a)
        out.putU32 (static_cast<std::uint32_t> (index.grid.counts[a]));
      out.putU64 (index.total_patches);
      out.putU32 (crc32 (out.bytes ().data (), out.size ()));
      const std::size_t start = out.size ();
      for (const TileIndexEntry& e : index.entries)
      {
        out.putU64 (e.tile);
        out.putU64 (e.first_patch);
        out.putU64 (e.num_patches);
        out.putU64 (e.offset);
        out.putU64 (e.size);
        for (int a = 0; a < 3; ++a)
          out.putF64 (e.reach.min ()[a]);
        for (int a = 0; a < 3; ++a)
          out.putF64 (e.reach.max ()[a]);
      }
      out.putU32 (crc32 (out.bytes ().data () + start, out.size () - start));
    }

    /// Parses and checks the header (\a data holds at least its bytes); returns the number of entries.
    std::size_t
    readHeader (const std::uint8_t* data, std::size_t size, const std::string& name, TiledModelIndex& index)
    {
      if (!isTiledModelData (data, size))
        throw Error (name + ": not a tiled pcl_sparse model file (magic bytes and version 2)");
      ByteReader in (data, size, name);
      in.getBytes (sizeof kMagic, "magic");
      in.getU16 ("version");
      const std::uint16_t flags = in.getU16 ("flags");
      const std::uint32_t entries = in.getU32 ("number of tiles");
      index.num_input_vertices = in.getU64 ("number of input vertices");
      index.bbox_diagonal = in.getF64 ("bbox diagonal");
      index.tolerance = in.getF64 ("tolerance");
      for (int a = 0; a < 3; ++a)
        index.grid.origin[a] = in.getF64 ("grid origin");
      index.grid.edge = in.getF64 ("tile edge");
      index.grid.margin = in.getF64 ("tile margin");
      for (int a = 0; a < 3; ++a)
        index.grid.counts[a] = static_cast<int> (std::min<std::uint32_t> (in.getU32 ("tile counts"), 1u << 30));
      index.total_patches = in.getU64 ("number of patches");
      const std::uint32_t crc = in.getU32 ("header checksum");
      if (kVerifyChecksums && crc32 (data, kHeaderBytes - 4) != crc)
        throw Error (name + ": tiled model file (version 2): header checksum mismatch (corrupt file)");
      if (flags != 0)
        throw Error (name + ": unknown header flags");
      if (!index.grid.origin.allFinite () || !(index.grid.edge > 0.0) || !std::isfinite (index.grid.edge) ||
          !(index.grid.margin >= 0.0) || !std::isfinite (index.grid.margin) || index.grid.counts.minCoeff () < 1 ||
          static_cast<std::uint64_t> (index.grid.size ()) > kMaxTiles || entries > index.grid.size ())
        throw Error (name + ": tile grid out of range");
      if (!std::isfinite (index.bbox_diagonal) || index.bbox_diagonal < 0.0 || !std::isfinite (index.tolerance) ||
          index.tolerance < 0.0)
        throw Error (name + ": bbox diagonal or tolerance out of range");
      return entries;
    }

    /// Parses and checks the index (\a data: its bytes and checksum) against a file of \a file_size bytes.
    void
    readEntries (const std::uint8_t* data, std::size_t count, std::uint64_t file_size, const std::string& name,
                 TiledModelIndex& index)
    {
      const std::size_t bytes = count * kEntryBytes;
      ByteReader in (data, bytes + 4, name + ": tile index");
      std::uint64_t offset = kHeaderBytes + bytes + 4, patches = 0;
      index.entries.resize (count);
      for (std::size_t i = 0; i < count; ++i)
      {
        TileIndexEntry& e = index.entries[i];
        e.tile = in.getU64 ("tile");
        e.first_patch = in.getU64 ("first patch");
        e.num_patches = in.getU64 ("number of patches");
        e.offset = in.getU64 ("offset");
        e.size = in.getU64 ("size");
        Eigen::Vector3d lo, hi;
        for (int a = 0; a < 3; ++a)
          lo[a] = in.getF64 ("reach");
        for (int a = 0; a < 3; ++a)
          hi[a] = in.getF64 ("reach");
        e.reach = Eigen::AlignedBox3d (lo, hi);
        if (e.tile >= index.grid.size () || (i > 0 && e.tile <= index.entries[i - 1].tile))
          throw Error (name + ": tile index entry " + std::to_string (i) + ": tile number out of order or range");
        if (e.first_patch != patches || e.num_patches > index.total_patches - patches)
          throw Error (name + ": tile index entry " + std::to_string (i) + ": patch range does not follow the last");
        if (e.offset != offset || e.size > file_size - std::min (file_size, offset) || e.size == 0)
          throw Error (name + ": tile index entry " + std::to_string (i) + ": byte range out of the file or out of order");
        if (!lo.allFinite () || !hi.allFinite ())
          throw Error (name + ": tile index entry " + std::to_string (i) + ": reach box not finite");
        patches += e.num_patches;
        offset += e.size;
      }
      const std::uint32_t crc = in.getU32 ("index checksum");
      if (kVerifyChecksums && crc32 (data, bytes) != crc)
        throw Error (name + ": tile index checksum mismatch (corrupt file)");
      if (patches != index.total_patches || offset != file_size)
        throw Error (name + ": the tiles do not add up to the header's patches and the file's size");
    }

    /// Decodes the tiles \a selected of \a index (their bytes from \a read) into one model.
    template <typename Read>
    TiledModel
    decodeTiles (const TiledModelIndex& index, const std::vector<std::size_t>& selected, const std::string& name, Read read)
    {
      TiledModel tiled;
      tiled.grid = index.grid;
      tiled.total_patches = index.total_patches;
      tiled.model.num_input_vertices = index.num_input_vertices;
      tiled.model.bbox_diagonal = index.bbox_diagonal;
      for (std::size_t i : selected)
      {
        const TileIndexEntry& e = index.entries[i];
        const std::string what = name + ": tile " + std::to_string (e.tile);
        std::vector<std::uint8_t> storage;
        const std::uint8_t* bytes = read (e, storage);
        SparseSurfaceModel tile = decodeModel (bytes, e.size, what);
        if (tile.patches.size () != e.num_patches || tile.num_input_vertices != index.num_input_vertices ||
            tile.bbox_diagonal != index.bbox_diagonal)
          throw Error (what + ": its model does not match the tile index");
        if (!tiled.model.basis)
        {
          tiled.model.basis = tile.basis;
          tiled.model.attribute_channels = tile.attribute_channels;
          tiled.model.attribute_basis = tile.attribute_basis;
        }
        tiled.tiles.push_back ({e.tile, e.first_patch, e.num_patches});
        for (PatchCode& patch : tile.patches)
          tiled.model.patches.push_back (std::move (patch));
      }
      return tiled;
    }

    /// Reads \a size bytes at \a offset of \a in.
    void
    readAt (std::ifstream& in, std::uint64_t offset, std::size_t size, std::uint8_t* into, const std::string& name)
    {
      in.seekg (static_cast<std::streamoff> (offset));
      if (!in.read (reinterpret_cast<char*> (into), static_cast<std::streamsize> (size)))
        throw Error (name + ": cannot read the model file (truncated?)");
    }

    /// Opens \a path and reads its index; \a file_size receives its size.
    TiledModelIndex
    openIndex (const std::string& path, std::ifstream& in, std::uint64_t& file_size)
    {
      std::error_code error;
      if (!std::filesystem::is_regular_file (path, error))
        throw Error (path + ": no such model file (or not a regular file)");
      file_size = std::filesystem::file_size (path, error);
      in.open (path, std::ios::binary);
      if (!in || error)
        throw Error (path + ": cannot open model file");
      TiledModelIndex index;
      std::vector<std::uint8_t> header (kHeaderBytes);
      if (file_size < kHeaderBytes)
        throw Error (path + ": tiled model file (version 2) too short for its header and index");
      readAt (in, 0, kHeaderBytes, header.data (), path);
      const std::size_t count = readHeader (header.data (), header.size (), path, index);
      const std::uint64_t index_end = kHeaderBytes + static_cast<std::uint64_t> (count) * kEntryBytes + 4;
      if (index_end > file_size)
        throw Error (path + ": the tile index runs past the end of the file");
      std::vector<std::uint8_t> entries (index_end - kHeaderBytes);
      readAt (in, kHeaderBytes, entries.size (), entries.data (), path);
      readEntries (entries.data (), count, file_size, path, index);
      index.index_bytes = index_end;
      return index;
    }

    /// The header and tile index of a tiled model file held in memory (\a size bytes at \a data).
    TiledModelIndex
    indexInMemory (const std::uint8_t* data, std::size_t size, const std::string& name)
    {
      TiledModelIndex index;
      if (size < kHeaderBytes + 4)
        throw Error (name + ": tiled model file (version 2) too short for its header and index");
      const std::size_t count = readHeader (data, kHeaderBytes, name, index);
      if ((size - kHeaderBytes - 4) / kEntryBytes < count)
        throw Error (name + ": the tile index runs past the end of the file");
      readEntries (data + kHeaderBytes, count, size, name, index);
      return index;
    }
  } // namespace

  bool
  isTiledModelData (const std::uint8_t* data, std::size_t size)
  {
    return size >= 10 && std::memcmp (data, kMagic, sizeof kMagic) == 0 && data[8] == (kTiledVersion & 0xff) &&
           data[9] == (kTiledVersion >> 8);
  }

  std::vector<std::uint8_t>
  encodeTiledModel (const TiledModel& tiled, const ModelWriteOptions& options, int num_threads)
  {
    std::size_t next = 0;
    for (const TileRange& range : tiled.tiles)
    {
      if (range.first_patch != next || range.num_patches == 0 || range.tile >= tiled.grid.size ())
        throw Error ("encodeTiledModel: tile ranges must follow each other, hold patches and lie in the grid");
      next += range.num_patches;
    }
    if (next != tiled.model.patches.size ())
      throw Error ("encodeTiledModel: the tile ranges do not cover the model's patches");
    const long count = static_cast<long> (tiled.tiles.size ());
    std::vector<std::vector<std::uint8_t>> blobs (tiled.tiles.size ());
    std::vector<std::string> errors (tiled.tiles.size ());
#ifdef _OPENMP
    const int threads = num_threads > 0 ? num_threads : omp_get_max_threads ();
#else
    const int threads = 1;
    (void) num_threads;
#endif
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long i = 0; i < count; ++i)
    {
      try
      {
        const TileRange& range = tiled.tiles[i];
        blobs[i] = encodeModel (subModel (tiled.model, range.first_patch, range.num_patches), options);
      }
      catch (const std::exception& e)
      {
        errors[i] = e.what ();
      }
    }
    for (const std::string& e : errors)
      if (!e.empty ())
        throw Error (e);
    TiledModelIndex index;
    index.grid = tiled.grid;
    index.num_input_vertices = tiled.model.num_input_vertices;
    index.bbox_diagonal = tiled.model.bbox_diagonal;
    index.tolerance = options.tolerance;
    index.total_patches = tiled.model.patches.size ();
    index.entries = indexEntries (tiled, blobs, options.tolerance * tiled.model.bbox_diagonal);
    ByteWriter out;
    putHeader (out, index);
    for (const std::vector<std::uint8_t>& blob : blobs)
      out.putBytes (blob.data (), blob.size ());
    return std::move (out.bytes ());
  }

  void
  saveTiledModel (const std::string& path, const TiledModel& tiled, const ModelWriteOptions& options, int num_threads)
  {
    const std::vector<std::uint8_t> bytes = encodeTiledModel (tiled, options, num_threads);
    writeBytesAtomically (path, bytes.data (), bytes.size ());
  }

  TiledModel
  decodeTiledModel (const std::uint8_t* data, std::size_t size, const std::string& name)
  {
    const TiledModelIndex index = indexInMemory (data, size, name);
    std::vector<std::size_t> all (index.entries.size ());
    std::iota (all.begin (), all.end (), std::size_t (0));
    return decodeTiles (index, all, name, [&] (const TileIndexEntry& e, std::vector<std::uint8_t>&) { return data + e.offset; });
  }

  TiledModelIndex
  readTiledModelIndex (const std::string& path)
  {
    std::ifstream in;
    std::uint64_t file_size = 0;
    return openIndex (path, in, file_size);
  }

  TiledModel
  loadTiledModelRegion (const std::string& path, const Eigen::AlignedBox3d& box, std::uint64_t* bytes_read)
  {
    return loadTiledModelRegions (path, {box}, bytes_read);
  }

  TiledModel
  loadTiledModelRegions (const std::string& path, const std::vector<Eigen::AlignedBox3d>& boxes, std::uint64_t* bytes_read)
  {
    std::ifstream in;
    std::uint64_t file_size = 0;
    const TiledModelIndex index = openIndex (path, in, file_size);
    std::vector<std::size_t> selected;
    std::uint64_t bytes = index.index_bytes;
    for (std::size_t i = 0; i < index.entries.size (); ++i)
      if (std::any_of (boxes.begin (), boxes.end (), [&] (const Eigen::AlignedBox3d& box) { return index.entries[i].reach.intersects (box); }))
      {
        selected.push_back (i);
        bytes += index.entries[i].size;
      }
    if (bytes_read)
      *bytes_read = bytes;
    return decodeTiles (index, selected, path, [&] (const TileIndexEntry& e, std::vector<std::uint8_t>& storage) {
      storage.resize (e.size);
      readAt (in, e.offset, e.size, storage.data (), path);
      return static_cast<const std::uint8_t*> (storage.data ());
    });
  }

  bool
  isTiledModelFile (const std::string& path)
  {
    std::ifstream probe (path, std::ios::binary);
    std::uint8_t head[10] = {};
    return probe.read (reinterpret_cast<char*> (head), sizeof head) && isTiledModelData (head, sizeof head);
  }

  TiledModel
  loadTiledModel (const std::string& path)
  {
    const Eigen::Vector3d inf = Eigen::Vector3d::Constant (std::numeric_limits<double>::infinity ());
    if (isTiledModelFile (path))
      return loadTiledModelRegion (path, Eigen::AlignedBox3d (-inf, inf));
    TiledModel tiled;
    tiled.model = loadModel (path);
    Eigen::AlignedBox3d box;
    for (const PatchCode& patch : tiled.model.patches)
      box.extend (patch.origin);
    if (box.isEmpty ())
      box = Eigen::AlignedBox3d (Eigen::Vector3d::Zero (), Eigen::Vector3d::Zero ());
    tiled.grid = makeTileGrid (box, 1, TileGridOptions ());
    tiled.total_patches = tiled.model.patches.size ();
    if (tiled.total_patches > 0)
      tiled.tiles.push_back ({0, 0, tiled.total_patches});
    return tiled;
  }
} // namespace pcl_sparse

namespace pcl_sparse
{
  ModelFileInfo
  inspectTiledModel (const std::uint8_t* data, std::size_t size, const std::string& name)
  {
    const TiledModelIndex index = indexInMemory (data, size, name);
    ModelFileInfo info;
    info.version = kTiledVersion;
    info.num_patches = static_cast<std::uint32_t> (std::min<std::size_t> (index.total_patches, 0xffffffffu));
    info.num_input_vertices = index.num_input_vertices;
    info.bbox_diagonal = index.bbox_diagonal;
    info.tolerance = index.tolerance;
    info.quantised = index.tolerance > 0.0;
    info.file_bytes = size;
    const std::size_t count = index.entries.size ();
    info.num_tiles = count;
    const std::uint64_t index_bytes = kHeaderBytes + kEntryBytes * count + 4;
    info.sections.push_back ({"TIDX", index_bytes, index_bytes});
    // The tiles' sections, summed by tag; the basis and flags of the first tile.
    for (std::size_t i = 0; i < count; ++i)
    {
      const TileIndexEntry& e = index.entries[i];
      const ModelFileInfo tile = inspectModel (data + e.offset, e.size, name + ": tile " + std::to_string (e.tile));
      if (i == 0)
      {
        info.basis = tile.basis;
        info.has_vertices = tile.has_vertices;
        info.attributes = tile.attributes;
      }
      for (const ModelFileSection& s : tile.sections)
      {
        auto it = std::find_if (info.sections.begin (), info.sections.end (),
                                [&] (const ModelFileSection& t) { return t.tag == s.tag; });
        if (it == info.sections.end ())
          info.sections.push_back (s);
        else
        {
          it->stored_bytes += s.stored_bytes;
          it->raw_bytes += s.raw_bytes;
        }
      }
    }
    return info;
  }
} // namespace pcl_sparse
