#include <pcl_sparse/io/scan_io.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include "cloud_readers.h"
#include "mesh_readers.h"
#include "point_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_sparse
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

    void
    readPcdScan (const std::string& path, ScanCloud& scan)
    {
      io_detail::PcdBlob blob;
      io_detail::readPcdBlob (path, blob);
      const pcl::PCLPointCloud2& cloud = blob.cloud;
      scan.positions = positionsFromCloud (cloud, path);  // checks the data length for width x height points
      scan.width = cloud.width;
      scan.height = cloud.height;
      for (const pcl::PCLPointField& field : cloud.fields)
        if (field.name != "_")  // PCL's padding
          scan.fields.push_back (field.name);
      scan.sensor_origin = blob.sensor_origin.head<3> ().cast<double> ();
      scan.sensor_orientation = blob.sensor_orientation.cast<double> ();
      scan.has_sensor_pose = true;

      const std::size_t n = scan.positions.size ();
      const auto point = [&] (std::size_t i) {
        return cloud.data.data () + (i / cloud.width) * cloud.row_step + (i % cloud.width) * cloud.point_step;
      };
      const pcl::PCLPointField* normal[3] = {io_detail::findField (cloud, "normal_x"),
                                             io_detail::findField (cloud, "normal_y"),
                                             io_detail::findField (cloud, "normal_z")};
      if (normal[0] && normal[1] && normal[2])
      {
        scan.normals.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          for (int k = 0; k < 3; ++k)
            scan.normals[i][k] = io_detail::readFieldValue (point (i) + normal[k]->offset, normal[k]->datatype);
      }
      // Colour: PCL packs it in 4 bytes, as "rgba" (TYPE U) or "rgb" (TYPE F); keep the bits as they are.
      const pcl::PCLPointField* color = io_detail::findField (cloud, "rgba");
      if (!color)
        color = io_detail::findField (cloud, "rgb");
      if (color && io_detail::fieldSize (color->datatype) == 4)
      {
        scan.colors.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          std::memcpy (&scan.colors[i], point (i) + color->offset, 4);
      }
      const pcl::PCLPointField* viewpoint[3] = {io_detail::findField (cloud, "vp_x"), io_detail::findField (cloud, "vp_y"),
                                                io_detail::findField (cloud, "vp_z")};
      if (viewpoint[0] && viewpoint[1] && viewpoint[2])
      {
        scan.viewpoints.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          for (int k = 0; k < 3; ++k)
            scan.viewpoints[i][k] = io_detail::readFieldValue (point (i) + viewpoint[k]->offset, viewpoint[k]->datatype);
      }
      if (const pcl::PCLPointField* intensity = io_detail::findField (cloud, "intensity"))
      {
        scan.intensities.resize (n);
        for (std::size_t i = 0; i < n; ++i)
          scan.intensities[i] = static_cast<float> (io_detail::readFieldValue (point (i) + intensity->offset, intensity->datatype));
      }
    }

    void
    readPlyScan (const std::string& path, ScanCloud& scan)
    {
      static const std::vector<std::string> wanted = {"nx",    "ny",    "nz",        "red",
                                                      "green", "blue",  "alpha",     "intensity",
                                                      "scalar_intensity"};
      io_detail::PlyPoints ply;
      io_detail::readPlyPoints (io_detail::readWholeFile (path), path, wanted, ply);
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

    void
    readXyzScan (const std::string& path, ScanCloud& scan)
    {
      io_detail::readXyz (io_detail::readWholeFile (path), path, scan.positions, scan.normals);
      scan.fields = {"x", "y", "z"};
      if (!scan.normals.empty ())
        scan.fields.insert (scan.fields.end (), {"nx", "ny", "nz"});
      if (scan.positions.size () > std::numeric_limits<std::uint32_t>::max ())
        throw Error (path + ": too many points (" + std::to_string (scan.positions.size ()) + ")");
      scan.width = static_cast<std::uint32_t> (scan.positions.size ());
      scan.height = 1;
    }

    void
    readMeshVertices (const std::string& path, ScanCloud& scan)
    {
      scan.positions = io_detail::readMeshFile (path).vertices;
      scan.fields = {"x", "y", "z"};
      scan.width = static_cast<std::uint32_t> (scan.positions.size ());
      scan.height = 1;
    }
  } // namespace

  bool
  isScanFileExtension (const std::string& path)
  {
    const std::string extension = io_detail::lowerCaseExtension (path);
    return extension == ".pcd" || extension == ".xyz" || isMeshFileExtension (path);
  }

  void
  loadScanCloud (const std::string& path, ScanCloud& scan, const ScanLoadOptions& options)
  {
    const std::string extension = io_detail::lowerCaseExtension (path);
    if (!isScanFileExtension (path))
      throw Error (path + ": unknown point cloud file extension '" + extension +
                   "' (expected .pcd, .ply, .xyz, .obj, .off or .stl)");
    ScanCloud loaded;
    if (extension == ".pcd")
      readPcdScan (path, loaded);
    else if (extension == ".ply")
      readPlyScan (path, loaded);
    else if (extension == ".xyz")
      readXyzScan (path, loaded);
    else
      readMeshVertices (path, loaded);
    if (loaded.positions.empty ())
      throw Error (path + ": the file has no points");

    loaded.indices.resize (loaded.positions.size ());
    std::iota (loaded.indices.begin (), loaded.indices.end (), std::size_t (0));
    loaded.report.input_points = loaded.report.kept = loaded.positions.size ();
    // Clean in the file's frame, then centre on what is kept: a "no return" at (0, 0, 0) among map
    // coordinates would otherwise stretch the box, and the frame, over millions of metres.
    if (options.clean)
      cleanScan (loaded, options.cleaning);
    centreScan (loaded);
    scan = std::move (loaded);
  }
} // namespace pcl_sparse
