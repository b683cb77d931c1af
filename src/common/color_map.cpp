#include <pcl_sparse/common/color_map.h>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// \a t clamped to [0, 1], NaN as 0.
    double
    unitInterval (double t)
    {
      return std::isnan (t) ? 0.0 : std::clamp (t, 0.0, 1.0);
    }
  } // namespace

  RgbColor
  errorColor (double t)
  {
    t = unitInterval (t);
    const double r = std::min (1.0, std::max (0.0, 2.0 * t - 1.0) * 2.0);
    const double g = t < 0.25 ? 4.0 * t : (t > 0.75 ? 4.0 * (1.0 - t) : 1.0);
    const double b = std::min (1.0, std::max (0.0, 1.0 - 2.0 * t) * 2.0);
    return {static_cast<std::uint8_t> (std::lround (255 * r)), static_cast<std::uint8_t> (std::lround (255 * g)),
            static_cast<std::uint8_t> (std::lround (255 * b))};
  }

  RgbColor
  viridisColor (double t)
  {
    static const double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
    t = unitInterval (t) * 4.0;
    const int i = std::min (3, static_cast<int> (t));
    const double f = t - i;
    RgbColor rgb;
    for (int c = 0; c < 3; ++c)
      rgb[c] = static_cast<std::uint8_t> (std::lround (stops[i][c] + f * (stops[i + 1][c] - stops[i][c])));
    return rgb;
  }

  RgbColor
  categoryColor (std::size_t i)
  {
    // HSV to RGB with h in [0, 6).
    const double h = std::fmod (0.61803398875 * static_cast<double> (i), 1.0) * 6.0;
    const double s = 0.55 + 0.35 * static_cast<double> ((i * 7) % 5) / 4.0, v = 0.95;
    const int k = static_cast<int> (h);
    const double f = h - k, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (k % 6)
    {
      case 1: r = q; g = v; b = p; break;
      case 2: r = p; g = v; b = t; break;
      case 3: r = p; g = q; b = v; break;
      case 4: r = t; g = p; b = v; break;
      case 5: r = v; g = p; b = q; break;
      default: break;
    }
    return {static_cast<std::uint8_t> (255 * r), static_cast<std::uint8_t> (255 * g), static_cast<std::uint8_t> (255 * b)};
  }
} // namespace pcl_sparse
