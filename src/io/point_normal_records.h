#pragma once
/// \file point_normal_records.h
/// Internal to src/io: the bytes of a cloud of points with normals in the files savePointNormalCloud and
/// PointNormalStreamWriter write, so that both write the same bytes. A point is x y z (float, or double
/// offset + position), then the extra field of a coloured or intensity cloud, then nx ny nz curvature
/// (float): the records of a binary PCD (PCL's writer, which drops the padding) and of a binary PLY are
/// the same but for colour, which a PLY stores as three uchar.

#include <pcl_sparse/io/cloud_io.h>

#include <Eigen/Core>

#include <pcl/PCLPointCloud2.h>
#include <pcl/point_types.h>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  namespace io_detail
  {
    /// Appends \a value in binary (native little endian) or as shortest round-trip text followed by \a separator.
    template <typename T>
    void
    appendValue (std::string& out, T value, bool binary, char separator)
    {
      if (binary)
      {
        out.append (reinterpret_cast<const char*> (&value), sizeof (value));
        return;
      }
      char text[32];
      const auto result = std::to_chars (text, text + sizeof (text), value);
      out.append (text, result.ptr);
      out += separator;
    }

    /// Bytes of the extra field in a binary record: the PCD's rgb (packed b g r a) or intensity (float); a
    /// PLY's red green blue (three uchar) or intensity (float).
    inline std::size_t
    extraFieldSize (CloudExtraField extra, bool ply)
    {
      switch (extra)
      {
        case CloudExtraField::Colour: return ply ? 3 : 4;
        case CloudExtraField::Intensity: return 4;
        case CloudExtraField::None: break;
      }
      return 0;
    }

    /// Bytes of one binary record: 28 with float x y z, 40 with double, plus the extra field's.
    inline std::size_t
    binaryRecordSize (bool doubles, CloudExtraField extra = CloudExtraField::None, bool ply = false)
    {
      return (doubles ? 40 : 28) + extraFieldSize (extra, ply);
    }

    /// Writes the extra field of \a point at \a out (extraFieldSize bytes).
    template <typename PointT>
    void
    writeExtraField (const PointT& point, bool ply, char* out)
    {
      if constexpr (cloudExtraFieldOf<PointT> () == CloudExtraField::Colour)
      {
        if (ply)
        {
          const std::uint8_t rgb[3] = {point.r, point.g, point.b};
          std::memcpy (out, rgb, sizeof (rgb));
        }
        else
        {
          const std::uint32_t packed = point.rgba;
          std::memcpy (out, &packed, sizeof (packed));
        }
      }
      else if constexpr (cloudExtraFieldOf<PointT> () == CloudExtraField::Intensity)
        std::memcpy (out, &point.intensity, sizeof (float));
    }

    /// Writes the binary record of \a point at \a out (binaryRecordSize bytes): x y z, the extra field
    /// (as a PLY stores it if \a ply), normal, curvature; with \a doubles, x y z = offset + position in
    /// double precision.
    template <typename PointT>
    void
    writeBinaryRecord (const PointT& point, bool doubles, const Eigen::Vector3d& offset, char* out, bool ply = false)
    {
      if (doubles)
      {
        const double xyz[3] = {offset[0] + static_cast<double> (point.x), offset[1] + static_cast<double> (point.y),
                               offset[2] + static_cast<double> (point.z)};
        std::memcpy (out, xyz, sizeof (xyz));
        out += sizeof (xyz);
      }
      else
      {
        std::memcpy (out, point.data, 3 * sizeof (float));
        out += 3 * sizeof (float);
      }
      writeExtraField (point, ply, out);
      out += extraFieldSize (cloudExtraFieldOf<PointT> (), ply);
      const float rest[4] = {point.normal_x, point.normal_y, point.normal_z, point.curvature};
      std::memcpy (out, rest, sizeof (rest));
    }

    /// The PLY header of \a count points; with \a doubles, x y z are double properties; \a extra: the
    /// properties after z (uchar red green blue, or float intensity).
    inline std::string
    plyHeader (std::size_t count, bool binary, bool doubles, CloudExtraField extra = CloudExtraField::None)
    {
      const std::string xyz_type = doubles ? "double" : "float";
      const char* extra_properties = extra == CloudExtraField::Colour
                                       ? "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                                       : extra == CloudExtraField::Intensity ? "property float intensity\n" : "";
      return std::string ("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
             " 1.0\ncomment written by pcl_sparse\nelement vertex " + std::to_string (count) + "\nproperty " + xyz_type +
             " x\nproperty " + xyz_type + " y\nproperty " + xyz_type + " z\n" + extra_properties +
             "property float nx\nproperty float ny\nproperty float nz\nproperty float curvature\nend_header\n";
    }

    /// Appends the PLY vertex of \a point (binary record or one ascii line).
    template <typename PointT>
    void
    appendPlyVertex (std::string& out, const PointT& point, bool binary, bool doubles, const Eigen::Vector3d& offset)
    {
      if (binary)
      {
        const std::size_t at = out.size ();
        out.resize (at + binaryRecordSize (doubles, cloudExtraFieldOf<PointT> (), true));
        writeBinaryRecord (point, doubles, offset, &out[at], true);
        return;
      }
      for (int k = 0; k < 3; ++k)
        if (doubles)
          appendValue (out, offset[k] + static_cast<double> (point.data[k]), false, ' ');
        else
          appendValue (out, point.data[k], false, ' ');
      if constexpr (cloudExtraFieldOf<PointT> () == CloudExtraField::Colour)
        for (const int c : {point.r, point.g, point.b})
          appendValue (out, c, false, ' ');
      else if constexpr (cloudExtraFieldOf<PointT> () == CloudExtraField::Intensity)
        appendValue (out, point.intensity, false, ' ');
      const float rest[4] = {point.normal_x, point.normal_y, point.normal_z, point.curvature};
      for (int k = 0; k < 4; ++k)
        appendValue (out, rest[k], false, k < 3 ? ' ' : '\n');
    }

    /// The layout (fields, sizes, no data) of \a count records with double x y z: x y z FLOAT64, the
    /// extra field (rgb UINT32 as PCL writes it, or intensity FLOAT32), then normal_x normal_y normal_z
    /// curvature FLOAT32, one row.
    inline pcl::PCLPointCloud2
    doublePositionLayout (std::size_t count, bool is_dense, CloudExtraField extra = CloudExtraField::None)
    {
      pcl::PCLPointCloud2 blob;
      std::vector<std::pair<const char*, std::uint8_t>> fields = {
        {"x", pcl::PCLPointField::FLOAT64}, {"y", pcl::PCLPointField::FLOAT64}, {"z", pcl::PCLPointField::FLOAT64}};
      if (extra == CloudExtraField::Colour)
        fields.emplace_back ("rgb", pcl::PCLPointField::UINT32);
      else if (extra == CloudExtraField::Intensity)
        fields.emplace_back ("intensity", pcl::PCLPointField::FLOAT32);
      for (const char* name : {"normal_x", "normal_y", "normal_z", "curvature"})
        fields.emplace_back (name, pcl::PCLPointField::FLOAT32);
      std::uint32_t offset = 0;
      for (const auto& [name, type] : fields)
      {
        pcl::PCLPointField field;
        field.name = name;
        field.offset = offset;
        field.datatype = type;
        field.count = 1;
        offset += type == pcl::PCLPointField::FLOAT64 ? 8 : 4;
        blob.fields.push_back (field);
      }
      blob.point_step = offset;
      blob.width = static_cast<std::uint32_t> (count);
      blob.height = 1;
      blob.row_step = blob.point_step * blob.width;
      blob.is_dense = is_dense;
      return blob;
    }
  } // namespace io_detail
} // namespace pcl_sparse
