/// Object File Format: a header keyword ([ST][C][N]OFF), optionally followed on the same line by the counts
/// "nv nf ne"; vertex lines "x y z [extra columns: normal, colour, texture]"; face lines "n i0 .. in-1
/// [colour]"; '#' comments anywhere. Polygons are fan-triangulated. Binary OFF and 4D/nD OFF are refused.

#include "mesh_readers.h"

#include <vector>

namespace pcl_sparse
{
  namespace io_detail
  {
    namespace
    {
      /// True for OFF, COFF, NOFF, CNOFF, STOFF, STCOFF, STNOFF, STCNOFF.
      bool
      isOffKeyword (std::string keyword)
      {
        if (keyword.size () < 3 || keyword.compare (keyword.size () - 3, 3, "OFF") != 0)
          return false;
        keyword.resize (keyword.size () - 3);
        if (keyword.compare (0, 2, "ST") == 0)
          keyword.erase (0, 2);
        if (!keyword.empty () && keyword[0] == 'C')
          keyword.erase (0, 1);
        if (!keyword.empty () && keyword[0] == 'N')
          keyword.erase (0, 1);
        return keyword.empty ();
      }

      std::string
      readWord (TextCursor& cursor)
      {
        const char* start = cursor.p;
        while (cursor.p < cursor.end && !cursor.atDelimiter ())
          ++cursor.p;
        return std::string (start, cursor.p);
      }

      long long
      readCount (TextCursor& cursor, const std::string& path, const char* what)
      {
        long long value;
        if (!cursor.skipToToken ())
          throw Error (path + ": truncated OFF header (no " + what + ")");
        if (!cursor.parseInteger (value) || !cursor.atDelimiter () || value < 0)
          throw Error (atLine (path, cursor.line, std::string ("bad ") + what + " " + cursor.tokenForMessage ()));
        return value;
      }
    } // namespace

    void
    readOff (const std::string& data, const std::string& path, TriangleMesh& mesh)
    {
      requireText (data, path, "OFF");
      TextCursor cursor (data);
      if (!cursor.skipToToken ())
        throw Error (path + ": no OFF header");
      const std::string keyword = readWord (cursor);
      if (!isOffKeyword (keyword))
      {
        if (keyword.size () >= 3 && keyword.compare (keyword.size () - 3, 3, "OFF") == 0)
          throw Error (atLine (path, cursor.line, "unsupported OFF variant '" + keyword + "' (only 3D OFF is read)"));
        throw Error (atLine (path, cursor.line, "not an OFF file (the first word is not OFF)"));
      }
      if (!cursor.atLineEnd ())
      {
        const char* save = cursor.p;
        if (readWord (cursor) == "BINARY")
          throw Error (atLine (path, cursor.line, "binary OFF is not supported"));
        cursor.p = save;
      }

      const long long num_vertices = readCount (cursor, path, "vertex count");
      const long long num_faces = readCount (cursor, path, "face count");
      // The edge count is optional in practice; whatever else is on the counts line is ignored.
      cursor.skipLine ();

      // A lying header must not make us allocate: a vertex needs at least "0 0 0\n", a face at least two
      // bytes (a looser bound than a valid face, so that a malformed face gets its own message).
      const long long remaining = static_cast<long long> (cursor.end - cursor.p);
      if (num_vertices > std::numeric_limits<int>::max () || num_faces > std::numeric_limits<int>::max () ||
          num_vertices * 6 + num_faces * 2 > remaining + 1)
        throw Error (path + ": the header announces " + std::to_string (num_vertices) + " vertices and " +
                     std::to_string (num_faces) + " faces, more than the file's " + std::to_string (remaining) +
                     " remaining bytes can hold");

      mesh.vertices.resize (static_cast<std::size_t> (num_vertices));
      for (long long i = 0; i < num_vertices; ++i)
      {
        Eigen::Vector3d& v = mesh.vertices[static_cast<std::size_t> (i)];
        for (int k = 0; k < 3; ++k)
        {
          if (!cursor.skipToToken ())
            throw Error (path + ": truncated: the file ends in vertex " + std::to_string (i) + " of " +
                         std::to_string (num_vertices));
          if (!cursor.parseDouble (v[k]) || !cursor.atDelimiter ())
            throw Error (atLine (path, cursor.line, "bad vertex coordinate " + cursor.tokenForMessage ()));
        }
        cursor.skipLine ();  // normals, colours, texture coordinates
      }

      // Reserve only what full triangle lines ("3 0 1 2\n") in the remaining bytes could need.
      mesh.triangles.reserve (static_cast<std::size_t> (std::min<long long> (num_faces, (cursor.end - cursor.p) / 8 + 1)));
      std::vector<int> polygon;
      for (long long f = 0; f < num_faces; ++f)
      {
        if (!cursor.skipToToken ())
          throw Error (path + ": truncated: the file ends before face " + std::to_string (f) + " of " +
                       std::to_string (num_faces));
        long long size;
        if (!cursor.parseInteger (size) || !cursor.atDelimiter ())
          throw Error (atLine (path, cursor.line, "bad face size " + cursor.tokenForMessage ()));
        if (size < 3 || size > cursor.end - cursor.p)
          throw Error (atLine (path, cursor.line, "face with " + std::to_string (size) + " vertices"));
        polygon.clear ();
        for (long long k = 0; k < size; ++k)
        {
          long long index;
          if (!cursor.skipToToken ())
            throw Error (path + ": truncated: the file ends in face " + std::to_string (f));
          if (!cursor.parseInteger (index) || !cursor.atDelimiter ())
            throw Error (atLine (path, cursor.line, "bad face index " + cursor.tokenForMessage ()));
          if (index < 0 || index >= num_vertices)
            throw Error (atLine (path, cursor.line, "face index " + std::to_string (index) + " is out of range (the file has " +
                                                        std::to_string (num_vertices) + " vertices)"));
          polygon.push_back (static_cast<int> (index));
        }
        for (std::size_t i = 1; i + 1 < polygon.size (); ++i)
          mesh.triangles.emplace_back (polygon[0], polygon[i], polygon[i + 1]);
        cursor.skipLine ();  // face colour
      }
      // A header announcing fewer faces than follow dropped the last ones silently.
      if (cursor.skipToToken ())
        throw Error (atLine (path, cursor.line, "data after the " + std::to_string (num_faces) +
                                                    " faces the header announces (a wrong face count?)"));
    }
  } // namespace io_detail
} // namespace pcl_sparse
