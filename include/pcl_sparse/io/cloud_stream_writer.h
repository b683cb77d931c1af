#pragma once
/// \file cloud_stream_writer.h
/// Writing a cloud of points with normals block by block (a streamed resampling larger than memory), in
/// the bytes savePointNormalCloud writes for the whole cloud, and atomically.

#include <pcl_sparse/io/cloud_io.h>

#include <Eigen/Core>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <memory>
#include <string>

namespace pcl_sparse
{
  /// \brief Writes a cloud of pcl::PointNormal (or pcl::PointXYZRGBNormal, pcl::PointXYZINormal: the
  /// constructor's extra field) given block by block: binary PCD, binary or ascii PLY, the same bytes as
  /// savePointNormalCloud (path, whole cloud, binary, offset). The point count goes into
  /// the header first, so it must be known before the first block. (With an offset, the PCD ends as
  /// PCL's PCLPointCloud2 writer ends it: in zeros up to a page plus the data.)
  ///
  /// The file is written to a temporary file next to \a path, renamed onto \a path by finish (): a writer
  /// destroyed before finish (an exception, a cancelled run) removes it, so nothing half-written is left.
  /// Blocks are formatted in the calling thread and written by a thread of the writer, one block ahead:
  /// the caller computes the next block while the disk takes the last one, and memory stays two
  /// formatted blocks. On Linux, beyond the first 256 MB of a file, each block's writeback starts as
  /// soon as it is written and the block before leaves the page cache once on the disk, so a huge file
  /// keeps the disk busy and does not fill the page cache.
  ///
  ///   pcl_sparse::PointNormalStreamWriter writer ("out.pcd", total);
  ///   writer.write (block);   // as many times as needed, total points in all
  ///   writer.finish ();
  class PointNormalStreamWriter
  {
  public:
    /// \brief True if the writer can write \a path in that form: .pcd binary, .ply binary or ascii (an
    /// ascii PCD is PCL's text format, written only whole by savePointNormalCloud).
    static bool
    supports (const std::string& path, bool binary);

    /// \brief Opens the temporary file and writes the header.
    /// \param[in] path   the file; its extension chooses the format (supports (path, binary) must hold)
    /// \param[in] total  the number of points that will be written
    /// \param[in] binary binary (default) or ascii (.ply only)
    /// \param[in] offset as in savePointNormalCloud: a non-zero offset writes double x y z = offset + point
    /// \param[in] extra  the field after x y z: the blocks are clouds of the matching point type
    /// \throws pcl_sparse::Error naming \a path for an unsupported form or a file that cannot be created
    PointNormalStreamWriter (const std::string& path, std::size_t total, bool binary = true,
                             const Eigen::Vector3d& offset = Eigen::Vector3d::Zero (),
                             CloudExtraField extra = CloudExtraField::None);
    /// Removes the temporary file unless finish () succeeded.
    ~PointNormalStreamWriter ();
    PointNormalStreamWriter (const PointNormalStreamWriter&) = delete;
    PointNormalStreamWriter& operator= (const PointNormalStreamWriter&) = delete;

    /// \brief Appends the points of \a block (PointT: pcl::PointNormal, pcl::PointXYZRGBNormal or
    /// pcl::PointXYZINormal, the one of the constructor's extra field).
    /// \throws pcl_sparse::Error if a write failed (disk full, ...), more than the total would be written,
    ///         or the point type does not match the extra field
    template <typename PointT>
    void
    write (const pcl::PointCloud<PointT>& block);

    /// \brief Waits for the writes, checks that exactly the total was written, closes the file and renames
    /// it onto the path.
    /// \throws pcl_sparse::Error naming the path on a failed write or a wrong count (the temporary file is
    ///         removed and the path not touched)
    void
    finish ();

    /// \brief Points written so far.
    std::size_t
    written () const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };
} // namespace pcl_sparse
