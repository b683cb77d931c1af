/// XYZ text point files: "x y z" or "x y z nx ny nz" per line, as CloudCompare, MeshLab and most scanner
/// software write them.

#include "cloud_readers.h"
#include "mesh_readers.h"

namespace pcl_sparse
{
  namespace io_detail
  {
    void
    readXyz (const std::string& data, const std::string& path, std::vector<Eigen::Vector3d>& positions,
             std::vector<Eigen::Vector3d>& normals)
    {
      requireText (data, path, "XYZ");
      positions.clear ();
      normals.clear ();
      // At most one point per line.
      positions.reserve (static_cast<std::size_t> (std::count (data.begin (), data.end (), '\n')) + 1);
      TextCursor cursor (data);
      int columns = 0;  // 3 or 6, fixed by the first point line
      double values[6];
      while (cursor.skipToToken ())
      {
        int n = 0;
        while (!cursor.atLineEnd ())
        {
          if (n == 6)
            throw Error (atLine (path, cursor.line, "more than 6 values on an XYZ line (expected x y z or x y z nx ny nz)"));
          if (!cursor.parseDouble (values[n]) || !cursor.atDelimiter ())
            throw Error (atLine (path, cursor.line, "bad XYZ value " + cursor.tokenForMessage ()));
          ++n;
        }
        if (columns == 0)
        {
          if (n != 3 && n != 6)
            throw Error (atLine (path, cursor.line, std::to_string (n) + " values on an XYZ line (expected x y z or x y z nx ny nz)"));
          columns = n;
          if (columns == 6)
            normals.reserve (positions.capacity ());
        }
        else if (n != columns)
          throw Error (atLine (path, cursor.line, std::to_string (n) + " values on an XYZ line, the lines before have " +
                                                      std::to_string (columns)));
        positions.emplace_back (values[0], values[1], values[2]);
        if (columns == 6)
          normals.emplace_back (values[3], values[4], values[5]);
      }
      positions.shrink_to_fit ();
      normals.shrink_to_fit ();
    }
  } // namespace io_detail
} // namespace pcl_sparse
