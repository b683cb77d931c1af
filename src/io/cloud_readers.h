#pragma once
/// \file cloud_readers.h
/// Internal to src/io: the point cloud readers behind loadPointCloud and loadScanCloud (PCD through PCL after
/// our own header check, XYZ text, the vertices and range grid of a PLY file). Like the mesh readers, they
/// throw pcl_sparse::Error with messages that start with the file path.

#include <pcl_sparse/common/error.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>

#include <map>
#include <string>
#include <vector>

namespace pcl_sparse
{
  namespace io_detail
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
      QuietPclConsole (const QuietPclConsole&) = delete;
      QuietPclConsole& operator= (const QuietPclConsole&) = delete;

    private:
      pcl::console::VERBOSITY_LEVEL level_;
    };

    /// Checks a PCD header before PCL's reader sees the file: pcl::PCDReader (PCL 1.13) crashes on some
    /// garbage files and trusts the counts, so the header must be complete and consistent, x y z must be
    /// fields, and binary data must be as long as the counts say.
    void
    validatePcdHeader (const std::string& path);

    /// A PCD file as PCL's reader gives it, after checkReadableFile and validatePcdHeader: the raw blob (any
    /// field types) and the VIEWPOINT pose.
    struct PcdBlob
    {
      pcl::PCLPointCloud2 cloud;
      Eigen::Vector4f sensor_origin = Eigen::Vector4f::Zero ();
      Eigen::Quaternionf sensor_orientation = Eigen::Quaternionf::Identity ();
    };

    /// Reads \a path with pcl::PCDReader after our checks; throws pcl_sparse::Error on any bad file.
    void
    readPcdBlob (const std::string& path, PcdBlob& blob);

    /// An XYZ text file: one point per line, "x y z" or "x y z nx ny nz" (the first point line decides, every
    /// line must then have as many values), blank lines and '#' comments allowed, values in double.
    /// \a normals is left empty for 3-column files.
    void
    readXyz (const std::string& data, const std::string& path, std::vector<Eigen::Vector3d>& positions,
             std::vector<Eigen::Vector3d>& normals);

    /// The vertex element of a PLY file with the scalar properties asked for, the number of faces, and the
    /// Stanford range grid when there is one.
    struct PlyPoints
    {
      std::vector<Eigen::Vector3d> positions;  ///< x y z of every vertex, file order
      std::vector<std::string> vertex_properties;  ///< names of every vertex property, file order
      std::map<std::string, std::vector<double>> values;  ///< asked-for properties present: one value per vertex
      long long num_faces = 0;                 ///< records of the face element (0 if none)
      /// Range grid (element "range_grid", one list "vertex_indices" per cell, row by row): the vertex of each
      /// cell or -1 for an empty cell; empty when the file has none. grid_width x grid_height come from the
      /// "obj_info num_cols" and "obj_info num_rows" header lines.
      std::vector<int> range_grid;
      std::uint32_t grid_width = 0, grid_height = 0;
    };

    /// Reads a PLY file's vertices (every check of the mesh reader applies) with the scalar vertex
    /// properties named in \a wanted, and its range grid. A range grid must have num_cols x num_rows cells,
    /// at most one vertex per cell and each vertex in exactly one cell.
    void
    readPlyPoints (const std::string& data, const std::string& path, const std::vector<std::string>& wanted,
                   PlyPoints& points);
  } // namespace io_detail
} // namespace pcl_sparse
