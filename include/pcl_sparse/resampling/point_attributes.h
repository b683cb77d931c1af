#pragma once
/// \file point_attributes.h
/// \brief Resampled attribute values into a PCL cloud's colour and intensity fields.

#include <pcl_sparse/model/vertex_attributes.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// \brief Writes r g b (and a, if there is an Alpha channel) when \a PointT has colour and \a channels
  /// has Red, Green and Blue, and intensity when both have it. Fields without a channel are left as they are.
  /// \param[in] channels the model's attribute channels (C)
  /// \param[in] values C values per point, point after point (SparseSurfaceResampling::getPointAttributes)
  /// \param[in,out] cloud the resampled points, values.size () / C of them
  template <typename PointT>
  void
  writePointAttributes (const std::vector<AttributeChannelInfo>& channels, const std::vector<float>& values,
                        pcl::PointCloud<PointT>& cloud)
  {
    const std::size_t stride = channels.size ();
    if (stride == 0 || values.size () != stride * cloud.size ())
      return;
    int index[num_attribute_channels] = {-1, -1, -1, -1, -1};
    for (std::size_t c = 0; c < stride; ++c)
      index[static_cast<int> (channels[c].channel)] = static_cast<int> (c);
    [[maybe_unused]] auto byte = [] (float v) {
      return static_cast<std::uint8_t> (std::lround (std::min (255.0f, std::max (0.0f, v))));
    };
    [[maybe_unused]] const int red = index[0], green = index[1], blue = index[2], alpha = index[3], intensity = index[4];
    for (std::size_t i = 0; i < cloud.size (); ++i)
    {
      [[maybe_unused]] const float* v = values.data () + i * stride;
      [[maybe_unused]] PointT& point = cloud[i];
      if constexpr (pcl::traits::has_color_v<PointT>)
      {
        if (red >= 0 && green >= 0 && blue >= 0)
        {
          point.r = byte (v[red]);
          point.g = byte (v[green]);
          point.b = byte (v[blue]);
        }
        if (alpha >= 0)
          point.a = byte (v[alpha]);
      }
      if constexpr (pcl::traits::has_intensity_v<PointT>)
        if (intensity >= 0)
          point.intensity = v[intensity];
    }
  }
} // namespace pcl_sparse
