#pragma once
/// \file sparse_surface_resampling.hpp
/// \brief Definitions of SparseSurfaceResampling (resampling/sparse_surface_resampling.h).

#include <pcl_sparse/resampling/point_attributes.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/common/io.h>

#include <type_traits>

namespace pcl_sparse
{
  template <typename PointOutT>
  void
  SparseSurfaceResampling<PointOutT>::compute (PointCloudOut& output)
  {
    // Attributes are evaluated only for output types with fields for them (PointNormal has none).
    constexpr bool attributes = pcl::traits::has_color_v<PointOutT> || pcl::traits::has_intensity_v<PointOutT>;
    if constexpr (std::is_same_v<PointOutT, pcl::PointNormal>)
      resample (output);
    else
    {
      PointCloud full;
      resample (full, attributes);
      pcl::copyPointCloud (full, output);
      if constexpr (attributes)
        writePointAttributes (getInputModel ()->attribute_channels, getPointAttributes (), output);
    }
  }
} // namespace pcl_sparse
