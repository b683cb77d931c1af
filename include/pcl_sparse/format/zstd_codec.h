#pragma once
/// \file zstd_codec.h
/// zstd compression of byte streams, with a decompressor that checks the declared sizes before it
/// allocates anything (a file cannot make it allocate more than the caller allowed).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Compresses bytes into one zstd frame, with the content size recorded in the frame header.
  /// \param[in] data   first byte
  /// \param[in] size   number of bytes
  /// \param[in] level  1 .. 22 (19 is a good size/time trade-off for files written once and read often)
  /// \return the frame
  std::vector<std::uint8_t>
  compressBytes (const std::uint8_t* data, std::size_t size, int level);

  /// The content size a zstd frame declares in its header (nothing is decompressed).
  /// \param[in] data  first byte of the frame
  /// \param[in] size  bytes of the frame
  /// \param[in] what  names the data in error messages
  /// \return the declared size
  /// \throws pcl_sparse::Error "<what>: ..." if the header is malformed or declares no size
  std::uint64_t
  zstdFrameContentSize (const std::uint8_t* data, std::size_t size, const std::string& what);

  /// Decompresses one zstd frame that must hold exactly a given number of bytes. The output buffer is
  /// allocated only after the frame header agreed with that number; callers bound it beforehand.
  /// \param[in] data           first byte of the frame
  /// \param[in] size           bytes of the frame
  /// \param[in] expected_size  bytes it must decompress to
  /// \param[in] what           names the data in error messages
  /// \return the \a expected_size decompressed bytes
  /// \throws pcl_sparse::Error "<what>: ..." if the frame is malformed, holds more than one frame or
  ///         trailing bytes, or declares another size
  std::vector<std::uint8_t>
  decompressBytes (const std::uint8_t* data, std::size_t size, std::size_t expected_size, const std::string& what);
} // namespace pcl_sparse
