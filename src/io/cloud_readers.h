#pragma once
/// \file cloud_readers.h
/// Internal to src/io: the point cloud readers behind loadPointCloud and loadScanCloud (PCD through PCL after
/// our own header check, XYZ text, the vertices and range grid of a PLY file). Like the mesh readers, they
/// throw pcl_sparse::Error with messages that start with the file path.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>

#include <map>
#include <memory>
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

    /// A PCD header, as readPcdHeader checks it and PCL's reader would lay out the points.
    struct PcdHeader
    {
      pcl::PCLPointCloud2 layout;  ///< fields (offset, datatype, count), point_step, row_step, width, height; no data
      std::string data_kind;       ///< "ascii", "binary" or "binary_compressed"
      std::size_t data_offset = 0; ///< bytes before the data (just after the DATA line)
      Eigen::Vector4f sensor_origin = Eigen::Vector4f::Zero ();              ///< VIEWPOINT origin
      Eigen::Quaternionf sensor_orientation = Eigen::Quaternionf::Identity ();  ///< VIEWPOINT orientation
    };

    /// Checks a PCD header before the data is read: pcl::PCDReader (PCL 1.13) crashes on some garbage files
    /// and trusts the counts, so the header must be complete and consistent, x y z must be fields, and
    /// binary data must be as long as the counts say. Returns the header it checked.
    PcdHeader
    readPcdHeader (const std::string& path);

    /// Checks the lines of DATA ascii (\a header from readPcdHeader) before PCL's ascii parser reads them: one
    /// number per field and element on each non-empty line, up to WIDTH x HEIGHT points (PCL skips other lines
    /// in silence and gives zeros for the points it did not find).
    void
    checkPcdAsciiData (const std::string& path, const PcdHeader& header);

    /// A PCD file as PCL's reader gives it, after checkReadableFile and readPcdHeader: the raw blob (any
    /// field types) and the VIEWPOINT pose.
    struct PcdBlob
    {
      pcl::PCLPointCloud2 cloud;
      Eigen::Vector4f sensor_origin = Eigen::Vector4f::Zero ();
      Eigen::Quaternionf sensor_orientation = Eigen::Quaternionf::Identity ();
    };

    /// Reads \a path after our header check: DATA binary ourselves at the header's layout, ascii and
    /// binary_compressed with pcl::PCDReader unless it would take the data's first line for a header line;
    /// throws pcl_sparse::Error on any bad file.
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

    /// The vertex records of a PLY file, for reading a large file a chunk at a time: parses the header and
    /// decodes chunks of records with the same reader as readPlyPoints.
    class PlyVertexRecords
    {
    public:
      /// Parses the header in \a head (the file's first bytes, at least up to end_header); throws as the
      /// whole-file reader does for a bad header.
      PlyVertexRecords (const std::string& head, const std::string& path);

      /// True if the vertex records can be read in chunks: a binary file whose vertex element is the first
      /// with data and has no list property, and no range_grid element (whose cell order is the scan's).
      bool
      streamable () const;
      /// Bytes before the first vertex record.
      std::size_t
      bodyOffset () const;
      /// Bytes of one vertex record.
      std::size_t
      recordBytes () const;
      /// Vertex records the header announces (0 when not streamable).
      long long
      count () const;
      /// Decodes whole records (a multiple of recordBytes ()) into \a points: positions, vertex_properties
      /// and the scalar properties named in \a wanted.
      void
      decode (const std::string& records, const std::vector<std::string>& wanted, PlyPoints& points) const;

    private:
      struct Layout;
      std::shared_ptr<const Layout> layout_;
      std::string path_;
    };

    /// The face records of a binary PLY mesh, for reading a large file a chunk at a time after its vertex
    /// records (PlyVertexRecords); decoded with the same reader as readPly.
    class PlyFaceRecords
    {
    public:
      /// Parses the header in \a head (the file's first bytes, at least up to end_header).
      PlyFaceRecords (const std::string& head, const std::string& path);

      /// True if the faces can be read in chunks: a binary file whose vertex element comes first with
      /// fixed-size records and whose face element comes next (elements without bytes may sit between).
      bool
      streamable () const;
      /// Bytes before the first face record.
      std::size_t
      bodyOffset () const;
      /// Face records the header announces (0 when not streamable).
      long long
      count () const;
      /// Decodes the complete face records at the start of \a data (at most \a max_records),
      /// fan-triangulated, appending to \a triangles (indices checked against the header's vertex count);
      /// \a records gets their number. Returns the bytes they take. \a next_record_bytes, if given, gets the
      /// least number of bytes the record after them takes, as far as the list sizes in \a data tell (0 when
      /// \a max_records were decoded): a reader can refuse a list size the rest of the file cannot hold.
      std::size_t
      decode (const std::string& data, long long max_records, std::vector<Eigen::Vector3i>& triangles,
              long long& records, std::size_t* next_record_bytes = nullptr) const;
      /// After the last face record: throws unless \a rest, the bytes that follow it, are padding (zero bytes
      /// or white space) or the file announces more elements after the faces.
      void
      checkEnd (const std::string& rest) const;

    private:
      struct Layout;
      std::shared_ptr<const Layout> layout_;
      std::string path_;
    };

    /// The points of \a cloud (width x height, decoded PCD records) into \a scan: positions, and normals
    /// (normal_x/y/z), colours (rgba or rgb), viewpoints (vp_x/y/z) and intensities where the fields exist;
    /// other members of \a scan are left as they are. Throws if x y z are missing or the data is short.
    void
    pcdScanPoints (const pcl::PCLPointCloud2& cloud, const std::string& path, ScanCloud& scan);

    /// What a PCD file says about its scan besides the points: width x height, the fields (without PCL's
    /// "_" padding) and the VIEWPOINT pose.
    void
    pcdScanLayout (const pcl::PCLPointCloud2& cloud, const Eigen::Vector4f& sensor_origin,
                   const Eigen::Quaternionf& sensor_orientation, ScanCloud& scan);

    /// The vertex properties a scan takes from a PLY file besides x y z (normals, colours, intensity).
    const std::vector<std::string>&
    plyScanProperties ();

    /// The points of \a ply (read with plyScanProperties) into \a scan: positions, normals, colours,
    /// intensities, fields, and width x height (the range grid's, whose empty cells become NaN points; the
    /// grid is moved out of \a ply). Other members of \a scan are left as they are.
    void
    plyScanPoints (PlyPoints& ply, const std::string& path, ScanCloud& scan);
  } // namespace io_detail
} // namespace pcl_sparse
