// A PCL user's whole program: a pcl::PolygonMesh in, a resampled pcl::PointCloud<pcl::PointNormal> out.
//   sample_polygon_mesh_to_cloud mesh.{obj,ply,stl,vtk} cloud.pcd [points]
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/vtk_lib_io.h>

#include <iostream>
#include <string>

int
main (int argc, char** argv)
{
  pcl::PolygonMesh mesh;
  if (argc < 3 || pcl::io::loadPolygonFile (argv[1], mesh) == 0)
    return std::cerr << "usage: " << argv[0] << " mesh.{obj,ply,stl,vtk} cloud.pcd [points]\n", 1;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  pcl::fromPCLPointCloud2 (mesh.cloud, *cloud);

  pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZ> encoder;                   // the paper's defaults
  encoder.setInputCloud (cloud);
  encoder.setInputPolygons (std::make_shared<std::vector<pcl::Vertices>> (mesh.polygons));
  auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
  encoder.compute (*model);                                                  // throws pcl_sparse::Error

  pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (argc > 3 ? std::stoul (argv[3]) : 100000);
  pcl::PointCloud<pcl::PointNormal> out;
  resampling.compute (out);
  return pcl::io::savePCDFileBinary (argv[2], out) == 0 ? 0 : 1;
}
