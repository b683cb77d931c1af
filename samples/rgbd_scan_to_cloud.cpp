// A PCL user's whole program for a coloured scan: a pcl::PointCloud<pcl::PointXYZRGBA> in (an RGB-D or
// stereo frame, organized or not, NaN where the sensor saw nothing), a clean, denser
// pcl::PointCloud<pcl::PointXYZRGBNormal> out: points on the coded surface with its normals, facing the
// sensor (the PCD's VIEWPOINT, as pcl::Feature would), and the scan's colours.
//   sample_rgbd_scan_to_cloud scan.pcd cloud.pcd [points]
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/io/pcd_io.h>

#include <iostream>
#include <memory>
#include <string>

int
main (int argc, char** argv)
{
  if (argc < 3)
    return std::cerr << "usage: " << argv[0] << " scan.pcd cloud.pcd [points]\n", 1;
  try
  {
    auto scan = std::make_shared<pcl::PointCloud<pcl::PointXYZRGBA>> ();
    if (pcl::io::loadPCDFile (argv[1], *scan) != 0)
      return std::cerr << argv[0] << ": cannot read " << argv[1] << "\n", 1;

    // A cloud without polygons is a scan: the encoder cleans it, builds its surface and codes its colour.
    pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZRGBA> encoder;
    encoder.setInputCloud (scan);
    auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
    encoder.compute (*model);

    pcl_sparse::SparseSurfaceResampling<pcl::PointXYZRGBNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (argc > 3 ? std::stoul (argv[3]) : 2 * encoder.getCleaningReport ().kept);
    pcl::PointCloud<pcl::PointXYZRGBNormal> out;
    resampling.compute (out);
    std::cout << scan->size () << " points in, " << model->numPatches () << " patches, " << out.size ()
              << " points out\n";
    return pcl::io::savePCDFileBinary (argv[2], out) == 0 ? 0 : 1;
  }
  catch (const pcl_sparse::Error& e)  // a bad file or option: one line, as the tools
  {
    return std::cerr << argv[0] << ": " << e.what () << "\n", 1;
  }
}
