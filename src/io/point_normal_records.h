#pragma once
/// \file point_normal_records.h
/// Internal to src/io: the bytes of a cloud of points with normals in the files savePointNormalCloud and
/// PointNormalStreamWriter write, so that both write the same bytes. A point is x y z (float, or double
/// offset + position), then nx ny nz curvature (float): the records of a binary PCD (PCL's writer, which
/// drops PointNormal's padding) and of a binary PLY are the same.

#include <Eigen/Core>

#include <pcl/PCLPointCloud2.h>
#include <pcl/point_types.h>

#include <charconv>
#include <cstring>
#include <string>

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

    /// Bytes of one binary record: 28 with float x y z, 40 with double.
    inline std::size_t
    binaryRecordSize (bool doubles)
    {
      return doubles ? 40 : 28;
    }

    /// Writes the binary record of \a point at \a out (binaryRecordSize bytes); with \a doubles, x y z =
    /// offset + position in double precision.
    inline void
    writeBinaryRecord (const pcl::PointNormal& point, bool doubles, const Eigen::Vector3d& offset, char* out)
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
      const float rest[4] = {point.normal_x, point.normal_y, point.normal_z, point.curvature};
      std::memcpy (out, rest, sizeof (rest));
    }

    /// The PLY header of \a count points; with \a doubles, x y z are double properties.
    inline std::string
    plyHeader (std::size_t count, bool binary, bool doubles)
    {
      const std::string xyz_type = doubles ? "double" : "float";
      return std::string ("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
             " 1.0\ncomment written by pcl_sparse\nelement vertex " + std::to_string (count) + "\nproperty " + xyz_type +
             " x\nproperty " + xyz_type + " y\nproperty " + xyz_type +
             " z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float curvature\nend_header\n";
    }

    /// Appends the PLY vertex of \a point (binary record or one ascii line).
    inline void
    appendPlyVertex (std::string& out, const pcl::PointNormal& point, bool binary, bool doubles,
                     const Eigen::Vector3d& offset)
    {
      if (binary)
      {
        const std::size_t at = out.size ();
        out.resize (at + binaryRecordSize (doubles));
        writeBinaryRecord (point, doubles, offset, &out[at]);
        return;
      }
      for (int k = 0; k < 3; ++k)
        if (doubles)
          appendValue (out, offset[k] + static_cast<double> (point.data[k]), false, ' ');
        else
          appendValue (out, point.data[k], false, ' ');
      const float rest[4] = {point.normal_x, point.normal_y, point.normal_z, point.curvature};
      for (int k = 0; k < 4; ++k)
        appendValue (out, rest[k], false, k < 3 ? ' ' : '\n');
    }

    /// The layout (fields, sizes, no data) of \a count records with double x y z: x y z FLOAT64, then
    /// normal_x normal_y normal_z curvature FLOAT32, 40 bytes a point, one row.
    inline pcl::PCLPointCloud2
    doublePositionLayout (std::size_t count, bool is_dense)
    {
      pcl::PCLPointCloud2 blob;
      const char* names[7] = {"x", "y", "z", "normal_x", "normal_y", "normal_z", "curvature"};
      std::uint32_t offset = 0;
      for (int k = 0; k < 7; ++k)
      {
        pcl::PCLPointField field;
        field.name = names[k];
        field.offset = offset;
        field.datatype = k < 3 ? pcl::PCLPointField::FLOAT64 : pcl::PCLPointField::FLOAT32;
        field.count = 1;
        offset += k < 3 ? 8 : 4;
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
