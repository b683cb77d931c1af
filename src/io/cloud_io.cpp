#include <pcl_sparse/io/cloud_io.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/io/mesh_io.h>

#include "mesh_readers.h"

#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>

#include <charconv>
#include <cstdio>

namespace pcl_sparse
{
  namespace
  {
    /// Silences PCL's console messages while alive: our one-line Error replaces them.
    class QuietPclConsole
    {
    public:
      QuietPclConsole () : level_ (pcl::console::getVerbosityLevel ())
      {
        pcl::console::setVerbosityLevel (pcl::console::L_ALWAYS);
      }
      ~QuietPclConsole () { pcl::console::setVerbosityLevel (level_); }

    private:
      pcl::console::VERBOSITY_LEVEL level_;
    };

    void
    loadPcd (const std::string& path, pcl::PointCloud<pcl::PointXYZ>& cloud)
    {
      io_detail::checkReadableFile (path);
      pcl::PCLPointCloud2 blob;
      {
        QuietPclConsole quiet;
        pcl::PCDReader reader;
        int result = -1;
        try
        {
          result = reader.read (path, blob);
        }
        catch (const pcl::PCLException&)
        {
        }
        if (result < 0)
          throw Error (path + ": not a readable PCD file (bad header or truncated data)");
      }
      int found = 0;
      for (const pcl::PCLPointField& field : blob.fields)
        found += field.name == "x" || field.name == "y" || field.name == "z";
      if (found != 3)
        throw Error (path + ": the PCD file has no x, y, z fields");
      if (static_cast<std::size_t> (blob.row_step) * blob.height > blob.data.size ())
        throw Error (path + ": truncated PCD data");
      QuietPclConsole quiet;
      pcl::fromPCLPointCloud2 (blob, cloud);
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
    MeshLoadOptions options;
    options.allow_no_faces = true;
    options.allow_non_finite = true;
    const TriangleMesh mesh = loadTriangleMesh (path, options);
    cloud.clear ();
    cloud.resize (mesh.vertices.size ());
    bool dense = true;
    for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
    {
      cloud[i].getVector3fMap () = mesh.vertices[i].cast<float> ();
      dense = dense && mesh.vertices[i].allFinite ();
    }
    cloud.width = static_cast<std::uint32_t> (cloud.size ());
    cloud.height = 1;
    cloud.is_dense = dense;
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
        QuietPclConsole quiet;
        pcl::PCDWriter writer;
        try
        {
          return (binary ? writer.writeBinary (temporary, cloud) : writer.writeASCII (temporary, cloud)) == 0;
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
    writeFileAtomically (path, [&buffer] (const std::string& temporary) {
      std::FILE* file = std::fopen (temporary.c_str (), "wb");
      if (!file)
        return false;
      const bool written = std::fwrite (buffer.data (), 1, buffer.size (), file) == buffer.size ();
      return std::fclose (file) == 0 && written;
    });
  }
} // namespace pcl_sparse
