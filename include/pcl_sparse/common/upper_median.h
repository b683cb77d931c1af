#pragma once
/// \file upper_median.h
/// The median the library takes of spacings, residuals and steps, in one place.

#include <algorithm>
#include <vector>

namespace pcl_sparse
{
  /// \brief The upper median of \a values: the element at index size / 2 once sorted (for an even count the
  /// larger of the two middle ones, so it is always one of the values). O(n): std::nth_element.
  /// \param[in,out] values  reordered
  /// \return the upper median, 0 when \a values is empty
  inline double
  upperMedian (std::vector<double>& values)
  {
    if (values.empty ())
      return 0.0;
    const auto middle = values.begin () + static_cast<std::ptrdiff_t> (values.size () / 2);
    std::nth_element (values.begin (), middle, values.end ());
    return *middle;
  }
} // namespace pcl_sparse
