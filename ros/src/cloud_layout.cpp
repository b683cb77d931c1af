#include <pcl_sparse_ros/cloud_layout.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>

namespace pcl_sparse_ros
{
  namespace
  {
    bool
    hasField (const sensor_msgs::PointCloud2& cloud, const std::string& name)
    {
      return std::any_of (cloud.fields.begin (), cloud.fields.end (),
                          [&] (const sensor_msgs::PointField& f) { return f.name == name; });
    }
  } // namespace

  CloudLayout
  cloudLayoutOf (const sensor_msgs::PointCloud2& cloud)
  {
    for (const char* axis : {"x", "y", "z"})
      if (!hasField (cloud, axis))
        throw pcl_sparse::Error (std::string ("the cloud has no field '") + axis + "' (fields: " + describeCloud (cloud) + ")");
    const bool normals = hasField (cloud, "normal_x") && hasField (cloud, "normal_y") && hasField (cloud, "normal_z");
    const bool rgba = hasField (cloud, "rgba");
    const bool colour = rgba || hasField (cloud, "rgb");
    const bool intensity = hasField (cloud, "intensity");

    CloudLayout layout;
    if (normals)
      layout.input = colour ? InputLayout::XYZRGBNormal : InputLayout::Normal;
    else if (colour)
      layout.input = rgba ? InputLayout::XYZRGBA : InputLayout::XYZRGB;
    else if (intensity)
      layout.input = InputLayout::XYZI;
    layout.output = colour ? OutputLayout::XYZRGBNormal : intensity ? OutputLayout::XYZINormal : OutputLayout::Normal;
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
