/// STL, ascii ("solid ... facet normal ... outer loop vertex x y z ... endsolid") and binary (80-byte header,
/// uint32 triangle count, 50 bytes per triangle). STL repeats every corner in every triangle; we weld corners
/// with exactly equal coordinates (no tolerance: anything else would change the geometry) so that the mesh is
/// indexed and has topology, numbering vertices in order of first appearance.

#include "mesh_readers.h"

#include <pcl_sparse/mesh/vertex_welding.h>

#include <vector>

namespace pcl_sparse
{
  namespace io_detail
  {
    namespace
    {
      void
      readBinaryStl (const std::string& data, const std::string& path, TriangleMesh& mesh)
      {
        std::uint32_t count;
        std::memcpy (&count, data.data () + 80, 4);  // little endian by the format; we assume a little-endian host
        const std::uint64_t needed = 84 + 50ull * count;
        if (data.size () < needed)
          throw Error (path + ": truncated binary STL: the header announces " + std::to_string (count) +
                       " triangles (" + std::to_string (needed) + " bytes) but the file has " +
                       std::to_string (data.size ()) + " bytes");
        mesh.triangles.reserve (count);
        VertexWelder welder (mesh.vertices, 3ull * count);
        const char* p = data.data () + 84;
        for (std::uint32_t t = 0; t < count; ++t, p += 50)
        {
          int corner[3];
          for (int c = 0; c < 3; ++c)
          {
            float xyz[3];
            std::memcpy (xyz, p + 12 + 12 * c, 12);  // skip the 12-byte facet normal
            corner[c] = welder.add (Eigen::Vector3d (xyz[0], xyz[1], xyz[2]));
          }
          mesh.triangles.emplace_back (corner[0], corner[1], corner[2]);
        }
      }

      bool
      matchWord (TextCursor& cursor, const char* word)
      {
        const std::size_t n = std::strlen (word);
        if (static_cast<std::size_t> (cursor.end - cursor.p) < n || std::memcmp (cursor.p, word, n) != 0)
          return false;
        const char* after = cursor.p + n;
        if (after != cursor.end && !TextCursor::isBlank (*after) && *after != '\n')
          return false;
        cursor.p = after;
        return true;
      }

      void
      readAsciiStl (const std::string& data, const std::string& path, TriangleMesh& mesh)
      {
        requireText (data, path, "ascii STL");
        TextCursor cursor (data);
        cursor.skipLine ();  // "solid name"
        VertexWelder welder (mesh.vertices, data.size () / 40);
        std::vector<int> polygon;
        bool in_facet = false;
        bool ended = false;
        // Token-driven: "facet" opens a facet, "vertex" adds a corner, "endfacet" closes it; "normal",
        // "outer loop", "endloop" carry nothing we need. Names after "solid"/"endsolid" are skipped.
        while (cursor.skipToToken ())
        {
          if (matchWord (cursor, "facet"))
          {
            if (in_facet)
              throw Error (atLine (path, cursor.line, "'facet' inside a facet"));
            in_facet = true;
            polygon.clear ();
            cursor.skipLine ();  // the normal
          }
          else if (matchWord (cursor, "vertex"))
          {
            if (!in_facet)
              throw Error (atLine (path, cursor.line, "'vertex' outside a facet"));
            Eigen::Vector3d v;
            for (int k = 0; k < 3; ++k)
            {
              cursor.skipBlanks ();
              if (!cursor.parseDouble (v[k]) || !cursor.atDelimiter ())
                throw Error (atLine (path, cursor.line, "bad vertex coordinate " + cursor.tokenForMessage ()));
            }
            polygon.push_back (welder.add (v));
          }
          else if (matchWord (cursor, "endfacet"))
          {
            if (!in_facet || polygon.size () < 3)
              throw Error (atLine (path, cursor.line, "facet with " + std::to_string (polygon.size ()) + " vertices"));
            for (std::size_t i = 1; i + 1 < polygon.size (); ++i)
              mesh.triangles.emplace_back (polygon[0], polygon[i], polygon[i + 1]);
            in_facet = false;
          }
          else if (matchWord (cursor, "outer") || matchWord (cursor, "loop") || matchWord (cursor, "endloop"))
          {
          }
          else if (matchWord (cursor, "endsolid"))
          {
            ended = true;
            cursor.skipLine ();
          }
          else if (matchWord (cursor, "solid"))  // several solids in one file
          {
            ended = false;
            cursor.skipLine ();
          }
          else
            throw Error (atLine (path, cursor.line, "unexpected " + cursor.tokenForMessage () + " in ascii STL"));
        }
        if (in_facet || !ended)
          throw Error (path + ": truncated ascii STL (no endsolid)");
      }
    } // namespace

    void
    readStl (const std::string& data, const std::string& path, TriangleMesh& mesh)
    {
      // Binary files may also start with "solid" (some exporters write it into the 80-byte header), so a file
      // whose size is exactly that of a binary STL with its announced count is binary.
      bool binary_size = false;
      if (data.size () >= 84)
      {
        std::uint32_t count;
        std::memcpy (&count, data.data () + 80, 4);
        binary_size = data.size () == 84 + 50ull * count;
      }
      std::size_t start = 0;
      while (start < data.size () && (TextCursor::isBlank (data[start]) || data[start] == '\n'))
        ++start;
      const bool starts_solid = data.compare (start, 5, "solid") == 0;
      // Binary STL almost always has NUL bytes early (counts, small floats); ascii never has.
      const bool looks_text = !std::memchr (data.data (), '\0', std::min<std::size_t> (data.size (), 4096));
      if (starts_solid && !binary_size && looks_text)
        readAsciiStl (data, path, mesh);
      else if (data.size () < 84)
        throw Error (path + ": not an STL file (too short for binary STL and not ascii STL)");
      else
        readBinaryStl (data, path, mesh);
    }
  } // namespace io_detail
} // namespace pcl_sparse
