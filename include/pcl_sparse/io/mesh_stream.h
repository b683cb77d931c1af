#pragma once
/// \file mesh_stream.h
/// Reading a mesh file a chunk at a time, for meshes larger than memory (issue 16): its vertices, then its
/// triangles, as loadTriangleMesh reads them (same values, same fan triangulation, same order).

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief Reads the vertices, then the triangles of a mesh file in chunks, in file order.
  ///
  /// Streamed (memory bounded by the chunk): binary PLY (little- or big-endian) whose vertex element comes
  /// first and face element next, as most writers (and saveTriangleMesh) write them. Any other mesh file
  /// loadTriangleMesh reads (.obj .off .stl, ascii PLY) is read whole on construction (isStreamed () false).
  /// Face indices are checked against the vertex count; NaN/Inf coordinates are given as they are.
  class MeshStreamReader
  {
  public:
    /// Opens \a path and reads its header. Throws pcl_sparse::Error as loadTriangleMesh does for a missing,
    /// empty, garbage or truncated file, and for a file without vertices or faces.
    explicit MeshStreamReader (const std::string& path);
    ~MeshStreamReader ();
    MeshStreamReader (const MeshStreamReader&) = delete;
    MeshStreamReader& operator= (const MeshStreamReader&) = delete;

    /// Vertices in the file.
    std::size_t
    numVertices () const;

    /// False if the file was read whole on construction.
    bool
    isStreamed () const;

    /// Reads the next vertices (at most \a max_vertices > 0) into \a chunk; false, with \a chunk empty,
    /// when all have been read.
    bool
    readVertices (std::vector<Eigen::Vector3d>& chunk, std::size_t max_vertices);

    /// Reads the next triangles (about \a max_triangles > 0: whole faces, fan-triangulated) into \a chunk,
    /// after every vertex has been read; false, with \a chunk empty, when all have been read. Throws
    /// pcl_sparse::Error for a truncated file or a bad face.
    bool
    readTriangles (std::vector<Eigen::Vector3i>& chunk, std::size_t max_triangles);

    /// Starts again at the first vertex.
    void
    rewind ();

    /// One way of reading a format (defined in mesh_stream.cpp).
    class Format;

  private:
    std::unique_ptr<Format> format_;
  };
} // namespace pcl_sparse
