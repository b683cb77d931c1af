#pragma once
/// \file scan_stream.h
/// Reading a scan file a chunk of points at a time, for files larger than memory (issue 16): the same
/// points, attributes and file indices loadScanCloud reads (before cleaning), in file order, holding one
/// chunk at a time.

#include <pcl_sparse/io/scan_cloud.h>

#include <cstddef>
#include <memory>
#include <string>

namespace pcl_sparse
{
  /// \brief Reads the points of a scan file in chunks, in file order.
  ///
  /// Streamed (memory bounded by the chunk): binary and ascii PCD, binary PLY (little- or big-endian) whose
  /// vertex element comes first. Every other file loadScanCloud reads (binary_compressed PCD, which PCL
  /// compresses as one block; ascii PLY; PLY with a range grid; .xyz .obj .off .stl) is read whole on
  /// construction and then handed out in chunks: same points, but memory grows with the file (isStreamed ()
  /// says which). A streamed file is refused for what loadScanCloud refuses it for, with one exception: the
  /// elements after a PLY file's vertex records (faces) are checked in the header but never read, so damage
  /// inside them goes unnoticed.
  ///
  /// A chunk is a ScanCloud in the file's frame (origin 0) holding the chunk's positions, the attributes
  /// the file has (normals, colours, intensities, viewpoints; as loadScanCloud reads them) and indices (the
  /// position in the file, row * width + column for an organized scan). Nothing is cleaned: NaN points and
  /// points at the sensor come as they are.
  class ScanStreamReader
  {
  public:
    /// Opens \a path and reads its header. Throws pcl_sparse::Error (one line naming the file) for what
    /// loadScanCloud refuses: a missing or empty file, an unknown extension, a bad header, a header whose
    /// counts the file is too short for, no x/y/z, no points.
    explicit ScanStreamReader (const std::string& path);
    ~ScanStreamReader ();
    ScanStreamReader (const ScanStreamReader&) = delete;
    ScanStreamReader& operator= (const ScanStreamReader&) = delete;

    /// What the file says besides the points: fields, width x height, sensor pose (the members of a
    /// ScanCloud other than the per-point vectors, which are empty).
    const ScanCloud&
    layout () const;

    /// Points in the file (width x height).
    std::size_t
    size () const;

    /// False if the file was read whole on construction (a format that cannot be streamed).
    bool
    isStreamed () const;

    /// Reads the next points, at most \a max_points (> 0; fewer for PCD points of over 16 kB), into \a chunk (replacing its points); false,
    /// with \a chunk empty, when every point has been read. Throws pcl_sparse::Error for a truncated file
    /// or bad data.
    bool
    read (ScanCloud& chunk, std::size_t max_points);

    /// Starts again at the first point.
    void
    rewind ();

    /// The path being read.
    const std::string&
    path () const;

    /// One way of reading a format (defined in scan_stream.cpp).
    class Format;

  private:
    std::unique_ptr<Format> format_;
    std::string path_;
  };
} // namespace pcl_sparse
