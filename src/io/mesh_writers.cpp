/// Mesh writers: OBJ and OFF with exact (shortest round-trip) decimal coordinates, binary little-endian PLY
/// with double coordinates, binary STL (float, the format's only precision), and PLY with vertex colours.
/// Each file is built in memory and written once through writeBytesAtomically.

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/io/mesh_io.h>

#include "mesh_readers.h"

#include <Eigen/Geometry>

#include <charconv>

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the binary PLY/STL readers and writers assume a little-endian host"
#endif

namespace pcl_sparse
{
  namespace
  {
    void
    checkIndices (const std::string& path, const TriangleMesh& mesh)
    {
      const int num_vertices = static_cast<int> (mesh.vertices.size ());
      for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
        for (int k = 0; k < 3; ++k)
          if (mesh.triangles[f][k] < 0 || mesh.triangles[f][k] >= num_vertices)
            throw Error (path + ": cannot write: triangle " + std::to_string (f) + " has vertex index " +
                         std::to_string (mesh.triangles[f][k]) + " out of range (" + std::to_string (num_vertices) +
                         " vertices)");
    }

    /// Appends the shortest decimal text that reads back as exactly \a value.
    void
    appendNumber (std::string& out, double value)
    {
      char text[32];
      const auto result = std::to_chars (text, text + sizeof (text), value);
      out.append (text, result.ptr);
    }

    void
    appendNumber (std::string& out, long long value)
    {
      char text[24];
      const auto result = std::to_chars (text, text + sizeof (text), value);
      out.append (text, result.ptr);
    }

    /// "x y z\n" at full double precision (shortest round-trip form).
    void
    appendCoordinates (std::string& out, const Eigen::Vector3d& v)
    {
      appendNumber (out, v.x ());
      out += ' ';
      appendNumber (out, v.y ());
      out += ' ';
      appendNumber (out, v.z ());
      out += '\n';
    }

    /// " a b c" with the indices shifted by \a base (OBJ counts from 1).
    void
    appendIndices (std::string& out, const Eigen::Vector3i& t, long long base)
    {
      for (int k = 0; k < 3; ++k)
      {
        out += ' ';
        appendNumber (out, static_cast<long long> (t[k]) + base);
      }
    }

    template <typename T>
    void
    appendBinary (std::string& out, const T& value)
    {
      out.append (reinterpret_cast<const char*> (&value), sizeof (T));
    }

    std::string
    objText (const TriangleMesh& mesh)
    {
      std::string out;
      out.reserve (mesh.vertices.size () * 40 + mesh.triangles.size () * 24 + 64);
      out += "# written by pcl_sparse\n";
      for (const Eigen::Vector3d& v : mesh.vertices)
      {
        out += "v ";
        appendCoordinates (out, v);
      }
      for (const Eigen::Vector3i& t : mesh.triangles)
      {
        out += 'f';
        appendIndices (out, t, 1);
        out += '\n';
      }
      return out;
    }

    std::string
    offText (const TriangleMesh& mesh)
    {
      std::string out;
      out.reserve (mesh.vertices.size () * 40 + mesh.triangles.size () * 24 + 64);
      out += "OFF\n";
      appendNumber (out, static_cast<long long> (mesh.vertices.size ()));
      out += ' ';
      appendNumber (out, static_cast<long long> (mesh.triangles.size ()));
      out += " 0\n";
      for (const Eigen::Vector3d& v : mesh.vertices)
        appendCoordinates (out, v);
      for (const Eigen::Vector3i& t : mesh.triangles)
      {
        out += '3';
        appendIndices (out, t, 0);
        out += '\n';
      }
      return out;
    }

    std::string
    plyHeader (std::size_t num_vertices, std::size_t num_faces, const char* vertex_properties)
    {
      return std::string ("ply\nformat binary_little_endian 1.0\ncomment written by pcl_sparse\nelement vertex ") +
             std::to_string (num_vertices) + "\n" + vertex_properties + "element face " + std::to_string (num_faces) +
             "\nproperty list uchar int vertex_indices\nend_header\n";
    }

    void
    appendPlyFaces (std::string& out, const TriangleMesh& mesh)
    {
      for (const Eigen::Vector3i& t : mesh.triangles)
      {
        appendBinary (out, static_cast<std::uint8_t> (3));
        for (int k = 0; k < 3; ++k)
          appendBinary (out, static_cast<std::int32_t> (t[k]));
      }
    }

    std::string
    plyBinary (const TriangleMesh& mesh)
    {
      std::string out = plyHeader (mesh.vertices.size (), mesh.triangles.size (),
                                   "property double x\nproperty double y\nproperty double z\n");
      out.reserve (out.size () + mesh.vertices.size () * 24 + mesh.triangles.size () * 13);
      for (const Eigen::Vector3d& v : mesh.vertices)
        for (int k = 0; k < 3; ++k)
          appendBinary (out, v[k]);
      appendPlyFaces (out, mesh);
      return out;
    }

    std::string
    stlBinary (const TriangleMesh& mesh)
    {
      std::string out (80, ' ');
      out.replace (0, 22, "binary STL, pcl_sparse");
      out.reserve (84 + 50 * mesh.triangles.size ());
      appendBinary (out, static_cast<std::uint32_t> (mesh.triangles.size ()));
      for (const Eigen::Vector3i& t : mesh.triangles)
      {
        const Eigen::Vector3d& a = mesh.vertices[t[0]];
        const Eigen::Vector3d& b = mesh.vertices[t[1]];
        const Eigen::Vector3d& c = mesh.vertices[t[2]];
        Eigen::Vector3d normal = (b - a).cross (c - a);
        const double length = normal.norm ();
        normal = length > 0.0 ? Eigen::Vector3d (normal / length) : Eigen::Vector3d::Zero ();
        for (int k = 0; k < 3; ++k)
          appendBinary (out, static_cast<float> (normal[k]));
        for (const Eigen::Vector3d* corner : {&a, &b, &c})
          for (int k = 0; k < 3; ++k)
            appendBinary (out, static_cast<float> ((*corner)[k]));
        appendBinary (out, static_cast<std::uint16_t> (0));
      }
      return out;
    }
  } // namespace

  void
  saveTriangleMesh (const std::string& path, const TriangleMesh& mesh)
  {
    const std::string extension = io_detail::lowerCaseExtension (path);
    if (!isMeshFileExtension (path))
      throw Error (path + ": unknown mesh file extension '" + extension + "' (expected .obj, .off, .ply or .stl)");
    checkIndices (path, mesh);
    const std::string buffer = extension == ".obj"   ? objText (mesh)
                               : extension == ".off" ? offText (mesh)
                               : extension == ".ply" ? plyBinary (mesh)
                                                     : stlBinary (mesh);
    writeBytesAtomically (path, buffer.data (), buffer.size ());
  }

  void
  saveColoredMesh (const std::string& path, const TriangleMesh& mesh, const std::vector<std::array<std::uint8_t, 3>>& colors)
  {
    if (io_detail::lowerCaseExtension (path) != ".ply")
      throw Error (path + ": coloured meshes are written as PLY: the file name must end in .ply");
    if (colors.size () != mesh.vertices.size ())
      throw Error (path + ": " + std::to_string (colors.size ()) + " colours for " +
                   std::to_string (mesh.vertices.size ()) + " vertices");
    checkIndices (path, mesh);
    std::string out = plyHeader (mesh.vertices.size (), mesh.triangles.size (),
                                 "property float x\nproperty float y\nproperty float z\n"
                                 "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    out.reserve (out.size () + mesh.vertices.size () * 15 + mesh.triangles.size () * 13);
    for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
    {
      for (int k = 0; k < 3; ++k)
        appendBinary (out, static_cast<float> (mesh.vertices[i][k]));
      out.append (reinterpret_cast<const char*> (colors[i].data ()), 3);
    }
    appendPlyFaces (out, mesh);
    writeBytesAtomically (path, out.data (), out.size ());
  }
} // namespace pcl_sparse
