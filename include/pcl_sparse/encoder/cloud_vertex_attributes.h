#pragma once
/// \file cloud_vertex_attributes.h
/// \brief The colour and intensity fields of a PCL cloud or a ScanCloud as VertexAttributes, for the encoder.

#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/model/vertex_attributes.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace pcl_sparse
{
  /// \brief Channels r, g, b (and a, if the type has an rgba field) when \a PointT has colour, intensity when
  /// it has an intensity field; one row per point, in storage order. Empty for types with neither.
  /// \param[in] cloud the points
  template <typename PointT>
  VertexAttributes
  cloudVertexAttributes (const pcl::PointCloud<PointT>& cloud)
  {
    constexpr bool colour = pcl::traits::has_color_v<PointT>;
    constexpr bool alpha = pcl::traits::has_field<PointT, pcl::fields::rgba>::value;
    constexpr bool intensity = pcl::traits::has_intensity_v<PointT>;
    VertexAttributes attributes;
    if constexpr (colour)
      attributes.channels = {AttributeChannel::Red, AttributeChannel::Green, AttributeChannel::Blue};
    if constexpr (colour && alpha)
      attributes.channels.push_back (AttributeChannel::Alpha);
    if constexpr (intensity)
      attributes.channels.push_back (AttributeChannel::Intensity);
    attributes.values.resize (static_cast<Eigen::Index> (cloud.size ()), static_cast<Eigen::Index> (attributes.channels.size ()));
    for (std::size_t i = 0; i < cloud.size (); ++i)
    {
      [[maybe_unused]] const PointT& point = cloud[i];
      [[maybe_unused]] const Eigen::Index row = static_cast<Eigen::Index> (i);
      Eigen::Index c = 0;
      if constexpr (colour)
      {
        attributes.values (row, c++) = point.r;
        attributes.values (row, c++) = point.g;
        attributes.values (row, c++) = point.b;
      }
      if constexpr (colour && alpha)
        attributes.values (row, c++) = point.a;
      if constexpr (intensity)
        attributes.values (row, c++) = point.intensity;
    }
    return attributes;
  }

  /// \brief The same for a ScanCloud: r, g, b from its colours (and a when the file's fields include
  /// rgba), intensity from its intensities; one row per scan point. Empty when it has neither.
  /// \param[in] scan the scan
  VertexAttributes
  scanVertexAttributes (const ScanCloud& scan);
} // namespace pcl_sparse
