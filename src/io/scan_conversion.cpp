/// The point types toScanCloud is compiled for (scan_conversion.h).

#include <pcl_sparse/io/impl/scan_conversion.hpp>

namespace pcl_sparse
{
  template void toScanCloud<pcl::PointXYZ> (const pcl::PointCloud<pcl::PointXYZ>&, ScanCloud&, const ScanCleaningOptions&);
  template void toScanCloud<pcl::PointXYZI> (const pcl::PointCloud<pcl::PointXYZI>&, ScanCloud&, const ScanCleaningOptions&);
  template void toScanCloud<pcl::PointXYZRGB> (const pcl::PointCloud<pcl::PointXYZRGB>&, ScanCloud&, const ScanCleaningOptions&);
  template void toScanCloud<pcl::PointXYZRGBA> (const pcl::PointCloud<pcl::PointXYZRGBA>&, ScanCloud&, const ScanCleaningOptions&);
  template void toScanCloud<pcl::PointNormal> (const pcl::PointCloud<pcl::PointNormal>&, ScanCloud&, const ScanCleaningOptions&);
  template void toScanCloud<pcl::PointXYZRGBNormal> (const pcl::PointCloud<pcl::PointXYZRGBNormal>&, ScanCloud&,
                                                     const ScanCleaningOptions&);
} // namespace pcl_sparse
