#include <pcl_sparse/render/color_bar.h>

#include <pcl_sparse/render/bitmap_font.h>

#include <algorithm>
#include <cstdio>

namespace pcl_sparse
{
  namespace
  {
    /// Font dot size: doubled on images tall enough that the scale would otherwise be hard to read.
    int
    fontScale (int height)
    {
      return height >= 480 ? 2 : 1;
    }
  } // namespace

  int
  colorBarWidth (int height)
  {
    // Room for "9.9e-05" beside the bar, and margins.
    return 14 * fontScale (height) + 8 * 6 * fontScale (height) + 12;
  }

  void
  drawColorBar (RgbImage& image, double max_value, const std::string& title)
  {
    const int s = fontScale (image.height);
    const int bar_w = 10 * s, left = image.width - colorBarWidth (image.height) + 4;
    const int top = std::max (7 * s + 14, image.height / 6), bottom = image.height - std::max (10, image.height / 8);
    const RgbColor ink = {0, 0, 0};
    if (bottom - top < 4)
      return;
    for (int y = top; y <= bottom; ++y)
    {
      const RgbColor c = errorColor (static_cast<double> (bottom - y) / (bottom - top));
      for (int x = left; x < left + bar_w; ++x)
        image.set (x, y, c);
    }
    for (int y = top - 1; y <= bottom + 1; ++y)
    {
      image.set (left - 1, y, ink);
      image.set (left + bar_w, y, ink);
    }
    for (int x = left - 1; x <= left + bar_w; ++x)
    {
      image.set (x, top - 1, ink);
      image.set (x, bottom + 1, ink);
    }
    char label[32];
    std::snprintf (label, sizeof (label), "%.2g", max_value);
    const int text_x = left + bar_w + 3 * s;
    drawText (image, text_x, top, label, ink, s);
    drawText (image, text_x, bottom - 7 * s + 1, "0", ink, s);
    const int title_x = std::max (0, std::min (left, image.width - textWidth (title, s) - 2));
    drawText (image, title_x, top - 7 * s - 6, title, ink, s);
  }
} // namespace pcl_sparse
