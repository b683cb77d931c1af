#pragma once
/// \file crc32.h
/// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as in zlib and PNG) for the per-section
/// checksums of the model file format. Table-driven, a few lines: not worth a dependency.

#include <cstddef>
#include <cstdint>

namespace pcl_sparse
{
  /// CRC-32 of a byte range; crc32 ("123456789") == 0xCBF43926.
  /// \param[in] data  first byte
  /// \param[in] size  number of bytes
  /// \return the checksum
  std::uint32_t
  crc32 (const std::uint8_t* data, std::size_t size);
} // namespace pcl_sparse
