#pragma once
/// \file cloud_readers.h
/// Internal to src/io: the point cloud readers behind loadPointCloud (PCD through PCL after our own header
/// check). Like the mesh readers, they throw pcl_sparse::Error with messages that start with the file path.

#include <pcl_sparse/common/error.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>

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
  } // namespace io_detail
} // namespace pcl_sparse
