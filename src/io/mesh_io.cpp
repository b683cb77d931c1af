#include <pcl_sparse/io/mesh_io.h>

#include "mesh_readers.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <sys/stat.h>

namespace pcl_sparse
{
  namespace io_detail
  {
    namespace
    {
      struct stat
      statFile (const std::string& path)
      {
        struct stat info;
        if (::stat (path.c_str (), &info) != 0)
          throw Error (path + ": cannot open the file (" + std::strerror (errno) + ")");
        if (S_ISDIR (info.st_mode))
          throw Error (path + ": is a directory, not a file");
        if (!S_ISREG (info.st_mode))
          throw Error (path + ": is not a regular file");
        return info;
      }
    } // namespace

    void
    checkReadableFile (const std::string& path)
    {
      if (statFile (path).st_size == 0)
        throw Error (path + ": empty file");
    }

    std::string
    readWholeFile (const std::string& path)
    {
      const struct stat info = statFile (path);
      std::FILE* file = std::fopen (path.c_str (), "rb");
      if (!file)
        throw Error (path + ": cannot open the file (" + std::strerror (errno) + ")");
      // One read of the whole file: the readers then scan memory, which is what makes them fast.
      std::string data (static_cast<std::size_t> (info.st_size), '\0');
      const std::size_t read = data.empty () ? 0 : std::fread (&data[0], 1, data.size (), file);
      const bool failed = std::ferror (file) != 0;
      std::fclose (file);
      if (failed)
        throw Error (path + ": read error");
      data.resize (read);
      if (data.empty ())
        throw Error (path + ": empty file");
      return data;
    }

    std::string
    lowerCaseExtension (const std::string& path)
    {
      const std::size_t slash = path.find_last_of ('/');
      const std::size_t dot = path.find_last_of ('.');
      if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return "";
      std::string extension = path.substr (dot);
      for (char& c : extension)
        if (c >= 'A' && c <= 'Z')
          c = static_cast<char> (c - 'A' + 'a');
      return extension;
    }

    void
    requireText (const std::string& data, const std::string& path, const char* format)
    {
      if (std::memchr (data.data (), '\0', data.size ()))
        throw Error (path + ": binary data in what should be an " + format + " text file");
    }
  } // namespace io_detail

  bool
  isMeshFileExtension (const std::string& path)
  {
    const std::string extension = io_detail::lowerCaseExtension (path);
    return extension == ".obj" || extension == ".off" || extension == ".ply" || extension == ".stl";
  }

  TriangleMesh
  io_detail::readMeshFile (const std::string& path)
  {
    const std::string extension = lowerCaseExtension (path);
    if (!isMeshFileExtension (path))
      throw Error (path + ": unknown mesh file extension '" + extension + "' (expected .obj, .off, .ply or .stl)");
    const std::string data = readWholeFile (path);
    TriangleMesh mesh;
    if (extension == ".obj")
      readObj (data, path, mesh);
    else if (extension == ".off")
      readOff (data, path, mesh);
    else if (extension == ".ply")
      readPly (data, path, mesh);
    else
      readStl (data, path, mesh);
    return mesh;
  }

  TriangleMesh
  loadTriangleMesh (const std::string& path, const MeshLoadOptions& options)
  {
    TriangleMesh mesh = io_detail::readMeshFile (path);

    if (mesh.vertices.empty ())
      throw Error (path + ": no vertices");
    if (mesh.triangles.empty () && !options.allow_no_faces)
      throw Error (path + ": no faces (a point cloud, not a mesh)");
    if (!options.allow_non_finite)
      for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
        if (!mesh.vertices[i].allFinite ())
        {
          const Eigen::Vector3d& v = mesh.vertices[i];
          char text[128];
          std::snprintf (text, sizeof (text), "vertex %zu has a non-finite coordinate (%g %g %g; vertices counted from 0)", i, v.x (), v.y (),
                         v.z ());
          throw Error (path + ": " + text);
        }
    return mesh;
  }
} // namespace pcl_sparse
