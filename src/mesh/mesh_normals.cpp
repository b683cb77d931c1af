#include <pcl_sparse/mesh/mesh_normals.h>

#include <Eigen/Geometry>

#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    Eigen::Vector3d
    faceCross (const TriangleMesh& mesh, const Eigen::Vector3i& t)
    {
      const Eigen::Vector3d& a = mesh.vertices[t[0]];
      return (mesh.vertices[t[1]] - a).cross (mesh.vertices[t[2]] - a);
    }

    Eigen::Vector3d
    normalizedOrZero (const Eigen::Vector3d& v)
    {
      const double n = v.norm ();
      return n > 0.0 && std::isfinite (n) ? Eigen::Vector3d (v / n) : Eigen::Vector3d::Zero ();
    }
  } // namespace

  std::vector<Eigen::Vector3d>
  computeFaceNormals (const TriangleMesh& mesh)
  {
    std::vector<Eigen::Vector3d> normals (mesh.triangles.size ());
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
      normals[f] = normalizedOrZero (faceCross (mesh, mesh.triangles[f]));
    return normals;
  }

  std::vector<double>
  computeFaceAreas (const TriangleMesh& mesh)
  {
    std::vector<double> areas (mesh.triangles.size ());
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
      areas[f] = 0.5 * faceCross (mesh, mesh.triangles[f]).norm ();
    return areas;
  }

  std::vector<Eigen::Vector3d>
  computeVertexNormals (const TriangleMesh& mesh, const MeshTopology& topology, NormalWeighting weighting)
  {
    const std::size_t num_vertices = mesh.vertices.size ();
    std::vector<Eigen::Vector3d> normals (num_vertices, Eigen::Vector3d::Zero ());
    for (std::size_t v = 0; v < num_vertices; ++v)
    {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero ();
      for (int f : topology.facesOf (static_cast<int> (v)))
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        const Eigen::Vector3d cross = faceCross (mesh, t);
        if (weighting == NormalWeighting::Area)
        {
          sum += cross;  // |cross| = 2 area
          continue;
        }
        int k = 0;
        while (t[k] != static_cast<int> (v))
          ++k;
        const Eigen::Vector3d e1 = mesh.vertices[t[(k + 1) % 3]] - mesh.vertices[t[k]];
        const Eigen::Vector3d e2 = mesh.vertices[t[(k + 2) % 3]] - mesh.vertices[t[k]];
        const double angle = std::atan2 (e1.cross (e2).norm (), e1.dot (e2));
        sum += angle * normalizedOrZero (cross);
      }
      normals[v] = normalizedOrZero (sum);
    }
    return normals;
  }
} // namespace pcl_sparse
