#pragma once
/// \file mesh_io.h
/// Reading and writing triangle meshes: OBJ, OFF, PLY (ascii and binary), STL (ascii and binary).
///
/// Why our own readers and not PCL's (measured with PCL 1.13 on Debian bookworm, bench/results/load.md):
///  - strictness: pcl::io::loadPLYFile and loadOBJFile accept face indices beyond the vertex count,
///    loadPLYFile throws std::bad_alloc on a header announcing 2e9 vertices in a 10-byte body, and the
///    VTK-based pcl::io::loadPolygonFile crashes (SIGSEGV) on an OBJ face "f 1//1" without a "vn" line and
///    drops the unreferenced vertices of OBJ files that have normals; ours refuse each bad file with a
///    one-line message naming the file and the problem;
///  - speed: one read into memory and std::from_chars on the buffer: 5-8x faster than loadPLYFile on the
///    200k-vertex binary PLY and 10-20x faster than loadOBJFile on sword.obj;
///  - formats: PCL has no OFF reader (four of the shared meshes are OFF); we also triangulate polygons
///    and keep every vertex of the file, unreferenced ones too (the counts match the file's);
///  - no heavy PCL/VTK headers in this header (see polygon_mesh_conversion.h for pcl::PolygonMesh).

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Options for loadTriangleMesh.
  struct MeshLoadOptions
  {
    /// Keep vertices with NaN/Inf coordinates instead of refusing the file (default: refuse).
    bool allow_non_finite = false;
    /// Accept a file with vertices but no faces (the result has no triangles). Default: refuse, since
    /// every mesh stage needs triangles.
    bool allow_no_faces = false;
  };

  /// Loads a triangle mesh, dispatching on the extension (.obj .off .ply .stl, any case).
  /// Polygons are fan-triangulated (v0, vi, vi+1). Every vertex of the file is kept, in file order,
  /// unreferenced ones too; binary STL, which has no shared vertices, is welded on exactly equal positions
  /// (in first-appearance order).
  /// \param[in] path     the file
  /// \param[in] options  whether NaN/Inf coordinates and files without faces are accepted
  /// \return the mesh
  /// \throws pcl_sparse::Error with a one-line message naming the file and the problem for: a missing
  ///         file, a directory, an unknown extension, an empty file, binary garbage, a truncated file, a
  ///         header whose counts the file cannot hold, a face index out of range, a face with fewer than
  ///         3 vertices, a NaN/Inf coordinate (unless options.allow_non_finite), no vertices, no faces
  ///         (unless options.allow_no_faces)
  TriangleMesh
  loadTriangleMesh (const std::string& path, const MeshLoadOptions& options = MeshLoadOptions ());

  /// Writes a mesh atomically (writeBytesAtomically) in the format given by the extension:
  /// - .obj, .off: ascii, coordinates with the shortest representation that reads back exactly (double);
  /// - .ply: binary little endian, double coordinates (exact), int32 indices in uchar lists;
  /// - .stl: binary, float coordinates (the format's precision), facet normals computed.
  ///
  /// \param[in] path  the file
  /// \param[in] mesh  the mesh
  /// \throws pcl_sparse::Error on an unknown extension, an invalid face index or a failed write
  void
  saveTriangleMesh (const std::string& path, const TriangleMesh& mesh);

  /// Writes a mesh with one RGB colour per vertex as binary little endian PLY (properties x y z as float,
  /// red green blue as uchar), for viewing keypoint responses, patches and error maps in MeshLab or
  /// CloudCompare. Written atomically.
  /// \param[in] path    the file; must end in .ply
  /// \param[in] mesh    the mesh
  /// \param[in] colors  one colour per vertex (color_map.h)
  /// \throws pcl_sparse::Error on a wrong extension or colour count, an invalid face index or a failed
  ///         write
  void
  saveColoredMesh (const std::string& path, const TriangleMesh& mesh, const std::vector<std::array<std::uint8_t, 3>>& colors);

  /// Whether a path has one of the extensions loadTriangleMesh reads (.obj .off .ply .stl, any case).
  /// \param[in] path  a file name
  /// \return true for a mesh file extension
  bool
  isMeshFileExtension (const std::string& path);
} // namespace pcl_sparse
