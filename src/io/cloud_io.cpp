#include <pcl_sparse/io/cloud_io.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include "cloud_readers.h"
#include "mesh_readers.h"

#include <pcl/io/pcd_io.h>

#include <charconv>
#include <cstring>
#include <cstdio>
#include <vector>

namespace pcl_sparse
{
  namespace
  {
    void
    loadPcd (const std::string& path, pcl::PointCloud<pcl::PointXYZ>& cloud)
    {
      io_detail::PcdBlob blob;
      io_detail::readPcdBlob (path, blob);
      // Read x, y, z at their own type: pcl::fromPCLPointCloud2 silently leaves fields whose type differs
      // from PointXYZ's (e.g. double x) at zero.
      const std::vector<Eigen::Vector3d> positions = positionsFromCloud (blob.cloud, path);
      cloud.clear ();
      cloud.resize (positions.size ());
      bool dense = true;
      for (std::size_t i = 0; i < positions.size (); ++i)
      {
        cloud[i].getVector3fMap () = positions[i].cast<float> ();
        dense = dense && cloud[i].getVector3fMap ().allFinite ();
      }
      cloud.width = blob.cloud.width;
      cloud.height = blob.cloud.height;
      cloud.is_dense = dense;
    }
  } // namespace

  void
  loadPointCloud (const std::string& path, pcl::PointCloud<pcl::PointXYZ>& cloud)
  {
    const std::string extension = io_detail::lowerCaseExtension (path);
    if (extension == ".pcd")
    {
      loadPcd (path, cloud);
      return;
    }
    if (!isMeshFileExtension (path))
      throw Error (path + ": unknown point cloud file extension '" + extension + "' (expected .pcd, .ply, .obj, .off or .stl)");
    // The vertices as they are: no faces, no points and NaN points are all fine for a cloud.
    cloud = verticesToCloud (io_detail::readMeshFile (path));
  }

  namespace
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

    /// The PLY file of \a cloud; with \a doubles, x y z are written as double offset + position.
    std::string
    plyText (const pcl::PointCloud<pcl::PointNormal>& cloud, bool binary, bool doubles, const Eigen::Vector3d& offset)
    {
      const std::string xyz_type = doubles ? "double" : "float";
      std::string out = std::string ("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
                        " 1.0\ncomment written by pcl_sparse\nelement vertex " + std::to_string (cloud.size ()) +
                        "\nproperty " + xyz_type + " x\nproperty " + xyz_type + " y\nproperty " + xyz_type +
                        " z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float curvature\nend_header\n";
      out.reserve (out.size () + cloud.size () * (binary ? 40 : 120));
      for (const pcl::PointNormal& point : cloud)
      {
        for (int k = 0; k < 3; ++k)
          if (doubles)
            appendValue (out, offset[k] + static_cast<double> (point.data[k]), binary, ' ');
          else
            appendValue (out, point.data[k], binary, ' ');
        const float rest[4] = {point.normal_x, point.normal_y, point.normal_z, point.curvature};
        for (int k = 0; k < 4; ++k)
          appendValue (out, rest[k], binary, k < 3 ? ' ' : '\n');
      }
      return out;
    }

    /// \a cloud as a PCLPointCloud2 with x y z as FLOAT64 (offset + position), the rest as in PointNormal.
    pcl::PCLPointCloud2
    doublePositionBlob (const pcl::PointCloud<pcl::PointNormal>& cloud, const Eigen::Vector3d& offset)
    {
      pcl::PCLPointCloud2 blob;
      const char* names[7] = {"x", "y", "z", "normal_x", "normal_y", "normal_z", "curvature"};
      std::uint32_t offset_bytes = 0;
      for (int k = 0; k < 7; ++k)
      {
        pcl::PCLPointField field;
        field.name = names[k];
        field.offset = offset_bytes;
        field.datatype = k < 3 ? pcl::PCLPointField::FLOAT64 : pcl::PCLPointField::FLOAT32;
        field.count = 1;
        offset_bytes += k < 3 ? 8 : 4;
        blob.fields.push_back (field);
      }
      blob.point_step = offset_bytes;
      blob.width = static_cast<std::uint32_t> (cloud.size ());
      blob.height = 1;
      blob.row_step = blob.point_step * blob.width;
      blob.is_dense = cloud.is_dense;
      blob.data.resize (static_cast<std::size_t> (blob.row_step));
      std::uint8_t* out = blob.data.data ();
      for (const pcl::PointNormal& point : cloud)
      {
        for (int k = 0; k < 3; ++k, out += 8)
        {
          const double value = offset[k] + static_cast<double> (point.data[k]);
          std::memcpy (out, &value, 8);
        }
        const float rest[4] = {point.normal_x, point.normal_y, point.normal_z, point.curvature};
        std::memcpy (out, rest, sizeof (rest));
        out += sizeof (rest);
      }
      return blob;
    }
  } // namespace

  void
  savePointNormalCloud (const std::string& path, const pcl::PointCloud<pcl::PointNormal>& cloud, bool binary)
  {
    savePointNormalCloud (path, cloud, binary, Eigen::Vector3d::Zero ());
  }

  void
  savePointNormalCloud (const std::string& path, const pcl::PointCloud<pcl::PointNormal>& cloud, bool binary,
                        const Eigen::Vector3d& offset)
  {
    const bool doubles = !offset.isZero (0.0);
    const std::string extension = io_detail::lowerCaseExtension (path);
    if (extension == ".pcd")
    {
      writeFileAtomically (path, [&] (const std::string& temporary) {
        io_detail::QuietPclConsole quiet;
        pcl::PCDWriter writer;
        try
        {
          if (doubles)
          {
            const pcl::PCLPointCloud2 blob = doublePositionBlob (cloud, offset);
            return (binary ? writer.writeBinary (temporary, blob)
                           : writer.writeASCII (temporary, blob, Eigen::Vector4f::Zero (), Eigen::Quaternionf::Identity (), 17)) == 0;
          }
          // 9 significant digits: ascii floats read back exactly.
          return (binary ? writer.writeBinary (temporary, cloud) : writer.writeASCII (temporary, cloud, 9)) == 0;
        }
        catch (const pcl::PCLException&)
        {
          return false;
        }
      });
      return;
    }
    if (extension != ".ply")
      throw Error (path + ": unknown point cloud file extension '" + extension + "' (expected .pcd or .ply)");
    const std::string buffer = plyText (cloud, binary, doubles, offset);
    writeBytesAtomically (path, buffer.data (), buffer.size ());
  }
} // namespace pcl_sparse
