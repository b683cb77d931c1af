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
  /// One zstd frame holding \a size bytes, with the content size recorded in the frame header.
  /// \a level 1..22 (19 is a good size/time trade-off for files written once and read often).
  std::vector<std::uint8_t>
  compressBytes (const std::uint8_t* data, std::size_t size, int level);

  /// Decompresses one zstd frame that must hold exactly \a expected_size bytes. Throws
  /// pcl_sparse::Error "<what>: ..." if the frame is malformed, holds more than one frame or trailing
  /// bytes, or declares another size. The output buffer (expected_size bytes) is allocated only after
  /// the frame header agreed; callers bound expected_size beforehand.
  std::vector<std::uint8_t>
  decompressBytes (const std::uint8_t* data, std::size_t size, std::size_t expected_size, const std::string& what);
} // namespace pcl_sparse
