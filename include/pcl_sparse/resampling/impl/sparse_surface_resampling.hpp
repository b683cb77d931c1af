#pragma once
/// \file sparse_surface_resampling.hpp
/// \brief Definitions of SparseSurfaceResampling (resampling/sparse_surface_resampling.h).

#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/common/io.h>

#include <type_traits>

namespace pcl_sparse
{
  template <typename PointOutT>
  void
  SparseSurfaceResampling<PointOutT>::compute (PointCloudOut& output)
  {
    if constexpr (std::is_same_v<PointOutT, pcl::PointNormal>)
      resample (output);
    else
    {
      PointCloud full;
      resample (full);
      pcl::copyPointCloud (full, output);
    }
  }
} // namespace pcl_sparse
