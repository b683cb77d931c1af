#pragma once
/// \file scan_conversion.h
/// From a pcl::PointCloud already in memory (from a grabber, a filter, PCL's readers) to a cleaned ScanCloud:
/// the same local frame and cleaning as loadScanCloud.

#include <pcl_sparse/io/scan_cleaning.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace pcl_sparse
{
  /// Copies \a cloud into \a scan in double precision and cleans it (cleanScan with \a options): positions in
  /// the local frame of localFrameOrigin of the kept points, normals when PointT has normal_x/y/z, colours (rgba) when it has
  /// rgb, intensities when it has intensity, width x height, the storage index of each point, and
  /// sensor_origin_ / sensor_orientation_ as the sensor pose. is_dense is not trusted: non-finite points are
  /// dropped and counted whatever it says.
  ///
  /// Instantiated in the library for pcl::PointXYZ, PointXYZI, PointXYZRGB, PointXYZRGBA, PointNormal and
  /// PointXYZRGBNormal; other point types: define PCL_NO_PRECOMPILE before including this header.
  template <typename PointT>
  void
  toScanCloud (const pcl::PointCloud<PointT>& cloud, ScanCloud& scan,
               const ScanCleaningOptions& options = ScanCleaningOptions ());
} // namespace pcl_sparse

#ifdef PCL_NO_PRECOMPILE
#include <pcl_sparse/io/impl/scan_conversion.hpp>
#else
namespace pcl_sparse
{
  extern template void toScanCloud<pcl::PointXYZ> (const pcl::PointCloud<pcl::PointXYZ>&, ScanCloud&, const ScanCleaningOptions&);
  extern template void toScanCloud<pcl::PointXYZI> (const pcl::PointCloud<pcl::PointXYZI>&, ScanCloud&, const ScanCleaningOptions&);
  extern template void toScanCloud<pcl::PointXYZRGB> (const pcl::PointCloud<pcl::PointXYZRGB>&, ScanCloud&, const ScanCleaningOptions&);
  extern template void toScanCloud<pcl::PointXYZRGBA> (const pcl::PointCloud<pcl::PointXYZRGBA>&, ScanCloud&, const ScanCleaningOptions&);
  extern template void toScanCloud<pcl::PointNormal> (const pcl::PointCloud<pcl::PointNormal>&, ScanCloud&, const ScanCleaningOptions&);
  extern template void toScanCloud<pcl::PointXYZRGBNormal> (const pcl::PointCloud<pcl::PointXYZRGBNormal>&, ScanCloud&,
                                                            const ScanCleaningOptions&);
} // namespace pcl_sparse
#endif
