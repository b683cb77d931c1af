#pragma once
/// \file seed_coding.h
/// The seeds of a quantised, range-coded model file (header_flag::coded_seeds, docs/FORMAT.md): each
/// patch's integer seed steps as the difference from the previous patch's, per axis, through an adaptive
/// signed-integer model. The encoder puts its patches in the Morton order of their seeds where that codes
/// smaller (coding_order.h), so the differences are short: 26-42 bits a seed on the shared meshes (33 in
/// the median), where byte planes under zstd took 25-48 (44).

#include <pcl_sparse/format/range_coder.h>

#include <array>
#include <cstdint>

namespace pcl_sparse
{
  /// Codes (or decodes) the seeds of one run of patches in order; a new run starts from a new coder.
  class SeedStepCoder
  {
  public:
    /// \brief Codes a patch's seed steps (each < 2^63).
    void put (RangeEncoder& out, const std::array<std::uint64_t, 3>& steps);

    /// \brief Decodes the next patch's seed steps.
    /// \param[in] in     the SEED stream
    /// \param[in] limit  every step must be below it (2^(8 seed bytes) of QUAN)
    /// \throws pcl_sparse::Error (through \a in) for a step outside [0, limit)
    std::array<std::uint64_t, 3> get (RangeDecoder& in, std::uint64_t limit);

  private:
    SignedIntegerModel axis_[3];
    std::array<std::int64_t, 3> previous_{};
  };
} // namespace pcl_sparse
