#pragma once
/// \file impl/scan_conversion.hpp
/// Definition of toScanCloud (scan_conversion.h).

#include <pcl_sparse/io/scan_conversion.h>

#include <pcl/common/io.h>

#include <numeric>

namespace pcl_sparse
{
  template <typename PointT>
  void
  toScanCloud (const pcl::PointCloud<PointT>& cloud, ScanCloud& scan, const ScanCleaningOptions& options)
  {
    ScanCloud out;
    const std::size_t n = cloud.size ();
    out.positions.resize (n);
    for (std::size_t i = 0; i < n; ++i)
      out.positions[i] = cloud[i].getVector3fMap ().template cast<double> ();
    if constexpr (pcl::traits::has_normal_v<PointT>)
    {
      out.normals.resize (n);
      for (std::size_t i = 0; i < n; ++i)
        out.normals[i] = cloud[i].getNormalVector3fMap ().template cast<double> ();
    }
    if constexpr (pcl::traits::has_color_v<PointT>)
    {
      out.colors.resize (n);
      for (std::size_t i = 0; i < n; ++i)
        out.colors[i] = cloud[i].rgba;
    }
    if constexpr (pcl::traits::has_intensity_v<PointT>)
    {
      out.intensities.resize (n);
      for (std::size_t i = 0; i < n; ++i)
        out.intensities[i] = cloud[i].intensity;
    }
    if constexpr (pcl::traits::has_field<PointT, pcl::fields::vp_x>::value)  // pcl::PointWithViewpoint
    {
      out.viewpoints.resize (n);
      for (std::size_t i = 0; i < n; ++i)
        out.viewpoints[i] = Eigen::Vector3d (cloud[i].vp_x, cloud[i].vp_y, cloud[i].vp_z);
    }
    out.indices.resize (n);
    std::iota (out.indices.begin (), out.indices.end (), std::size_t (0));
    // A cloud whose width x height disagrees with its size is not a grid: keep it as a list.
    const bool grid = static_cast<std::size_t> (cloud.width) * cloud.height == n;
    out.width = grid ? cloud.width : static_cast<std::uint32_t> (n);
    out.height = grid ? cloud.height : 1;
    out.sensor_origin = cloud.sensor_origin_.template head<3> ().template cast<double> ();
    out.sensor_orientation = cloud.sensor_orientation_.template cast<double> ();
    out.has_sensor_pose = true;
    for (const pcl::PCLPointField& field : pcl::getFields<PointT> ())
      if (field.name != "_")
        out.fields.push_back (field.name);

    cleanScan (out, options);
    centreScan (out);  // on the kept points (see loadScanCloud)
    scan = std::move (out);
  }
} // namespace pcl_sparse
