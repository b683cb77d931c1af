#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/polygon_faces.h>

namespace pcl_sparse
{
  std::vector<Eigen::Vector3i>
  trianglesFromPolygons (const std::vector<pcl::Vertices>& polygons, std::size_t num_points, const std::string& what)
  {
    std::vector<Eigen::Vector3i> triangles;
    triangles.reserve (polygons.size ());
    for (std::size_t f = 0; f < polygons.size (); ++f)
    {
      const auto& indices = polygons[f].vertices;
      if (indices.size () < 3)
        throw Error (what + ": polygon " + std::to_string (f) + " has " + std::to_string (indices.size ()) +
                     " vertices (at least 3 needed)");
      for (const auto index : indices)
        if (index < 0 || static_cast<std::size_t> (index) >= num_points)
          throw Error (what + ": polygon " + std::to_string (f) + " has vertex index " + std::to_string (index) +
                       " out of range (" + std::to_string (num_points) + " points)");
      for (std::size_t i = 1; i + 1 < indices.size (); ++i)
        triangles.emplace_back (static_cast<int> (indices[0]), static_cast<int> (indices[i]),
                                static_cast<int> (indices[i + 1]));
    }
    return triangles;
  }
} // namespace pcl_sparse
