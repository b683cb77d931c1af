#pragma once
/// \file cloud_io.h
/// Point cloud input/output with the same error discipline as mesh_io.h: one pcl_sparse::Error whose message
/// names the file and the problem, and atomic writes.

#include <Eigen/Core>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>
#include <type_traits>

namespace pcl_sparse
{
  /// Loads the points of a file:
  /// - .pcd through PCL's PCD reader (any fields; x, y, z required);
  /// - .ply (with or without faces), .obj, .off, .stl: the vertices, read by loadTriangleMesh.
  ///
  /// NaN/Inf points are kept (PCL's convention) and make is_dense false; a file with no points gives an
  /// empty cloud.
  /// \param[in]  path   the file
  /// \param[out] cloud  the points (width = #points, height = 1 for mesh formats)
  /// \throws pcl_sparse::Error for a missing, empty, malformed or truncated file, a directory or an
  ///         unknown extension
  void
  loadPointCloud (const std::string& path, pcl::PointCloud<pcl::PointXYZ>& cloud);

  /// The field a resampled cloud has between x y z and its normal: none (pcl::PointNormal), colour
  /// (pcl::PointXYZRGBNormal: PCD field rgb, PLY properties uchar red green blue) or intensity
  /// (pcl::PointXYZINormal: float intensity in both).
  enum class CloudExtraField
  {
    None,
    Colour,
    Intensity
  };

  /// The extra field of PointT: pcl::PointNormal none, pcl::PointXYZRGBNormal colour, pcl::PointXYZINormal
  /// intensity.
  template <typename PointT>
  constexpr CloudExtraField
  cloudExtraFieldOf ()
  {
    if constexpr (std::is_same_v<PointT, pcl::PointXYZRGBNormal>)
      return CloudExtraField::Colour;
    else if constexpr (std::is_same_v<PointT, pcl::PointXYZINormal>)
      return CloudExtraField::Intensity;
    else
    {
      static_assert (std::is_same_v<PointT, pcl::PointNormal>, "a point type with a normal and curvature");
      return CloudExtraField::None;
    }
  }

  /// Writes points with normals and curvature, atomically: .pcd through PCL's writer, or .ply with float
  /// properties x y z nx ny nz curvature (with colour or intensity after z, as PCL's PLY writer puts them).
  /// PointT: pcl::PointNormal, pcl::PointXYZRGBNormal or pcl::PointXYZINormal.
  /// \param[in] path    the file; its extension chooses the format
  /// \param[in] cloud   the points
  /// \param[in] binary  binary (PCD binary, PLY binary little endian; default) or ascii
  /// \throws pcl_sparse::Error on an unknown extension or a failed write
  template <typename PointT>
  void
  savePointNormalCloud (const std::string& path, const pcl::PointCloud<PointT>& cloud, bool binary = true);

  /// \brief Same, for a cloud in a local frame: the file gets x y z = \a offset + each point's position, in
  /// double precision (PCD fields x y z of TYPE F SIZE 8, PLY properties double x y z), so that map
  /// coordinates (1e5 - 1e7) keep the cloud's local resolution. A zero \a offset writes the float file
  /// of the overload above, byte for byte.
  /// \param[in] path .pcd or .ply
  /// \param[in] cloud points in the local frame
  /// \param[in] binary binary (default) or ascii
  /// \param[in] offset the local frame's origin in the file's frame
  template <typename PointT>
  void
  savePointNormalCloud (const std::string& path, const pcl::PointCloud<PointT>& cloud, bool binary,
                        const Eigen::Vector3d& offset);
} // namespace pcl_sparse
