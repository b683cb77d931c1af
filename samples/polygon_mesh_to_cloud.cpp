// A PCL user's whole program: a pcl::PolygonMesh in, a resampled pcl::PointCloud<pcl::PointNormal> out.
//   sample_polygon_mesh_to_cloud mesh.{obj,off,ply,stl} cloud.pcd [points]
// (pcl::io::loadPolygonFile would do for a mesh whose faces share their vertices; its OBJ reader splits a
// vertex per face corner when the file has per-corner normals, a triangle soup the encoder refuses.)
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>

#include <iostream>
#include <string>

int
main (int argc, char** argv)
{
  if (argc < 3)
    return std::cerr << "usage: " << argv[0] << " mesh.{obj,off,ply,stl} cloud.pcd [points]\n", 1;
  try
  {
    pcl::PolygonMesh mesh;
    pcl_sparse::loadPolygonMesh (argv[1], mesh);
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    pcl::fromPCLPointCloud2 (mesh.cloud, *cloud);

    pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZ> encoder;                 // the library's defaults
    encoder.setInputCloud (cloud);
    encoder.setInputPolygons (std::make_shared<std::vector<pcl::Vertices>> (mesh.polygons));
    auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
    encoder.compute (*model);

    pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (argc > 3 ? std::stoul (argv[3]) : 100000);
    pcl::PointCloud<pcl::PointNormal> out;
    resampling.compute (out);
    return pcl::io::savePCDFileBinary (argv[2], out) == 0 ? 0 : 1;
  }
  catch (const pcl_sparse::Error& e)  // a bad file or option: one line, as the tools
  {
    return std::cerr << argv[0] << ": " << e.what () << "\n", 1;
  }
}
