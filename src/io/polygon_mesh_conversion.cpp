#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/polygon_faces.h>

#include "point_fields.h"

#include <pcl/conversions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>


namespace pcl_sparse
{
  pcl::PointCloud<pcl::PointXYZ>
  verticesToCloud (const TriangleMesh& mesh)
  {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    cloud.resize (mesh.vertices.size ());
    bool dense = true;
    for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
    {
      cloud[i].getVector3fMap () = mesh.vertices[i].cast<float> ();
      dense = dense && mesh.vertices[i].allFinite ();
    }
    cloud.width = static_cast<std::uint32_t> (cloud.size ());
    cloud.height = 1;
    cloud.is_dense = dense;
    return cloud;
  }

  pcl::PolygonMesh
  toPolygonMesh (const TriangleMesh& mesh)
  {
    const pcl::PointCloud<pcl::PointXYZ> cloud = verticesToCloud (mesh);

    pcl::PolygonMesh polygon_mesh;
    pcl::toPCLPointCloud2 (cloud, polygon_mesh.cloud);
    polygon_mesh.polygons.resize (mesh.triangles.size ());
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      polygon_mesh.polygons[f].vertices = {static_cast<pcl::index_t> (t[0]), static_cast<pcl::index_t> (t[1]),
                                           static_cast<pcl::index_t> (t[2])};
    }
    return polygon_mesh;
  }

  std::vector<Eigen::Vector3d>
  positionsFromCloud (const pcl::PCLPointCloud2& cloud, const std::string& what)
  {
    const pcl::PCLPointField* fields[3] = {nullptr, nullptr, nullptr};
    for (const pcl::PCLPointField& field : cloud.fields)
      for (int k = 0; k < 3; ++k)
        if (field.name == std::string (1, static_cast<char> ('x' + k)))
          fields[k] = &field;
    for (int k = 0; k < 3; ++k)
    {
      if (!fields[k])
        throw Error (what + ": the cloud has no '" + static_cast<char> ('x' + k) + "' field");
      const std::size_t size = io_detail::fieldSize (fields[k]->datatype);
      if (size == 0 || fields[k]->offset + size > cloud.point_step)
        throw Error (what + ": bad '" + static_cast<char> ('x' + k) + "' field");
    }
    if (cloud.height > 0 &&
        (static_cast<std::size_t> (cloud.row_step) * (cloud.height - 1) + static_cast<std::size_t> (cloud.point_step) * cloud.width >
             cloud.data.size () ||
         static_cast<std::size_t> (cloud.point_step) * cloud.width > cloud.row_step))
      throw Error (what + ": the cloud data is shorter than width, height and row_step say");

    std::vector<Eigen::Vector3d> positions (static_cast<std::size_t> (cloud.width) * cloud.height);
    for (std::uint32_t row = 0; row < cloud.height; ++row)
      for (std::uint32_t col = 0; col < cloud.width; ++col)
      {
        const std::uint8_t* point = cloud.data.data () + static_cast<std::size_t> (row) * cloud.row_step +
                                    static_cast<std::size_t> (col) * cloud.point_step;
        Eigen::Vector3d& v = positions[static_cast<std::size_t> (row) * cloud.width + col];
        for (int k = 0; k < 3; ++k)
          v[k] = io_detail::readFieldValue (point + fields[k]->offset, fields[k]->datatype);
      }
    return positions;
  }

  TriangleMesh
  fromPolygonMesh (const pcl::PolygonMesh& polygon_mesh)
  {
    TriangleMesh mesh;
    mesh.vertices = positionsFromCloud (polygon_mesh.cloud);

    mesh.triangles = trianglesFromPolygons (polygon_mesh.polygons, mesh.vertices.size (), "PolygonMesh");
    return mesh;
  }

  void
  loadPolygonMesh (const std::string& path, pcl::PolygonMesh& polygon_mesh, const MeshLoadOptions& options)
  {
    polygon_mesh = toPolygonMesh (loadTriangleMesh (path, options));
  }
} // namespace pcl_sparse
