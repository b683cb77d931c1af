/// The points of a scan from decoded PCD or PLY records: positions and the attributes loadScanCloud keeps
/// (normals, colours, intensities, viewpoints). Shared by the whole-file readers (scan_io.cpp) and the
/// streaming reader (scan_stream.cpp), so that both give the same values for the same file.

#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include "cloud_readers.h"
#include "point_fields.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace pcl_sparse
{
  namespace io_detail
  {
    namespace
    {
      constexpr double kNaN = std::numeric_limits<double>::quiet_NaN ();

      /// PCL's rgba packing, 0xAARRGGBB, from channel values (clamped to 0..255).
      std::uint32_t
      packColor (double r, double g, double b, double a)
      {
        const auto channel = [] (double v) {
          return static_cast<std::uint32_t> (std::isfinite (v) ? std::clamp (std::round (v), 0.0, 255.0) : 0.0);
        };
        return channel (a) << 24 | channel (r) << 16 | channel (g) << 8 | channel (b);
      }
    } // namespace

    void
    pcdScanPoints (const pcl::PCLPointCloud2& cloud, const std::string& path, ScanCloud& scan)
    {
      scan.positions = positionsFromCloud (cloud, path);  // checks the data length for width x height points
      scan.normals.clear ();
      scan.colors.clear ();
      scan.viewpoints.clear ();
      scan.intensities.clear ();
      const std::size_t n = scan.positions.size ();
      const auto point = [&] (std::size_t i) {
        return cloud.data.data () + (i / cloud.width) * cloud.row_step + (i % cloud.width) * cloud.point_step;
      };
      // Three fields read as one vector per point (normals, viewpoints), when all three exist.
      const auto readVectors = [&] (const char* x, const char* y, const char* z, std::vector<Eigen::Vector3d>& out) {
        const pcl::PCLPointField* field[3] = {findField (cloud, x), findField (cloud, y), findField (cloud, z)};
        if (!field[0] || !field[1] || !field[2])
          return;
        out.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          for (int k = 0; k < 3; ++k)
            out[i][k] = readFieldValue (point (i) + field[k]->offset, field[k]->datatype);
      };
      readVectors ("normal_x", "normal_y", "normal_z", scan.normals);
      readVectors ("vp_x", "vp_y", "vp_z", scan.viewpoints);
      // Colour: PCL packs it in 4 bytes, as "rgba" (TYPE U) or "rgb" (TYPE F); keep the bits as they are.
      const pcl::PCLPointField* color = findField (cloud, "rgba");
      if (!color)
        color = findField (cloud, "rgb");
      if (color && fieldSize (color->datatype) == 4)
      {
        scan.colors.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          std::memcpy (&scan.colors[i], point (i) + color->offset, 4);
      }
      if (const pcl::PCLPointField* intensity = findField (cloud, "intensity"))
      {
        scan.intensities.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          scan.intensities[i] = static_cast<float> (readFieldValue (point (i) + intensity->offset, intensity->datatype));
      }
    }

    void
    pcdScanLayout (const pcl::PCLPointCloud2& cloud, const Eigen::Vector4f& sensor_origin,
                   const Eigen::Quaternionf& sensor_orientation, ScanCloud& scan)
    {
      scan.width = cloud.width;
      scan.height = cloud.height;
      scan.fields.clear ();
      for (const pcl::PCLPointField& field : cloud.fields)
        if (field.name != "_")  // PCL's padding
          scan.fields.push_back (field.name);
      scan.sensor_origin = sensor_origin.head<3> ().cast<double> ();
      scan.sensor_orientation = sensor_orientation.cast<double> ();
      scan.has_sensor_pose = true;
    }

    const std::vector<std::string>&
    plyScanProperties ()
    {
      static const std::vector<std::string> wanted = {"nx",    "ny",    "nz",        "red",
                                                      "green", "blue",  "alpha",     "intensity",
                                                      "scalar_intensity"};
      return wanted;
    }

    void
    plyScanPoints (PlyPoints& ply, const std::string& path, ScanCloud& scan)
    {
      scan.normals.clear ();
      scan.colors.clear ();
      scan.viewpoints.clear ();
      scan.intensities.clear ();
      scan.fields = ply.vertex_properties;
      const auto column = [&] (const char* name) -> const std::vector<double>* {
        const auto found = ply.values.find (name);
        return found == ply.values.end () ? nullptr : &found->second;
      };
      const std::vector<double>*nx = column ("nx"), *ny = column ("ny"), *nz = column ("nz");
      const std::vector<double>*red = column ("red"), *green = column ("green"), *blue = column ("blue");
      const std::vector<double>* alpha = column ("alpha");
      const std::vector<double>* intensity = column ("intensity");
      if (!intensity)
        intensity = column ("scalar_intensity");

      // Grid cell -> vertex (identity without a range grid); -1 is an empty cell, a NaN point.
      std::vector<int> vertex_of = std::move (ply.range_grid);
      if (vertex_of.empty ())
      {
        if (ply.positions.size () > std::numeric_limits<std::uint32_t>::max ())
          throw Error (path + ": too many points (" + std::to_string (ply.positions.size ()) + ")");
        vertex_of.resize (ply.positions.size ());
        std::iota (vertex_of.begin (), vertex_of.end (), 0);
        scan.width = static_cast<std::uint32_t> (vertex_of.size ());
        scan.height = 1;
      }
      else
      {
        scan.width = ply.grid_width;
        scan.height = ply.grid_height;
      }
      const std::size_t n = vertex_of.size ();
      scan.positions.resize (n);
      if (nx && ny && nz)
        scan.normals.resize (n);
      if (red && green && blue)
        scan.colors.resize (n);
      if (intensity)
        scan.intensities.resize (n);
      for (std::size_t i = 0; i < n; ++i)
      {
        const int v = vertex_of[i];
        if (v < 0)
        {
          scan.positions[i].setConstant (kNaN);
          if (!scan.normals.empty ())
            scan.normals[i].setConstant (kNaN);
          if (!scan.colors.empty ())
            scan.colors[i] = 0;
          if (!scan.intensities.empty ())
            scan.intensities[i] = static_cast<float> (kNaN);
          continue;
        }
        const std::size_t j = static_cast<std::size_t> (v);
        scan.positions[i] = ply.positions[j];
        if (!scan.normals.empty ())
          scan.normals[i] = Eigen::Vector3d ((*nx)[j], (*ny)[j], (*nz)[j]);
        if (!scan.colors.empty ())
          scan.colors[i] = packColor ((*red)[j], (*green)[j], (*blue)[j], alpha ? (*alpha)[j] : 255.0);
        if (!scan.intensities.empty ())
          scan.intensities[i] = static_cast<float> ((*intensity)[j]);
      }
    }
  } // namespace io_detail
} // namespace pcl_sparse
