#include <pcl_sparse/format/seed_coding.h>

#include <string>

namespace pcl_sparse
{
  void
  SeedStepCoder::put (RangeEncoder& out, const std::array<std::uint64_t, 3>& steps)
  {
    for (int i = 0; i < 3; ++i)
    {
      const auto step = static_cast<std::int64_t> (steps[i]);
      axis_[i].put (out, step - previous_[i]);
      previous_[i] = step;
    }
  }

  std::array<std::uint64_t, 3>
  SeedStepCoder::get (RangeDecoder& in, std::uint64_t limit)
  {
    std::array<std::uint64_t, 3> steps{};
    for (int i = 0; i < 3; ++i)
    {
      const std::int64_t delta = axis_[i].get (in);  // |delta| < 2^63, previous_ in [0, limit), limit <= 2^32
      const auto room = static_cast<std::int64_t> (limit) - previous_[i];
      if (delta >= 0 ? delta >= room : -delta > previous_[i])
        in.fail ("a seed step outside 0.." + std::to_string (limit - 1));
      previous_[i] += delta;
      steps[i] = static_cast<std::uint64_t> (previous_[i]);
    }
    return steps;
  }
} // namespace pcl_sparse
