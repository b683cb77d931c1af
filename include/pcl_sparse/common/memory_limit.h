#pragma once
/// \file memory_limit.h
/// Work that cannot fit in this machine's memory is refused with the reason before it starts, instead of
/// ending in an OOM kill or std::bad_alloc after minutes (a resampled cloud of 1e9 points, a picture of
/// 16384 x 16384).

#include <string>

namespace pcl_sparse
{
  /// \brief This machine's physical memory in bytes (0 when it is unknown).
  double
  physicalMemoryBytes ();

  /// \brief Throws pcl_sparse::Error ("<what> need about X GB, more than this machine's Y GB[: <remedy>]")
  /// when \a bytes (an estimate) exceed the machine's physical memory; nothing when it is unknown.
  /// \param[in] bytes   the estimated need
  /// \param[in] what    what needs it, the start of the message ("SparseSurfaceResampling::compute: 1e+09 points held in memory")
  /// \param[in] remedy  what to do instead (may be empty)
  void
  checkFitsInMemory (double bytes, const std::string& what, const std::string& remedy = std::string ());
} // namespace pcl_sparse
