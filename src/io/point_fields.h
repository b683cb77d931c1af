#pragma once
/// \file point_fields.h
/// Internal to src/io: reading the fields of a pcl::PCLPointCloud2 at their own type (PCL's conversions
/// leave fields whose type differs from the point type's at zero, e.g. double x y z into PointXYZ).

#include <pcl/PCLPointCloud2.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace io_detail
  {
    /// Bytes of one value of a PCLPointField datatype, 0 for an unknown datatype.
    inline std::size_t
    fieldSize (std::uint8_t datatype)
    {
      switch (datatype)
      {
        case pcl::PCLPointField::INT8:
        case pcl::PCLPointField::UINT8: return 1;
        case pcl::PCLPointField::INT16:
        case pcl::PCLPointField::UINT16: return 2;
        case pcl::PCLPointField::INT32:
        case pcl::PCLPointField::UINT32:
        case pcl::PCLPointField::FLOAT32: return 4;
        case pcl::PCLPointField::FLOAT64: return 8;
        default: return 0;
      }
    }

    /// Reads one value of a PCLPointField datatype at \a p as double (exact for every type but 64-bit
    /// integers, which PCD does not have).
    inline double
    readFieldValue (const std::uint8_t* p, std::uint8_t datatype)
    {
      switch (datatype)
      {
        case pcl::PCLPointField::INT8: { std::int8_t v; std::memcpy (&v, p, 1); return v; }
        case pcl::PCLPointField::UINT8: { std::uint8_t v; std::memcpy (&v, p, 1); return v; }
        case pcl::PCLPointField::INT16: { std::int16_t v; std::memcpy (&v, p, 2); return v; }
        case pcl::PCLPointField::UINT16: { std::uint16_t v; std::memcpy (&v, p, 2); return v; }
        case pcl::PCLPointField::INT32: { std::int32_t v; std::memcpy (&v, p, 4); return v; }
        case pcl::PCLPointField::UINT32: { std::uint32_t v; std::memcpy (&v, p, 4); return v; }
        case pcl::PCLPointField::FLOAT32: { float v; std::memcpy (&v, p, 4); return v; }
        case pcl::PCLPointField::FLOAT64: { double v; std::memcpy (&v, p, 8); return v; }
        default: return std::numeric_limits<double>::quiet_NaN ();
      }
    }

    /// The field named \a name that fits in a point (offset + size <= point_step), or null.
    inline const pcl::PCLPointField*
    findField (const pcl::PCLPointCloud2& cloud, const std::string& name)
    {
      for (const pcl::PCLPointField& field : cloud.fields)
        if (field.name == name)
        {
          const std::size_t size = fieldSize (field.datatype);
          return size != 0 && field.offset + size <= cloud.point_step ? &field : nullptr;
        }
      return nullptr;
    }
  } // namespace io_detail
} // namespace pcl_sparse
