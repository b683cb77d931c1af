// Load a mesh, encode it as a sparse surface model, resample it into a PointNormal cloud, save it.
//   sample_resample_mesh mesh.off cloud.pcd [points]
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <iostream>
#include <string>

int
main (int argc, char** argv)
{
  if (argc < 3)
  {
    std::cerr << "usage: " << argv[0] << " mesh.off cloud.pcd [points]\n";
    return 1;
  }
  try
  {
    auto mesh = std::make_shared<pcl_sparse::TriangleMesh> (pcl_sparse::loadTriangleMesh (argv[1]));

    pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZ> encoder;  // defaults: rho = 0.001, f = 0.5, 144 cosines and the quadric
    encoder.setInputMesh (mesh);
    auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
    encoder.compute (*model);

    pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (argc > 3 ? std::stoul (argv[3]) : 4 * mesh->numVertices ());
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);  // normals and curvature come from the codes, no estimation step

    pcl_sparse::savePointNormalCloud (argv[2], cloud);
    std::cout << model->numPatches () << " patches -> " << cloud.size () << " points in " << argv[2] << "\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << e.what () << "\n";
    return 1;
  }
  return 0;
}
