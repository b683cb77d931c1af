/// Wavefront OBJ: "v x y z [w] [r g b]" vertices, faces "f a", "f a/b", "f a/b/c", "f a//c" with 1-based or
/// negative (relative) indices; polygons fan-triangulated; vt/vn, groups, materials, other statements and
/// comments skipped. Lines may end in CRLF.

#include "mesh_readers.h"

#include <limits>
#include <vector>

namespace pcl_sparse
{
  namespace io_detail
  {
    namespace
    {
      /// A statement keyword is letters, digits and '_' starting with a letter; anything else at the start of
      /// a line means this is not OBJ text.
      bool
      isKeywordStart (char c)
      {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
      }
    } // namespace

    void
    readObj (const std::string& data, const std::string& path, TriangleMesh& mesh)
    {
      requireText (data, path, "OBJ");
      TextCursor cursor (data);

      std::vector<int> polygon;
      // Positive indices may refer to vertices defined later in the file: remember the largest one and check
      // it at the end.
      long long max_index = -1;
      std::size_t max_index_line = 0;

      while (cursor.p < cursor.end)
      {
        cursor.skipBlanks ();
        if (cursor.atLineEnd ())
        {
          cursor.skipLine ();
          continue;
        }
        const char* keyword = cursor.p;
        if (!isKeywordStart (*keyword))
          throw Error (atLine (path, cursor.line, "not an OBJ statement: " + cursor.tokenForMessage ()));
        while (cursor.p < cursor.end && !cursor.atDelimiter ())
          ++cursor.p;
        const std::size_t keyword_length = static_cast<std::size_t> (cursor.p - keyword);

        if (keyword_length == 1 && keyword[0] == 'v')
        {
          Eigen::Vector3d v;
          for (int k = 0; k < 3; ++k)
          {
            cursor.skipBlanks ();
            if (!cursor.parseDouble (v[k]) || !cursor.atDelimiter ())
              throw Error (atLine (path, cursor.line, "bad vertex coordinate " + cursor.tokenForMessage ()));
          }
          if (mesh.vertices.size () >= static_cast<std::size_t> (std::numeric_limits<int>::max ()))
            throw Error (atLine (path, cursor.line, "too many vertices"));
          mesh.vertices.push_back (v);
        }
        else if (keyword_length == 1 && keyword[0] == 'f')
        {
          polygon.clear ();
          while (!cursor.atLineEnd ())
          {
            long long index;
            if (!cursor.parseInteger (index))
              throw Error (atLine (path, cursor.line, "bad face index " + cursor.tokenForMessage ()));
            // Texture and normal indices after '/' are not needed: skip the rest of the token.
            if (cursor.p < cursor.end && *cursor.p == '/')
              while (cursor.p < cursor.end && !cursor.atDelimiter ())
                ++cursor.p;
            else if (!cursor.atDelimiter ())
              throw Error (atLine (path, cursor.line, "bad face index " + cursor.tokenForMessage ()));
            const long long count = static_cast<long long> (mesh.vertices.size ());
            if (index == 0)
              throw Error (atLine (path, cursor.line, "face index 0 (OBJ indices start at 1)"));
            if (index < 0)
            {
              if (count + index < 0)
                throw Error (atLine (path, cursor.line,
                                     "relative face index " + std::to_string (index) + " points before the first vertex"));
              index = count + index;
            }
            else
            {
              index -= 1;
              if (index > max_index)
              {
                max_index = index;
                max_index_line = cursor.line;
              }
              if (index >= std::numeric_limits<int>::max ())
                throw Error (atLine (path, cursor.line, "face index " + std::to_string (index + 1) + " is out of range"));
            }
            polygon.push_back (static_cast<int> (index));
          }
          if (polygon.size () < 3)
            throw Error (atLine (path, cursor.line,
                                 "face with " + std::to_string (polygon.size ()) + " vertices (at least 3 needed)"));
          for (std::size_t i = 1; i + 1 < polygon.size (); ++i)
            mesh.triangles.emplace_back (polygon[0], polygon[i], polygon[i + 1]);
        }
        // Everything else (vt, vn, o, g, s, usemtl, mtllib, l, p, ...) is not needed for the triangle mesh.
        cursor.skipLine ();
      }

      if (max_index >= static_cast<long long> (mesh.vertices.size ()))
        throw Error (atLine (path, max_index_line,
                             "face index " + std::to_string (max_index + 1) + " is out of range (the file has " +
                                 std::to_string (mesh.vertices.size ()) + " vertices)"));
    }
  } // namespace io_detail
} // namespace pcl_sparse
