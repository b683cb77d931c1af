#pragma once
/// \file rgb_image.h
/// An 8-bit RGB raster image, rows top to bottom, what the renderer draws into and savePng writes.

#include <pcl_sparse/common/color_map.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// A width x height image of 8-bit RGB pixels, row-major from the top-left corner.
  struct RgbImage
  {
    int width = 0;                     ///< pixels per row
    int height = 0;                    ///< rows
    std::vector<std::uint8_t> pixels;  ///< width * height * 3 bytes, R G B per pixel

    /// Resizes the image and fills it with one colour.
    /// \param[in] w      width in pixels
    /// \param[in] h      height in pixels
    /// \param[in] color  the fill colour
    void
    reset (int w, int h, const RgbColor& color)
    {
      width = w;
      height = h;
      pixels.resize (static_cast<std::size_t> (w) * h * 3);
      for (std::size_t i = 0; i < pixels.size (); i += 3)
      {
        pixels[i] = color[0];
        pixels[i + 1] = color[1];
        pixels[i + 2] = color[2];
      }
    }

    /// The colour of a pixel.
    /// \param[in] x  column, 0 at the left
    /// \param[in] y  row, 0 at the top
    /// \return its colour
    RgbColor
    at (int x, int y) const
    {
      const std::size_t i = (static_cast<std::size_t> (y) * width + x) * 3;
      return {pixels[i], pixels[i + 1], pixels[i + 2]};
    }

    /// Sets a pixel; coordinates outside the image are ignored (so marks may be clipped).
    /// \param[in] x      column
    /// \param[in] y      row
    /// \param[in] color  the colour
    void
    set (int x, int y, const RgbColor& color)
    {
      if (x < 0 || y < 0 || x >= width || y >= height)
        return;
      const std::size_t i = (static_cast<std::size_t> (y) * width + x) * 3;
      pixels[i] = color[0];
      pixels[i + 1] = color[1];
      pixels[i + 2] = color[2];
    }
  };
} // namespace pcl_sparse
