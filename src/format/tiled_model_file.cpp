#include <pcl_sparse/format/tiled_model_file.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/format/attribute_sections.h>
#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/crc32.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/format/zstd_codec.h>

#include <algorithm>
#include <array>
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
    // ---- constants of the tiled formats, versions 3 and 2 (docs/FORMAT.md, "Tiled files") -------------
    constexpr std::uint8_t kMagic[8] = {0x89, 'P', 'S', 'M', '\r', '\n', 0x1a, '\n'};
    constexpr std::uint16_t kTiledVersion = 3;      ///< lean tiles: shared sections once, a tile one zstd frame
    constexpr std::uint16_t kTiledVersion2 = 2;     ///< older layout: every tile a complete version-1 model (read only)
    constexpr std::size_t kHeaderBytes = 116;
    constexpr std::size_t kHeaderBytes2 = 104;
    constexpr std::size_t kEntryBytes2 = 88;
    constexpr std::uint8_t kCodecStored = 0;
    constexpr std::uint8_t kCodecZstd = 1;
    constexpr double kReachSteps = 64.0;            ///< reach boxes are stored in steps of edge / 64
    // As version 1's sections: a tile may decompress to at most 64 x its stored bytes + 4 KiB.
    constexpr std::uint64_t kMaxExpansion = 64;
    constexpr std::uint64_t kExpansionSlack = 4096;
    constexpr std::uint64_t kMaxTiles = 1u << 30;
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    constexpr bool kVerifyChecksums = false;  // as in model_file.cpp: let the fuzzer past the CRCs
#else
    constexpr bool kVerifyChecksums = true;
#endif

    // ---- version 3 --------------------------------------------------------------------------------

    /// One bound of a reach box from its step count: the grid's core box side plus steps of edge / 64.
    double
    reachBound (double side, std::int64_t steps, double edge)
    {
      return side + static_cast<double> (steps) * (edge / kReachSteps);
    }

    /// Steps that round \a box outward from the core box \a core (one extra step, so that no rounding of
    /// the decoder's arithmetic can make the stored box smaller than \a box).
    std::array<std::int64_t, 6>
    reachSteps (const Eigen::AlignedBox3d& box, const Eigen::AlignedBox3d& core, double edge)
    {
      std::array<std::int64_t, 6> steps;
      const double unit = edge / kReachSteps;
      for (int a = 0; a < 3; ++a)
      {
        const double lo = std::floor ((box.min ()[a] - core.min ()[a]) / unit) - 1.0;
        const double hi = std::ceil ((box.max ()[a] - core.max ()[a]) / unit) + 1.0;
        if (!(std::abs (lo) < 4e18) || !(std::abs (hi) < 4e18))
          throw Error ("encodeTiledModel: a tile's reach box is not finite or far outside its tile");
        steps[a] = static_cast<std::int64_t> (lo);
        steps[3 + a] = static_cast<std::int64_t> (hi);
        while (reachBound (core.min ()[a], steps[a], edge) > box.min ()[a])
          --steps[a];
        while (reachBound (core.max ()[a], steps[3 + a], edge) < box.max ()[a])
          ++steps[3 + a];
      }
      return steps;
    }

    /// A tile's stored bytes (its CRC-32 follows them): per section a varint 2 S + codec (S its stored bytes;
    /// codec 1: a zstd frame, 0: the payload itself, where zstd would not make it smaller), then the sections.
    std::vector<std::uint8_t>
    encodeTile (const std::vector<std::vector<std::uint8_t>>& sections, const ModelWriteOptions& options)
    {
      ByteWriter out;
      std::vector<std::vector<std::uint8_t>> payloads;
      for (const std::vector<std::uint8_t>& section : sections)
      {
        std::vector<std::uint8_t> payload;
        std::uint8_t codec = kCodecStored;
        const int level = zstdLevelFor (section.size (), options);
        if (level > 0 && !section.empty ())
        {
          payload = compressBytes (section.data (), section.size (), level);
          // Stored where zstd does not help, or where the ratio exceeds what the reader accepts.
          if (payload.size () < section.size () && section.size () <= kMaxExpansion * payload.size () + kExpansionSlack)
            codec = kCodecZstd;
        }
        if (codec == kCodecStored)
          payload = section;
        out.putVarint (2 * payload.size () + codec);
        payloads.push_back (std::move (payload));
      }
      for (const std::vector<std::uint8_t>& payload : payloads)
        out.putBytes (payload.data (), payload.size ());
      return std::move (out.bytes ());
    }

    /// One section of a tile as stored.
    struct TileSection
    {
      const std::uint8_t* payload = nullptr;
      std::size_t stored = 0;
      std::uint64_t raw = 0;
      bool zstd = false;
    };

    /// The sections of a tile from its stored bytes (\a bytes, \a size: without the CRC-32), with their
    /// raw sizes (from the zstd frame headers, checked against the expansion bound), not decompressed.
    std::vector<TileSection>
    tileSectionTable (const std::uint8_t* bytes, std::size_t size, const std::vector<std::string>& tags, const std::string& what)
    {
      ByteReader in (bytes, size, what);
      std::vector<TileSection> sections (tags.size ());
      for (TileSection& section : sections)
      {
        const std::uint64_t head = in.getVarint ("section size");
        if ((head >> 1) > in.remaining ())
          in.fail ("section size runs past the tile");
        section.stored = static_cast<std::size_t> (head >> 1);
        section.zstd = (head & 1) == kCodecZstd;
      }
      for (std::size_t i = 0; i < tags.size (); ++i)
      {
        TileSection& section = sections[i];
        section.payload = in.getBytes (section.stored, "section");
        section.raw = section.stored;
        if (!section.zstd)
          continue;
        const std::string name = what + ": section " + tags[i];
        section.raw = zstdFrameContentSize (section.payload, section.stored, name);
        if (section.raw > kMaxExpansion * section.stored + kExpansionSlack)
          throw Error (name + ": claims " + std::to_string (section.raw) + " decompressed bytes, more than its " +
                       std::to_string (section.stored) + " stored bytes can justify");
      }
      in.expectEnd ();
      return sections;
    }

    /// The sections of a tile from its stored bytes (\a bytes, \a size: without the CRC-32), decompressed.
    std::vector<std::vector<std::uint8_t>>
    decodeTileSections (const std::uint8_t* bytes, std::size_t size, const std::vector<std::string>& tags,
                        const std::string& what)
    {
      const std::vector<TileSection> table = tileSectionTable (bytes, size, tags, what);
      std::vector<std::vector<std::uint8_t>> sections (tags.size ());
      for (std::size_t i = 0; i < tags.size (); ++i)
        if (table[i].zstd)
          sections[i] = decompressBytes (table[i].payload, table[i].stored, static_cast<std::size_t> (table[i].raw),
                                         what + ": section " + tags[i]);
        else
          sections[i].assign (table[i].payload, table[i].payload + table[i].stored);
      return sections;
    }

    /// Checks the CRC-32 of a tile's bytes in the file; returns its stored bytes (without the CRC).
    std::size_t
    checkTile (const TileIndexEntry& e, const std::uint8_t* bytes, const std::string& what)
    {
      const std::size_t stored = static_cast<std::size_t> (e.size - 4);
      ByteReader crc_reader (bytes + stored, 4, what);
      if (kVerifyChecksums && crc32 (bytes, stored) != crc_reader.getU32 ("tile checksum"))
        throw Error (what + ": checksum mismatch (corrupt file)");
      return stored;
    }

    /// Pointers to \a sections, as decodeModelSections takes them.
    std::vector<std::pair<const std::uint8_t*, std::size_t>>
    spans (const std::vector<std::vector<std::uint8_t>>& sections)
    {
      std::vector<std::pair<const std::uint8_t*, std::size_t>> out;
      for (const std::vector<std::uint8_t>& section : sections)
        out.emplace_back (section.data (), section.size ());
      return out;
    }

    /// A tile's patches from its bytes in the file.
    SparseSurfaceModel
    decodeTile (const TiledModelIndex& index, const TileIndexEntry& e, const std::uint8_t* bytes, const std::string& what)
    {
      const std::vector<std::vector<std::uint8_t>> sections =
        decodeTileSections (bytes, checkTile (e, bytes, what), runSectionTags (index.shared.flags), what);
      return decodeModelSections (index.shared, e.num_patches, spans (sections), what);
    }

    /// The header, shared sections and index of version 3 (docs/FORMAT.md).
    void
    putHeader (ByteWriter& out, const TiledModelIndex& index)
    {
      const SharedModelFields& shared = index.shared;
      ByteWriter body;
      body.putBytes (shared.quantisation.data (), shared.quantisation.size ());
      body.putBytes (shared.channels.data (), shared.channels.size ());
      const std::size_t shared_bytes = body.size ();
      std::size_t previous = 0;
      for (std::size_t i = 0; i < index.entries.size (); ++i)
      {
        const TileIndexEntry& e = index.entries[i];
        body.putVarint (i == 0 ? e.tile : e.tile - previous - 1);
        previous = e.tile;
        body.putVarint (e.num_patches);
        body.putVarint (e.size - 4);
        for (std::int64_t v : reachSteps (e.reach, index.grid.coreBox (e.tile), index.grid.edge))
          body.putSignedVarint (v);
      }
      out.putBytes (kMagic, sizeof kMagic);
      out.putU16 (kTiledVersion);
      out.putU16 (shared.flags);
      out.putU8 (shared.basis_kind);
      out.putU8 (0);
      out.putU16 (shared.basis_parameter);
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
      out.putU32 (static_cast<std::uint32_t> (shared_bytes));
      out.putU32 (static_cast<std::uint32_t> (body.size () - shared_bytes));
      out.putU32 (crc32 (out.bytes ().data (), out.size ()));
      out.putBytes (body.bytes ().data (), body.size ());
      out.putU32 (crc32 (body.bytes ().data (), body.size ()));
    }

    /// Checks the grid, diagonal and tolerance of a header.
    void
    checkGrid (const TiledModelIndex& index, std::uint64_t entries, const std::string& name)
    {
      if (!index.grid.origin.allFinite () || !(index.grid.edge > 0.0) || !std::isfinite (index.grid.edge) ||
          !(index.grid.margin >= 0.0) || !std::isfinite (index.grid.margin) || index.grid.counts.minCoeff () < 1 ||
          index.grid.counts.cast<double> ().prod () > static_cast<double> (kMaxTiles) ||  // size () could wrap
          entries > index.grid.size ())
        throw Error (name + ": tile grid out of range");
      if (!std::isfinite (index.bbox_diagonal) || index.bbox_diagonal < 0.0 || !std::isfinite (index.tolerance) ||
          index.tolerance < 0.0)
        throw Error (name + ": bbox diagonal or tolerance out of range");
    }

    /// Reads the fields both header layouts hold in this order after the number of tiles: input vertices,
    /// bbox diagonal, tolerance, the grid (origin, edge, margin, counts) and the number of patches.
    void
    getModelAndGrid (ByteReader& in, TiledModelIndex& index)
    {
      index.num_input_vertices = in.getU64 ("number of input vertices");
      index.bbox_diagonal = in.getF64 ("bbox diagonal");
      index.tolerance = in.getF64 ("tolerance");
      for (int a = 0; a < 3; ++a)
        index.grid.origin[a] = in.getF64 ("grid origin");
      index.grid.edge = in.getF64 ("tile edge");
      index.grid.margin = in.getF64 ("tile margin");
      for (int a = 0; a < 3; ++a)
      {
        const std::uint32_t count = in.getU32 ("tile counts");
        index.grid.counts[a] = count > kMaxTiles ? 0 : static_cast<int> (count);  // 0: checkGrid refuses it
      }
      index.total_patches = in.getU64 ("number of patches");
    }

    /// Version 3: parses and checks the fixed header (\a data holds its kHeaderBytes); returns the number of
    /// entries and the bytes of the shared sections and of the index.
    std::size_t
    readHeader (const std::uint8_t* data, const std::string& name, TiledModelIndex& index, std::uint64_t& shared_bytes,
                std::uint64_t& entry_bytes)
    {
      ByteReader in (data, kHeaderBytes, name);
      in.getBytes (sizeof kMagic, "magic");
      index.version = in.getU16 ("version");
      SharedModelFields& shared = index.shared;
      shared.flags = in.getU16 ("flags");
      shared.basis_kind = in.getU8 ("basis kind");
      const std::uint8_t reserved = in.getU8 ("reserved");
      shared.basis_parameter = in.getU16 ("basis parameter");
      const std::uint32_t entries = in.getU32 ("number of tiles");
      getModelAndGrid (in, index);
      shared_bytes = in.getU32 ("shared section bytes");
      entry_bytes = in.getU32 ("tile index bytes");
      const std::uint32_t crc = in.getU32 ("header checksum");
      if (kVerifyChecksums && crc32 (data, kHeaderBytes - 4) != crc)
        throw Error (name + ": tiled model file (version 3): header checksum mismatch (corrupt file)");
      if (reserved != 0 || (shared.flags & ~header_flag::known) != 0)
        throw Error (name + ": unknown header flags");
      checkGrid (index, entries, name);
      shared.num_input_vertices = index.num_input_vertices;
      shared.bbox_diagonal = index.bbox_diagonal;
      shared.tolerance = index.tolerance;
      // Every entry takes at least 9 bytes (3 varints and 6 svarints, a byte each).
      if (entry_bytes < 9u * static_cast<std::uint64_t> (entries) || (entries == 0) != (index.total_patches == 0))
        throw Error (name + ": the tile index's size does not fit its tiles");
      return entries;
    }

    /// Version 3: parses and checks the shared sections and the index (\a data: their bytes and checksum,
    /// \a shared_bytes + \a entry_bytes + 4) against a file of \a file_size bytes.
    void
    readBody (const std::uint8_t* data, std::size_t count, std::uint64_t shared_bytes, std::uint64_t entry_bytes,
              std::uint64_t file_size, const std::string& name, TiledModelIndex& index)
    {
      const std::size_t body = static_cast<std::size_t> (shared_bytes + entry_bytes);
      ByteReader crc_reader (data + body, 4, name);
      if (kVerifyChecksums && crc32 (data, body) != crc_reader.getU32 ("index checksum"))
        throw Error (name + ": tile index checksum mismatch (corrupt file)");
      SharedModelFields& shared = index.shared;
      const bool quantised = shared.flags & header_flag::quantised;
      const std::size_t quan_bytes = quantised ? 75 : 0;
      if (shared_bytes < quan_bytes || (shared_bytes > quan_bytes) != static_cast<bool> (shared.flags & header_flag::attributes))
        throw Error (name + ": shared sections of " + std::to_string (shared_bytes) + " bytes do not match the flags");
      shared.quantisation.assign (data, data + quan_bytes);
      shared.channels.assign (data + quan_bytes, data + shared_bytes);
      checkSharedModelFields (shared, name);
      ByteReader in (data + shared_bytes, static_cast<std::size_t> (entry_bytes), name + ": tile index");
      std::uint64_t offset = index.index_bytes, patches = 0;
      index.entries.resize (count);
      for (std::size_t i = 0; i < count; ++i)
      {
        TileIndexEntry& e = index.entries[i];
        const std::string what = name + ": tile index entry " + std::to_string (i);
        const std::uint64_t step = in.getVarint ("tile");
        const std::uint64_t tile = i == 0 ? step : index.entries[i - 1].tile + 1 + step;
        if (step >= index.grid.size () || tile >= index.grid.size ())
          throw Error (what + ": tile number out of order or range");
        e.tile = static_cast<std::size_t> (tile);
        e.first_patch = patches;
        const std::uint64_t num_patches = in.getVarint ("number of patches");
        if (num_patches == 0 || num_patches > index.total_patches - patches)
          throw Error (what + ": patch count out of range");
        e.num_patches = static_cast<std::size_t> (num_patches);
        const std::uint64_t stored = in.getVarint ("size");
        e.offset = offset;
        if (stored == 0 || stored > file_size - std::min (file_size, offset + 4))
          throw Error (what + ": byte range out of the file");
        e.size = stored + 4;
        Eigen::Vector3d lo, hi;
        const Eigen::AlignedBox3d core = index.grid.coreBox (e.tile);
        for (int a = 0; a < 3; ++a)
          lo[a] = reachBound (core.min ()[a], in.getSignedVarint ("reach"), index.grid.edge);
        for (int a = 0; a < 3; ++a)
          hi[a] = reachBound (core.max ()[a], in.getSignedVarint ("reach"), index.grid.edge);
        if (!lo.allFinite () || !hi.allFinite ())
          throw Error (what + ": reach box not finite");
        e.reach = Eigen::AlignedBox3d (lo, hi);
        patches += e.num_patches;
        offset += e.size;
      }
      in.expectEnd ();
      if (patches != index.total_patches || offset != file_size)
        throw Error (name + ": the tiles do not add up to the header's patches and the file's size");
    }

    // ---- version 2 (read only) ----------------------------------------------------------------------

    /// A version-2 tile is a complete version-1 file. A tiled file in its place is refused: decoding it would
    /// read tiled files inside tiled files without end, each level a few hundred bytes, until the stack ran out.
    const std::uint8_t*
    version2Tile (const std::uint8_t* bytes, std::size_t size, const std::string& what)
    {
      if (isTiledModelData (bytes, size))
        throw Error (what + ": a tile of a version-2 file is itself a tiled file (corrupt file)");
      return bytes;
    }

    /// Version 2: parses and checks the header (\a data holds at least its bytes); returns the number of entries.
    std::size_t
    readHeader2 (const std::uint8_t* data, const std::string& name, TiledModelIndex& index)
    {
      ByteReader in (data, kHeaderBytes2, name);
      in.getBytes (sizeof kMagic, "magic");
      index.version = in.getU16 ("version");
      const std::uint16_t flags = in.getU16 ("flags");
      const std::uint32_t entries = in.getU32 ("number of tiles");
      getModelAndGrid (in, index);
      const std::uint32_t crc = in.getU32 ("header checksum");
      if (kVerifyChecksums && crc32 (data, kHeaderBytes2 - 4) != crc)
        throw Error (name + ": tiled model file (version 2): header checksum mismatch (corrupt file)");
      if (flags != 0)
        throw Error (name + ": unknown header flags");
      checkGrid (index, entries, name);
      return entries;
    }

    /// Version 2: parses and checks the index (\a data: its bytes and checksum) against a file of \a file_size bytes.
    void
    readEntries2 (const std::uint8_t* data, std::size_t count, std::uint64_t file_size, const std::string& name,
                  TiledModelIndex& index)
    {
      const std::size_t bytes = count * kEntryBytes2;
      ByteReader in (data, bytes + 4, name + ": tile index");
      std::uint64_t offset = kHeaderBytes2 + bytes + 4, patches = 0;
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

    // ---- both -----------------------------------------------------------------------------------------

    /// Version of the tiled file starting with \a data (at least 10 bytes), 0 if it is none.
    std::uint16_t
    tiledVersion (const std::uint8_t* data, std::size_t size)
    {
      if (size < 10 || std::memcmp (data, kMagic, sizeof kMagic) != 0)
        return 0;
      const std::uint16_t version = static_cast<std::uint16_t> (data[8] | (data[9] << 8));
      return version == kTiledVersion || version == kTiledVersion2 ? version : 0;
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
        SparseSurfaceModel tile =
          index.version == kTiledVersion ? decodeTile (index, e, bytes, what)
                                          : decodeModel (version2Tile (bytes, e.size, what), e.size, what);
        if (tile.patches.size () != e.num_patches || tile.num_input_vertices != index.num_input_vertices ||
            tile.bbox_diagonal != index.bbox_diagonal)
          throw Error (what + ": its model does not match the tile index");
        if (!tiled.model.basis)
        {
          tiled.model.basis = tile.basis;
          tiled.model.attribute_channels = tile.attribute_channels;
          tiled.model.attribute_basis = tile.attribute_basis;
        }
        tiled.model.footprint_step = std::max (tiled.model.footprint_step, tile.footprint_step);
        tiled.tiles.push_back ({e.tile, e.first_patch, e.num_patches, {}});
        for (PatchCode& patch : tile.patches)
          tiled.model.patches.push_back (std::move (patch));
      }
      if (!tiled.model.basis && index.version == kTiledVersion)
      {
        // No tile read (a model without patches, or a region no tile reaches): the basis and the attribute
        // channels still come from the shared fields, as a version-1 file of no patches gives them.
        static const std::uint8_t none = 0;
        const std::vector<std::pair<const std::uint8_t*, std::size_t>> empty (runSectionTags (index.shared.flags).size (),
                                                                              {&none, 0});
        const SparseSurfaceModel shared = decodeModelSections (index.shared, 0, empty, name);
        tiled.model.basis = shared.basis;
        tiled.model.attribute_channels = shared.attribute_channels;
        tiled.model.attribute_basis = shared.attribute_basis;
      }
      else if (!tiled.model.basis)
      {
        // Version 2 keeps the basis in its tiles only: a region no tile reaches takes it from the first tile,
        // and a file of no tile has none to give (the fuzzer's round trip found such a model, which could
        // not be saved again).
        if (index.entries.empty ())
          throw Error (name + ": tiled model file (version 2) without a tile, hence without a basis");
        std::vector<std::uint8_t> storage;
        const TileIndexEntry& e = index.entries.front ();
        const std::string what = name + ": tile " + std::to_string (e.tile);
        const SparseSurfaceModel first = decodeModel (version2Tile (read (e, storage), e.size, what), e.size, what);
        tiled.model.basis = first.basis;
        tiled.model.attribute_channels = first.attribute_channels;
        tiled.model.attribute_basis = first.attribute_basis;
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

    /// Reads the index of a tiled file through \a read (offset, size, into), which checks the file's size.
    template <typename Read>
    TiledModelIndex
    readIndex (std::uint64_t file_size, const std::string& name, Read read)
    {
      TiledModelIndex index;
      std::uint8_t head[10] = {};
      if (file_size >= sizeof head)
        read (0, sizeof head, head);
      const std::uint16_t version = tiledVersion (head, file_size >= sizeof head ? sizeof head : 0);
      if (version == 0)
        throw Error (name + ": not a tiled pcl_sparse model file (magic bytes and version 2 or 3)");
      const std::size_t header_bytes = version == kTiledVersion ? kHeaderBytes : kHeaderBytes2;
      if (file_size < header_bytes + 4)
        throw Error (name + ": tiled model file (version " + std::to_string (version) + ") too short for its header and index");
      std::vector<std::uint8_t> header (header_bytes);
      read (0, header_bytes, header.data ());
      if (version == kTiledVersion)
      {
        std::uint64_t shared_bytes = 0, entry_bytes = 0;
        const std::size_t count = readHeader (header.data (), name, index, shared_bytes, entry_bytes);
        index.index_bytes = kHeaderBytes + shared_bytes + entry_bytes + 4;
        if (index.index_bytes > file_size)
          throw Error (name + ": the tile index runs past the end of the file");
        std::vector<std::uint8_t> body (static_cast<std::size_t> (index.index_bytes - kHeaderBytes));
        read (kHeaderBytes, body.size (), body.data ());
        readBody (body.data (), count, shared_bytes, entry_bytes, file_size, name, index);
      }
      else
      {
        const std::size_t count = readHeader2 (header.data (), name, index);
        if ((file_size - kHeaderBytes2 - 4) / kEntryBytes2 < count)
          throw Error (name + ": the tile index runs past the end of the file");
        index.index_bytes = kHeaderBytes2 + static_cast<std::uint64_t> (count) * kEntryBytes2 + 4;
        std::vector<std::uint8_t> entries (static_cast<std::size_t> (index.index_bytes - kHeaderBytes2));
        read (kHeaderBytes2, entries.size (), entries.data ());
        readEntries2 (entries.data (), count, file_size, name, index);
      }
      return index;
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
      return readIndex (file_size, path, [&] (std::uint64_t offset, std::size_t size, std::uint8_t* into) {
        readAt (in, offset, size, into, path);
      });
    }

    /// The header and tile index of a tiled model file held in memory (\a size bytes at \a data).
    TiledModelIndex
    indexInMemory (const std::uint8_t* data, std::size_t size, const std::string& name)
    {
      return readIndex (size, name, [&] (std::uint64_t offset, std::size_t count, std::uint8_t* into) {
        std::memcpy (into, data + offset, count);  // readIndex checked offset + count <= size
      });
    }
  } // namespace

  bool
  isTiledModelData (const std::uint8_t* data, std::size_t size)
  {
    return tiledVersion (data, size) != 0;
  }

  std::vector<std::uint8_t>
  encodeTiledModel (const TiledModel& tiled, const ModelWriteOptions& options, int num_threads)
  {
    std::size_t next = 0;
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (const TileRange& range : tiled.tiles)
    {
      if (range.first_patch != next || range.num_patches == 0 || range.tile >= tiled.grid.size () ||
          (!runs.empty () && range.tile <= tiled.tiles[runs.size () - 1].tile))
        throw Error ("encodeTiledModel: tile ranges must follow each other, hold patches and lie in the grid, in tile order");
      next += range.num_patches;
      runs.emplace_back (range.first_patch, range.num_patches);
    }
    if (next != tiled.model.patches.size ())
      throw Error ("encodeTiledModel: the tile ranges do not cover the model's patches");
    // Quantisation over the whole model: every tile decodes to the patches the untiled file would give.
    const ModelSections sections = encodeModelSections (tiled.model, options, runs);
    TiledModelIndex index;
    index.grid = tiled.grid;
    index.num_input_vertices = tiled.model.num_input_vertices;
    index.bbox_diagonal = tiled.model.bbox_diagonal;
    index.tolerance = options.tolerance;
    index.total_patches = tiled.model.patches.size ();
    index.shared = sections.shared;
    index.entries.resize (tiled.tiles.size ());
    const double reach_margin = options.tolerance * tiled.model.bbox_diagonal;

    const long count = static_cast<long> (tiled.tiles.size ());
    std::vector<std::vector<std::uint8_t>> blobs (tiled.tiles.size ());
    std::vector<std::string> errors (tiled.tiles.size ());
#ifdef _OPENMP
    const int threads = resolveThreadCount (num_threads);
#else
    const int threads = 1;
    (void) num_threads;
#endif
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long i = 0; i < count; ++i)
    {
      try
      {
        TileIndexEntry& e = index.entries[i];
        e.tile = tiled.tiles[i].tile;
        e.first_patch = tiled.tiles[i].first_patch;
        e.num_patches = tiled.tiles[i].num_patches;
        std::vector<std::uint8_t>& blob = blobs[i];
        blob = encodeTile (sections.runs[i], options);
        ByteWriter crc;
        crc.putU32 (crc32 (blob.data (), blob.size ()));
        blob.insert (blob.end (), crc.bytes ().begin (), crc.bytes ().end ());
        e.size = blob.size ();
        // The reach of the patches as the reader decodes them, so quantisation is accounted for exactly.
        const SparseSurfaceModel decoded =
          decodeModelSections (index.shared, e.num_patches, spans (sections.runs[i]), "tile");
        for (const PatchCode& patch : decoded.patches)
          e.reach.extend (patchReachBox (patch, *decoded.basis));
        e.reach.min ().array () -= reach_margin;
        e.reach.max ().array () += reach_margin;
      }
      catch (const std::exception& e)
      {
        errors[i] = e.what ();
      }
    }
    for (const std::string& e : errors)
      if (!e.empty ())
        throw Error (e);
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
    auto meets = [] (const Eigen::AlignedBox3d& reach, const std::vector<Eigen::AlignedBox3d>& regions) {
      return std::any_of (regions.begin (), regions.end (), [&] (const Eigen::AlignedBox3d& r) { return reach.intersects (r); });
    };
    auto read = [&] (const TileIndexEntry& e, std::vector<std::uint8_t>& storage) {
      storage.resize (e.size);
      readAt (in, e.offset, e.size, storage.data (), path);
      return static_cast<const std::uint8_t*> (storage.data ());
    };
    std::uint64_t bytes = index.index_bytes;
    // First the tiles whose patches can place a point in a box or contend for one there.
    std::vector<std::size_t> first;
    std::vector<bool> taken (index.entries.size (), false);
    for (std::size_t i = 0; i < index.entries.size (); ++i)
      if (meets (index.entries[i].reach, boxes))
      {
        first.push_back (i);
        taken[i] = true;
        bytes += index.entries[i].size;
      }
    TiledModel near = decodeTiles (index, first, path, read);
    // Then every tile that can contend anywhere in the footprint of such a patch: a patch keeps its points by
    // systematic sampling over all the cells it owns, so which of them fall in the box depends on who owns
    // its places outside the box too (docs/TILES.md, "Regions").
    std::vector<Eigen::AlignedBox3d> reaches;
    for (const PatchCode& patch : near.model.patches)
    {
      const Eigen::AlignedBox3d reach = patchReachBox (patch, *near.model.basis);
      if (meets (reach, boxes))
        reaches.push_back (reach);
    }
    std::vector<std::size_t> second;
    for (std::size_t i = 0; i < index.entries.size (); ++i)
      if (!taken[i] && meets (index.entries[i].reach, reaches))
      {
        second.push_back (i);
        bytes += index.entries[i].size;
      }
    if (bytes_read)
      *bytes_read = bytes;
    if (second.empty ())
      return near;
    // Merge the two reads in tile order.
    TiledModel far = decodeTiles (index, second, path, read);
    TiledModel merged;
    merged.grid = near.grid;
    merged.total_patches = near.total_patches;
    merged.model = subModel (near.model, 0, 0);
    merged.model.footprint_step = std::max (near.model.footprint_step, far.model.footprint_step);
    merged.model.patches.reserve (near.model.patches.size () + far.model.patches.size ());
    std::size_t a = 0, b = 0, pa = 0, pb = 0;
    while (a < near.tiles.size () || b < far.tiles.size ())
    {
      const bool from_near = b == far.tiles.size () || (a < near.tiles.size () && near.tiles[a].tile < far.tiles[b].tile);
      const TileRange& range = from_near ? near.tiles[a++] : far.tiles[b++];
      std::size_t& at = from_near ? pa : pb;
      std::vector<PatchCode>& source = from_near ? near.model.patches : far.model.patches;
      for (std::size_t k = 0; k < range.num_patches; ++k)
        merged.model.patches.push_back (std::move (source[at++]));
      merged.tiles.push_back (range);
    }
    return merged;
  }

  bool
  isTiledModelFile (const std::string& path)
  {
    // Not a regular file: not a model (opening a FIFO blocked pcl_sparse_decode forever); the loaders say why.
    std::error_code ec;
    if (!std::filesystem::is_regular_file (path, ec))
      return false;
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
      tiled.tiles.push_back ({0, 0, tiled.total_patches, {}});
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
    info.version = index.version;
    info.num_patches = static_cast<std::uint32_t> (std::min<std::size_t> (index.total_patches, 0xffffffffu));
    info.num_input_vertices = index.num_input_vertices;
    info.bbox_diagonal = index.bbox_diagonal;
    info.tolerance = index.tolerance;
    info.quantised = index.tolerance > 0.0;
    info.range_coded = index.shared.flags & header_flag::range_coded;
    info.file_bytes = size;
    const std::size_t count = index.entries.size ();
    info.num_tiles = count;
    auto add = [&] (const ModelFileSection& s) {
      auto it = std::find_if (info.sections.begin (), info.sections.end (), [&] (const ModelFileSection& t) { return t.tag == s.tag; });
      if (it == info.sections.end ())
        info.sections.push_back (s);
      else
      {
        it->stored_bytes += s.stored_bytes;
        it->raw_bytes += s.raw_bytes;
      }
    };
    if (index.version == kTiledVersion2)
    {
      const std::uint64_t index_bytes = index.index_bytes;
      info.sections.push_back ({"TIDX", index_bytes, index_bytes});
      // The tiles' sections, summed by tag; the basis and flags of the first tile.
      for (std::size_t i = 0; i < count; ++i)
      {
        const TileIndexEntry& e = index.entries[i];
        const std::string what = name + ": tile " + std::to_string (e.tile);
        const ModelFileInfo tile = inspectModel (version2Tile (data + e.offset, e.size, what), e.size, what);
        if (i == 0)
        {
          info.basis = tile.basis;
          info.has_vertices = tile.has_vertices;
          info.attributes = tile.attributes;
        }
        for (const ModelFileSection& s : tile.sections)
          add (s);
      }
      return info;
    }
    const SharedModelFields& shared = index.shared;
    info.basis = basisDescription (shared.basis_kind, shared.basis_parameter);
    info.has_vertices = shared.flags & header_flag::vertices;
    const std::uint64_t index_bytes = index.index_bytes - shared.quantisation.size () - shared.channels.size ();
    info.sections.push_back ({"TIDX", index_bytes, index_bytes});
    if (!shared.quantisation.empty ())
      info.sections.push_back ({"QUAN", shared.quantisation.size (), shared.quantisation.size ()});
    if (!shared.channels.empty ())
    {
      info.sections.push_back ({"ACHN", shared.channels.size (), shared.channels.size ()});
      ByteReader channels (shared.channels.data (), shared.channels.size (), name + ": section ACHN");
      for (const AttributeChannelInfo& channel : decodeAttributeChannels (channels, info.quantised))
        info.attributes.push_back (attributeChannelName (channel.channel));
    }
    // Each section's stored and decompressed bytes summed over the tiles; TILE: the tiles' own framing
    // (section sizes and CRC-32).
    const std::vector<std::string> tags = runSectionTags (shared.flags);
    for (const std::string& tag : tags)
      info.sections.push_back ({tag, 0, 0});
    info.sections.push_back ({"TILE", 0, 0});
    for (std::size_t i = 0; i < count; ++i)
    {
      const TileIndexEntry& e = index.entries[i];
      const std::string what = name + ": tile " + std::to_string (e.tile);
      const std::uint8_t* bytes = data + e.offset;
      const std::vector<TileSection> table = tileSectionTable (bytes, checkTile (e, bytes, what), tags, what);
      std::uint64_t framing = e.size;
      for (std::size_t t = 0; t < tags.size (); ++t)
      {
        add ({tags[t], table[t].stored, table[t].raw});
        framing -= table[t].stored;
      }
      add ({"TILE", framing, framing});
    }
    return info;
  }
} // namespace pcl_sparse
