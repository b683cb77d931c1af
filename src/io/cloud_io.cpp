#include <pcl_sparse/io/cloud_io.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include "cloud_readers.h"
#include "mesh_readers.h"
#include "point_normal_records.h"

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
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
    /// The PLY file of \a cloud; with \a doubles, x y z are written as double offset + position.
    template <typename PointT>
    std::string
    plyText (const pcl::PointCloud<PointT>& cloud, bool binary, bool doubles, const Eigen::Vector3d& offset)
    {
      constexpr CloudExtraField extra = cloudExtraFieldOf<PointT> ();
      std::string out = io_detail::plyHeader (cloud.size (), binary, doubles, extra);
      out.reserve (out.size () + cloud.size () * (binary ? io_detail::binaryRecordSize (doubles, extra, true) : 120));
      for (const PointT& point : cloud)
        io_detail::appendPlyVertex (out, point, binary, doubles, offset);
      return out;
    }

    /// \a cloud as a PCLPointCloud2 with x y z as FLOAT64 (offset + position), the rest as in PointT.
    template <typename PointT>
    pcl::PCLPointCloud2
    doublePositionBlob (const pcl::PointCloud<PointT>& cloud, const Eigen::Vector3d& offset)
    {
      constexpr CloudExtraField extra = cloudExtraFieldOf<PointT> ();
      pcl::PCLPointCloud2 blob = io_detail::doublePositionLayout (cloud.size (), cloud.is_dense, extra);
      blob.data.resize (cloud.size () * io_detail::binaryRecordSize (true, extra));  // row_step is 32-bit
      char* out = reinterpret_cast<char*> (blob.data.data ());
      for (const PointT& point : cloud)
      {
        io_detail::writeBinaryRecord (point, true, offset, out);
        out += io_detail::binaryRecordSize (true, extra);
      }
      return blob;
    }

    /// Whether the ascii PCD file at \a path ends with \a points complete lines after its "DATA ascii" line.
    /// pcl::PCDWriter::writeASCII returns success even when the disk fills up (it never checks its stream).
    bool
    asciiPcdComplete (const std::string& path, std::size_t points)
    {
      std::FILE* file = std::fopen (path.c_str (), "rb");
      if (!file)
        return false;
      // The header PCL writes (a dozen short lines) lies within the first read, or the file is cut short.
      static const std::string marker = "\nDATA ascii\n";
      std::vector<char> buffer (1 << 16);
      std::size_t n = std::fread (buffer.data (), 1, buffer.size (), file);
      const auto data = std::search (buffer.begin (), buffer.begin () + n, marker.begin (), marker.end ());
      if (data == buffer.begin () + n)
      {
        std::fclose (file);
        return false;
      }
      std::size_t lines = 0;
      char last = '\n';
      for (auto begin = data + static_cast<std::ptrdiff_t> (marker.size ()); n > 0; begin = buffer.begin ())
      {
        const auto end = buffer.begin () + static_cast<std::ptrdiff_t> (n);
        lines += static_cast<std::size_t> (std::count (begin, end, '\n'));
        if (begin != end)
          last = end[-1];
        n = std::fread (buffer.data (), 1, buffer.size (), file);
      }
      const bool read_all = !std::ferror (file);
      std::fclose (file);
      return read_all && lines == points && last == '\n';
    }

    /// True if the ascii PCD at \a temporary is complete (asciiPcdComplete); throws, naming \a path and the likely
    /// cause, if it came out short (PCL's writer reports no error, and leaves no errno to name one).
    bool
    requireCompleteAsciiPcd (const std::string& temporary, std::size_t points, const std::string& path)
    {
      if (!asciiPcdComplete (temporary, points))
        throw Error (path + ": could not write the file (it came out short: the disk is full or the file over a "
                            "size limit)");
      return true;
    }
  } // namespace

  template <typename PointT>
  void
  savePointNormalCloud (const std::string& path, const pcl::PointCloud<PointT>& cloud, bool binary)
  {
    savePointNormalCloud (path, cloud, binary, Eigen::Vector3d::Zero ());
  }

  template <typename PointT>
  void
  savePointNormalCloud (const std::string& path, const pcl::PointCloud<PointT>& cloud, bool binary,
                        const Eigen::Vector3d& offset)
  {
    const bool doubles = !offset.isZero (0.0);
    const std::string extension = io_detail::lowerCaseExtension (path);
    // A PCLPointCloud2 counts its bytes in 32 bits (row_step): from 4 GiB (107 million points of 40 bytes)
    // the double-position blob would wrap. The streamed writer (PointNormalStreamWriter) has no such limit.
    if (extension == ".pcd" && doubles &&
        cloud.size () > std::numeric_limits<std::uint32_t>::max () / io_detail::binaryRecordSize (true, cloudExtraFieldOf<PointT> ()))
      throw Error (path + ": " + std::to_string (cloud.size ()) +
                   " points with double positions are more than a PCD written whole holds (4 GiB); write it streamed "
                   "(binary .pcd or .ply)");
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
            if (binary)
              return writer.writeBinary (temporary, blob) == 0;
            return writer.writeASCII (temporary, blob, Eigen::Vector4f::Zero (), Eigen::Quaternionf::Identity (), 17) == 0 &&
                   requireCompleteAsciiPcd (temporary, cloud.size (), path);
          }
          if (binary)
            return writer.writeBinary (temporary, cloud) == 0;
          // 9 significant digits: ascii floats read back exactly.
          return writer.writeASCII (temporary, cloud, 9) == 0 && requireCompleteAsciiPcd (temporary, cloud.size (), path);
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

#define PCL_SPARSE_INSTANTIATE_SAVE_CLOUD(T)                                                                       \
  template void savePointNormalCloud<T> (const std::string&, const pcl::PointCloud<T>&, bool);                   \
  template void savePointNormalCloud<T> (const std::string&, const pcl::PointCloud<T>&, bool, const Eigen::Vector3d&);
  PCL_SPARSE_INSTANTIATE_SAVE_CLOUD (pcl::PointNormal)
  PCL_SPARSE_INSTANTIATE_SAVE_CLOUD (pcl::PointXYZRGBNormal)
  PCL_SPARSE_INSTANTIATE_SAVE_CLOUD (pcl::PointXYZINormal)
#undef PCL_SPARSE_INSTANTIATE_SAVE_CLOUD
} // namespace pcl_sparse
