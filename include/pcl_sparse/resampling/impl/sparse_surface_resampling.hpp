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
    // Replaced, and left empty when compute throws (it kept the last result, or a part of the new one).
    output.clear ();
    try
    {
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
    catch (...)
    {
      output.clear ();
      throw;
    }
  }

  template <typename PointOutT>
  void
  SparseSurfaceResampling<PointOutT>::compute (const BlockCallback& callback)
  {
    constexpr bool attributes = pcl::traits::has_color_v<PointOutT> || pcl::traits::has_intensity_v<PointOutT>;
    if constexpr (std::is_same_v<PointOutT, pcl::PointNormal>)
      resampleBlocks (callback);
    else
    {
      // One block of the output type, reused: converted as compute (cloud) converts the whole cloud.
      Block out;
      resampleBlocks (
        [&] (const ResampledBlock<pcl::PointNormal>& block) {
          pcl::copyPointCloud (block.cloud, out.cloud);
          if constexpr (attributes)
            writePointAttributes (getInputModel ()->attribute_channels, block.attributes, out.cloud);
          out.patches = block.patches;
          out.attributes = block.attributes;
          out.first = block.first;
          out.total = block.total;
          callback (out);
        },
        attributes);
    }
  }
} // namespace pcl_sparse
