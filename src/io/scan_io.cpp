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
    void
    readPcdScan (const std::string& path, ScanCloud& scan)
    {
      io_detail::PcdBlob blob;
      io_detail::readPcdBlob (path, blob);
      io_detail::pcdScanPoints (blob.cloud, path, scan);
      io_detail::pcdScanLayout (blob.cloud, blob.sensor_origin, blob.sensor_orientation, scan);
    }

    void
    readPlyScan (const std::string& path, ScanCloud& scan)
    {
      io_detail::PlyPoints ply;
      io_detail::readPlyPoints (io_detail::readWholeFile (path), path, io_detail::plyScanProperties (), ply);
      io_detail::plyScanPoints (ply, path, scan);
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
