#include <pcl_sparse/format/zstd_codec.h>

#include <pcl_sparse/common/error.h>

#include <zstd.h>

#include <memory>

namespace pcl_sparse
{
  std::vector<std::uint8_t>
  compressBytes (const std::uint8_t* data, std::size_t size, int level)
  {
    std::vector<std::uint8_t> out (ZSTD_compressBound (size));
    std::unique_ptr<ZSTD_CCtx, decltype (&ZSTD_freeCCtx)> context (ZSTD_createCCtx (), &ZSTD_freeCCtx);
    if (!context)
      throw Error ("zstd: cannot create a compression context");
    ZSTD_CCtx_setParameter (context.get (), ZSTD_c_compressionLevel, level);
    ZSTD_CCtx_setParameter (context.get (), ZSTD_c_contentSizeFlag, 1);
    ZSTD_CCtx_setParameter (context.get (), ZSTD_c_checksumFlag, 0);  // our own CRC covers the section
    const std::size_t written = ZSTD_compress2 (context.get (), out.data (), out.size (), data, size);
    if (ZSTD_isError (written))
      throw Error (std::string ("zstd: compression failed: ") + ZSTD_getErrorName (written));
    out.resize (written);
    return out;
  }

  std::uint64_t
  zstdFrameContentSize (const std::uint8_t* data, std::size_t size, const std::string& what)
  {
    const unsigned long long declared = ZSTD_getFrameContentSize (data, size);
    if (declared == ZSTD_CONTENTSIZE_ERROR)
      throw Error (what + ": not a valid zstd frame");
    if (declared == ZSTD_CONTENTSIZE_UNKNOWN)
      throw Error (what + ": zstd frame without a content size");
    return declared;
  }

  std::vector<std::uint8_t>
  decompressBytes (const std::uint8_t* data, std::size_t size, std::size_t expected_size, const std::string& what)
  {
    const unsigned long long declared = ZSTD_getFrameContentSize (data, size);
    if (declared == ZSTD_CONTENTSIZE_ERROR)
      throw Error (what + ": not a valid zstd frame");
    if (declared == ZSTD_CONTENTSIZE_UNKNOWN)
      throw Error (what + ": zstd frame without a content size");
    if (declared != expected_size)
      throw Error (what + ": zstd frame holds " + std::to_string (declared) + " bytes, the section header says " +
                   std::to_string (expected_size));
    const std::size_t frame_size = ZSTD_findFrameCompressedSize (data, size);
    if (ZSTD_isError (frame_size))
      throw Error (what + ": truncated or malformed zstd frame (" + ZSTD_getErrorName (frame_size) + ")");
    if (frame_size != size)
      throw Error (what + ": " + std::to_string (size - frame_size) + " bytes after the zstd frame");
    // One-shot decompression into a buffer of the checked size: no streaming window is allocated.
    std::vector<std::uint8_t> out (expected_size);
    std::unique_ptr<ZSTD_DCtx, decltype (&ZSTD_freeDCtx)> context (ZSTD_createDCtx (), &ZSTD_freeDCtx);
    if (!context)
      throw Error (what + ": cannot create a zstd decompression context");
    const std::size_t got = ZSTD_decompressDCtx (context.get (), out.data (), out.size (), data, size);
    if (ZSTD_isError (got))
      throw Error (what + ": corrupt zstd data (" + ZSTD_getErrorName (got) + ")");
    if (got != expected_size)
      throw Error (what + ": zstd frame decoded to " + std::to_string (got) + " bytes, expected " +
                   std::to_string (expected_size));
    return out;
  }
} // namespace pcl_sparse
