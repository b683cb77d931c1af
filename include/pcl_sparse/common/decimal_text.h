#pragma once
/// \file decimal_text.h
/// Numbers in messages: the shortest decimal text that reads back as the same double.

#include <charconv>
#include <string>

namespace pcl_sparse
{
  /// The shortest decimal text that reads back exactly as \a value ("67108864", "0.1", "-1e-09"): %g rounded
  /// to 6 digits (6.71089e+07) and std::to_string to 6 decimals (an int 0 as 0.000000).
  inline std::string
  shortestDecimal (double value)
  {
    char text[32];
    return std::string (text, std::to_chars (text, text + sizeof (text), value).ptr);
  }
} // namespace pcl_sparse
