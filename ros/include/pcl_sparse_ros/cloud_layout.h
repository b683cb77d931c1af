#pragma once
/// \file cloud_layout.h
/// Which of the library's instantiated point types a sensor_msgs/PointCloud2 maps to, going in (encoder)
/// and coming out (resampling), by its field names.

#include <sensor_msgs/PointCloud2.h>

#include <string>

namespace pcl_sparse_ros
{
  /// Encoder input types (SparseSurfaceEncoder<T>), chosen by the fields the message has.
  enum class InputLayout
  {
    XYZ,          ///< pcl::PointXYZ
    XYZI,         ///< pcl::PointXYZI: an `intensity` field
    XYZRGB,       ///< pcl::PointXYZRGB: an `rgb` field (packed float, as office1.pcd)
    XYZRGBA,      ///< pcl::PointXYZRGBA: an `rgba` field (uint32)
    Normal,       ///< pcl::PointNormal: normal_x normal_y normal_z
    XYZRGBNormal  ///< pcl::PointXYZRGBNormal: normals and a colour
  };

  /// Resampling output types (SparseSurfaceResampling<T>): x y z normal_x normal_y normal_z curvature,
  /// plus the input's colour or intensity.
  enum class OutputLayout
  {
    Normal,        ///< pcl::PointNormal
    XYZRGBNormal,  ///< pcl::PointXYZRGBNormal (field `rgb`)
    XYZINormal     ///< pcl::PointXYZINormal (field `intensity`)
  };

  struct CloudLayout
  {
    InputLayout input = InputLayout::XYZ;
    OutputLayout output = OutputLayout::Normal;
  };

  /// \brief Refuses a message PCL's conversion would read past or misread (it checks nothing: a cloud
  /// declaring more points than its data holds crashed the node, and with it a nodelet manager): a
  /// big-endian cloud, row_step below width x point_step, data shorter than row_step x height, a field of
  /// an unknown datatype or past point_step. Throws pcl_sparse::Error saying which.
  void
  checkCloudMessage (const sensor_msgs::PointCloud2& cloud);

  /// \brief The layout of \a cloud: normals when it has all three normal fields, colour for `rgb` or
  /// `rgba`, intensity for a FLOAT32 `intensity` (colour wins over intensity; with normals, intensity is
  /// not an encoder input, so the output has none either). Throws pcl_sparse::Error when x, y or z is
  /// missing or not one FLOAT32, or the message fails checkCloudMessage.
  /// \param[in] cloud the message (its sizes are checked, its values not read)
  CloudLayout
  cloudLayoutOf (const sensor_msgs::PointCloud2& cloud);

  /// PCL's name of the type, e.g. "PointXYZRGBA".
  const char*
  pointTypeName (InputLayout layout);
  const char*
  pointTypeName (OutputLayout layout);

  /// One line about \a cloud for log messages: "640x480 (organized), x y z rgba".
  std::string
  describeCloud (const sensor_msgs::PointCloud2& cloud);
} // namespace pcl_sparse_ros
