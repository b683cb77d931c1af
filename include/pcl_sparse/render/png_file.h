#pragma once
/// \file png_file.h
/// PNG output through libpng (a deflate encoder is not something to write again). No time stamp or other
/// varying chunk is written, so the same image always gives the same bytes.

#include <pcl_sparse/render/rgb_image.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Encodes an image as an 8-bit RGB PNG in memory.
  /// \param[in] image  the image (at least 1 x 1)
  /// \return the bytes of the PNG file
  /// \throws pcl_sparse::Error if the image is empty or libpng fails
  std::vector<std::uint8_t>
  encodePng (const RgbImage& image);

  /// Writes an image as a PNG file, atomically (writeBytesAtomically: no partial file on failure).
  /// \param[in] path   the file
  /// \param[in] image  the image
  /// \throws pcl_sparse::Error naming \a path if encoding or writing fails
  void
  savePng (const std::string& path, const RgbImage& image);
} // namespace pcl_sparse
