#include <pcl_sparse/io/cloud_io.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include "mesh_readers.h"

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <vector>

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

    /// Checks a PCD header before PCL's reader sees the file: pcl::PCDReader (PCL 1.13) crashes on some
    /// garbage files and trusts the counts, so the header must be complete and consistent, x y z must be
    /// fields, and binary data must be as long as the counts say.
    void
    validatePcdHeader (const std::string& path)
    {
      std::FILE* file = std::fopen (path.c_str (), "rb");
      if (!file)
        throw Error (path + ": cannot open the file");
      std::string head (65536, '\0');
      head.resize (std::fread (&head[0], 1, head.size (), file));
      std::fseek (file, 0, SEEK_END);
      const long file_size = std::ftell (file);
      std::fclose (file);

      std::map<std::string, std::vector<std::string>> header;
      std::size_t position = 0;
      std::string data_kind;
      while (data_kind.empty ())
      {
        const std::size_t nl = head.find ('\n', position);
        if (nl == std::string::npos)
          throw Error (path + ": not a PCD file (no complete header with a DATA line)");
        std::istringstream line (head.substr (position, nl - position));
        position = nl + 1;
        std::string keyword;
        if (!(line >> keyword) || keyword[0] == '#')
          continue;
        std::vector<std::string> values;
        for (std::string value; line >> value;)
          values.push_back (value);
        static const std::set<std::string> known = {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT",
                                                    "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
        if (!known.count (keyword))
          throw Error (path + ": not a PCD file (unknown header line)");
        if (keyword == "DATA")
          data_kind = values.empty () ? "?" : values[0];
        header[keyword == "COLUMNS" ? "FIELDS" : keyword] = values;
      }
      const std::vector<std::string>& fields = header["FIELDS"];
      const std::vector<std::string>& sizes = header["SIZE"];
      const std::vector<std::string>& types = header["TYPE"];
      std::vector<std::string> counts = header["COUNT"];
      if (counts.empty ())
        counts.assign (fields.size (), "1");
      if (fields.empty () || sizes.size () != fields.size () || types.size () != fields.size () ||
          counts.size () != fields.size ())
        throw Error (path + ": bad PCD header (FIELDS, SIZE, TYPE, COUNT disagree)");
      const auto number = [&] (const std::string& text, long long max) {
        long long value = -1;
        const auto result = std::from_chars (text.data (), text.data () + text.size (), value);
        if (result.ec != std::errc () || result.ptr != text.data () + text.size () || value < 0 || value > max)
          throw Error (path + ": bad PCD header value '" + text.substr (0, 20) + "'");
        return value;
      };
      long long point_size = 0;
      for (std::size_t i = 0; i < fields.size (); ++i)
      {
        const long long size = number (sizes[i], 8);
        if ((size != 1 && size != 2 && size != 4 && size != 8) ||
            (types[i] != "I" && types[i] != "U" && types[i] != "F"))
          throw Error (path + ": bad PCD field type for '" + fields[i] + "'");
        point_size += size * number (counts[i], 1 << 20);
      }
      for (const char* name : {"x", "y", "z"})
        if (std::find (fields.begin (), fields.end (), name) == fields.end ())
          throw Error (path + ": the PCD file has no x, y, z fields");
      if (header["WIDTH"].size () != 1 || header["HEIGHT"].size () != 1)
        throw Error (path + ": bad PCD header (WIDTH/HEIGHT)");
      const long long points = number (header["WIDTH"][0], 1ll << 32) * number (header["HEIGHT"][0], 1ll << 32);
      if (header.count ("POINTS") && (header["POINTS"].size () != 1 || number (header["POINTS"][0], 1ll << 62) != points))
        throw Error (path + ": bad PCD header (POINTS is not WIDTH * HEIGHT)");
      const long long remaining = file_size - static_cast<long long> (position);
      if (data_kind == "binary")
      {
        if (points > remaining / std::max (1ll, point_size) + 1 || points * point_size > remaining)
          throw Error (path + ": truncated PCD data (" + std::to_string (points) + " points of " +
                       std::to_string (point_size) + " bytes announced, " + std::to_string (remaining) + " bytes left)");
      }
      else if (data_kind == "ascii")
      {
        if (points > remaining)  // every point needs at least one character
          throw Error (path + ": truncated PCD data (" + std::to_string (points) + " points announced)");
      }
      else if (data_kind == "binary_compressed")
      {
        if (remaining < 8)
          throw Error (path + ": truncated PCD data");
      }
      else
        throw Error (path + ": unknown PCD DATA kind '" + data_kind.substr (0, 20) + "'");
    }

    void
    loadPcd (const std::string& path, pcl::PointCloud<pcl::PointXYZ>& cloud)
    {
      io_detail::checkReadableFile (path);
      validatePcdHeader (path);
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
      // Read x, y, z at their own type: pcl::fromPCLPointCloud2 silently leaves fields whose type differs
      // from PointXYZ's (e.g. double x) at zero.
      const std::vector<Eigen::Vector3d> positions = positionsFromCloud (blob, path);
      cloud.clear ();
      cloud.resize (positions.size ());
      bool dense = true;
      for (std::size_t i = 0; i < positions.size (); ++i)
      {
        cloud[i].getVector3fMap () = positions[i].cast<float> ();
        dense = dense && cloud[i].getVector3fMap ().allFinite ();
      }
      cloud.width = blob.width;
      cloud.height = blob.height;
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
        QuietPclConsole quiet;
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
