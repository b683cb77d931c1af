#pragma once
/// \file bitmap_font.h
/// A tiny built-in 5 x 7 bitmap font for labels in rendered images (colour-bar scales): digits, the
/// signs of numbers and a few lower-case letters, so no font file or library is needed.

#include <pcl_sparse/render/rgb_image.h>

#include <string>

namespace pcl_sparse
{
  /// Width of a text in pixels: 6 * scale per character (5 columns and a gap), no trailing gap.
  /// \param[in] text   the text
  /// \param[in] scale  pixel size of one font dot
  /// \return the width
  int
  textWidth (const std::string& text, int scale);

  /// Draws a text, 7 * scale pixels high, with its top-left corner at (x, y). Characters the font does
  /// not have (anything but 0-9 . - + / : % = ( ) space and a c d e g h i l m n o p r s t u w x) are drawn as a box.
  /// \param[in,out] image  the image
  /// \param[in] x          left edge
  /// \param[in] y          top edge
  /// \param[in] text       the text
  /// \param[in] color      the colour of the dots
  /// \param[in] scale      pixel size of one font dot (1, 2, ...)
  void
  drawText (RgbImage& image, int x, int y, const std::string& text, const RgbColor& color, int scale = 1);
} // namespace pcl_sparse
