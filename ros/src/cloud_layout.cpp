#include <pcl_sparse_ros/cloud_layout.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cstdint>

namespace pcl_sparse_ros
{
  namespace
  {
    const sensor_msgs::PointField*
    findField (const sensor_msgs::PointCloud2& cloud, const std::string& name)
    {
      const auto it = std::find_if (cloud.fields.begin (), cloud.fields.end (),
                                    [&] (const sensor_msgs::PointField& f) { return f.name == name; });
      return it == cloud.fields.end () ? nullptr : &*it;
    }

    bool
    hasField (const sensor_msgs::PointCloud2& cloud, const std::string& name)
    {
      return findField (cloud, name) != nullptr;
    }

    /// Bytes of one value of a PointField datatype; 0 for an unknown one.
    std::uint64_t
    valueBytes (std::uint8_t datatype)
    {
      switch (datatype)
      {
        case sensor_msgs::PointField::INT8:
        case sensor_msgs::PointField::UINT8: return 1;
        case sensor_msgs::PointField::INT16:
        case sensor_msgs::PointField::UINT16: return 2;
        case sensor_msgs::PointField::INT32:
        case sensor_msgs::PointField::UINT32:
        case sensor_msgs::PointField::FLOAT32: return 4;
        case sensor_msgs::PointField::FLOAT64: return 8;
      }
      return 0;
    }

    const char*
    datatypeName (std::uint8_t datatype)
    {
      static const char* const names[] = {"?", "INT8", "UINT8", "INT16", "UINT16", "INT32", "UINT32", "FLOAT32", "FLOAT64"};
      return datatype <= 8 ? names[datatype] : "?";
    }
  } // namespace

  void
  checkCloudMessage (const sensor_msgs::PointCloud2& cloud)
  {
    using pcl_sparse::Error;
    if (cloud.is_bigendian)
      throw Error ("the cloud is big-endian (is_bigendian): only little-endian clouds are read");
    const std::uint64_t row_bytes = static_cast<std::uint64_t> (cloud.width) * cloud.point_step;
    if (cloud.row_step < row_bytes)
      throw Error ("row_step " + std::to_string (cloud.row_step) + " is less than width x point_step = " +
                   std::to_string (row_bytes));
    const std::uint64_t bytes = static_cast<std::uint64_t> (cloud.row_step) * cloud.height;
    if (cloud.data.size () < bytes)
      throw Error ("the data holds " + std::to_string (cloud.data.size ()) + " bytes, less than row_step x height = " +
                   std::to_string (bytes));
    for (const sensor_msgs::PointField& f : cloud.fields)
    {
      const std::uint64_t size = valueBytes (f.datatype);
      if (size == 0)
        throw Error ("field '" + f.name + "' has the unknown datatype " + std::to_string (f.datatype));
      if (f.offset + size * std::max<std::uint32_t> (f.count, 1) > cloud.point_step)
        throw Error ("field '" + f.name + "' lies past point_step " + std::to_string (cloud.point_step));
    }
  }

  CloudLayout
  cloudLayoutOf (const sensor_msgs::PointCloud2& cloud)
  {
    for (const char* axis : {"x", "y", "z"})
    {
      const sensor_msgs::PointField* field = findField (cloud, axis);
      if (!field)
        throw pcl_sparse::Error (std::string ("the cloud has no field '") + axis + "' (fields: " + describeCloud (cloud) + ")");
      // PCL's conversion matches fields by name and type: doubles became "no usable point" (numpy's default).
      if (field->datatype != sensor_msgs::PointField::FLOAT32 || field->count > 1)
        throw pcl_sparse::Error (std::string ("field '") + axis + "' is " + datatypeName (field->datatype) +
                                 (field->count > 1 ? " x " + std::to_string (field->count) : std::string ()) +
                                 ": x, y and z must be one FLOAT32 each");
    }
    checkCloudMessage (cloud);
    const bool normals = hasField (cloud, "normal_x") && hasField (cloud, "normal_y") && hasField (cloud, "normal_z");
    const bool rgba = hasField (cloud, "rgba");
    const bool colour = rgba || hasField (cloud, "rgb");
    // PCL's conversion keeps a FLOAT32 intensity only (a UINT16 one came out as zeros).
    const sensor_msgs::PointField* intensity_field = findField (cloud, "intensity");
    const bool intensity = intensity_field && intensity_field->datatype == sensor_msgs::PointField::FLOAT32;

    CloudLayout layout;
    if (normals)
      layout.input = colour ? InputLayout::XYZRGBNormal : InputLayout::Normal;
    else if (colour)
      layout.input = rgba ? InputLayout::XYZRGBA : InputLayout::XYZRGB;
    else if (intensity)
      layout.input = InputLayout::XYZI;
    // Intensity goes out only when it went in (with normals the input type has none: it came out as zeros).
    layout.output = colour ? OutputLayout::XYZRGBNormal
                           : layout.input == InputLayout::XYZI ? OutputLayout::XYZINormal : OutputLayout::Normal;
    return layout;
  }

  const char*
  pointTypeName (InputLayout layout)
  {
    switch (layout)
    {
      case InputLayout::XYZ: return "PointXYZ";
      case InputLayout::XYZI: return "PointXYZI";
      case InputLayout::XYZRGB: return "PointXYZRGB";
      case InputLayout::XYZRGBA: return "PointXYZRGBA";
      case InputLayout::Normal: return "PointNormal";
      case InputLayout::XYZRGBNormal: return "PointXYZRGBNormal";
    }
    return "?";
  }

  const char*
  pointTypeName (OutputLayout layout)
  {
    switch (layout)
    {
      case OutputLayout::Normal: return "PointNormal";
      case OutputLayout::XYZRGBNormal: return "PointXYZRGBNormal";
      case OutputLayout::XYZINormal: return "PointXYZINormal";
    }
    return "?";
  }

  std::string
  describeCloud (const sensor_msgs::PointCloud2& cloud)
  {
    std::string text = std::to_string (cloud.width) + "x" + std::to_string (cloud.height) +
                       (cloud.height > 1 ? " (organized)," : ",");
    for (const sensor_msgs::PointField& f : cloud.fields)
      text += " " + f.name;
    return text;
  }
} // namespace pcl_sparse_ros
