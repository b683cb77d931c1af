#pragma once
/// \file color_map.h
/// Colour maps for inspecting per-vertex values and partitions: an error map (blue -> red), a
/// viridis-like ordered map and categorical colours. Each returns 8-bit RGB, as saveColoredMesh takes.

#include <array>
#include <cstddef>
#include <cstdint>

namespace pcl_sparse
{
  /// One 8-bit RGB colour.
  using RgbColor = std::array<std::uint8_t, 3>;

  /// Colour of a value on the error map: blue (0) -> cyan -> green -> yellow -> red (1). Used for
  /// reconstruction errors divided by their maximum.
  /// \param[in] t  value in [0, 1]; values outside are clamped, NaN maps like 0
  /// \return the colour
  RgbColor
  errorColor (double t);

  /// Colour of a value on a viridis-like map: dark purple (0) -> blue -> teal -> green -> yellow (1),
  /// linear between five stops of matplotlib's viridis. Perceptually ordered and readable in grey too.
  /// \param[in] t  value in [0, 1]; values outside are clamped, NaN maps like 0
  /// \return the colour
  RgbColor
  viridisColor (double t);

  /// A colour per category (a patch, a component): hue steps of the golden ratio, so neighbouring
  /// indices differ strongly, saturation varied with period 5, value 0.95. Never black or grey, so both
  /// stay free for marks (seeds) and "no category".
  /// \param[in] i  category index
  /// \return the colour
  RgbColor
  categoryColor (std::size_t i);
} // namespace pcl_sparse
