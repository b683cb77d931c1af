#pragma once
/// \file color_bar.h
/// The scale of an error map drawn into the image: the errorColor ramp with its end values and a title.

#include <pcl_sparse/render/rgb_image.h>

#include <string>

namespace pcl_sparse
{
  /// Width in pixels colour bars take at the right edge of an image of \a height rows (bar, labels,
  /// margins); renderers leave it free.
  /// \param[in] height  image height
  /// \return the width
  int
  colorBarWidth (int height);

  /// Draws a vertical errorColor bar at the right edge: 0 at the bottom, \a max_value at the top (printed
  /// with 2 significant digits), \a title above.
  /// \param[in,out] image     the image
  /// \param[in] max_value     the value of the top colour
  /// \param[in] title         a short title (bitmap_font.h characters), e.g. "dist/diag"
  void
  drawColorBar (RgbImage& image, double max_value, const std::string& title);
} // namespace pcl_sparse
