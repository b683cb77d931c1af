#pragma once
/// \file error.h
/// The one exception type the library throws for bad input (files, meshes, options).
/// Tools catch it, print its message on one line and exit non-zero.

#include <pcl_sparse/common/decimal_text.h>

#include <stdexcept>
#include <string>

namespace pcl_sparse
{
  /// Raised for input the library refuses: unreadable or malformed files, meshes it cannot process,
  /// options out of range. The message names the offending file or option and the problem.
  class Error : public std::runtime_error
  {
  public:
    explicit Error (const std::string& message) : std::runtime_error (message) {}
  };

  /// Throws the options structs' validate () error: "<options>: <field> = <value> is out of range (<range>)",
  /// the value in its shortest exact decimal form (std::to_string wrote an int 0 as 0.000000, and -1e-9 as
  /// -0.000000).
  [[noreturn]] inline void
  throwOutOfRange (const std::string& options, const std::string& field, double value, const std::string& range)
  {
    throw Error (options + ": " + field + " = " + shortestDecimal (value) + " is out of range (" + range + ")");
  }
} // namespace pcl_sparse
