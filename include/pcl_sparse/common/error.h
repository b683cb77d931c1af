#pragma once
/// \file error.h
/// The one exception type the library throws for bad input (files, meshes, options).
/// Tools catch it, print its message on one line and exit non-zero.

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

  /// Throws the options structs' validate () error: "<options>: <field> = <value> is out of range (<range>)".
  [[noreturn]] inline void
  throwOutOfRange (const std::string& options, const std::string& field, double value, const std::string& range)
  {
    throw Error (options + ": " + field + " = " + std::to_string (value) + " is out of range (" + range + ")");
  }
} // namespace pcl_sparse
