#include <pcl_sparse/io/cloud_io.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include "cloud_readers.h"
#include "mesh_readers.h"

#include <pcl/io/pcd_io.h>

#include <charconv>
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
    std::string
    plyText (const pcl::PointCloud<pcl::PointNormal>& cloud, bool binary)
    {
      std::string out = std::string ("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
                        " 1.0\ncomment written by pcl_sparse\nelement vertex " + std::to_string (cloud.size ()) +
                        "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                        "property float nz\nproperty float curvature\nend_header\n";
      out.reserve (out.size () + cloud.size () * (binary ? 28 : 100));
      for (const pcl::PointNormal& point : cloud)
      {
        const float values[7] = {point.x, point.y, point.z, point.normal_x, point.normal_y, point.normal_z, point.curvature};
        if (binary)
        {
          out.append (reinterpret_cast<const char*> (values), sizeof (values));
          continue;
        }
        for (int k = 0; k < 7; ++k)
        {
          char text[32];
          const auto result = std::to_chars (text, text + sizeof (text), values[k]);
          out.append (text, result.ptr);
          out += k < 6 ? ' ' : '\n';
        }
      }
      return out;
    }
  } // namespace

  void
  savePointNormalCloud (const std::string& path, const pcl::PointCloud<pcl::PointNormal>& cloud, bool binary)
  {
    const std::string extension = io_detail::lowerCaseExtension (path);
    if (extension == ".pcd")
    {
      writeFileAtomically (path, [&] (const std::string& temporary) {
        io_detail::QuietPclConsole quiet;
        pcl::PCDWriter writer;
        try
        {
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
    const std::string buffer = plyText (cloud, binary);
    writeBytesAtomically (path, buffer.data (), buffer.size ());
  }
} // namespace pcl_sparse
