// A point type the library is not compiled for works through the impl/*.hpp templates, as in PCL: define
// PCL_NO_PRECOMPILE before the stage headers.
#define PCL_NO_PRECOMPILE
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/register_point_struct.h>

#include <gtest/gtest.h>

namespace my_robot
{
  /// A user's own point type: position, a label and a range, nothing the library instantiates.
  struct EIGEN_ALIGN16 LabelledPoint
  {
    PCL_ADD_POINT4D;
    float range;
    std::uint32_t label;
    PCL_MAKE_ALIGNED_OPERATOR_NEW
  };

  /// A user's own output type: position and normal only.
  struct EIGEN_ALIGN16 SurfelPoint
  {
    PCL_ADD_POINT4D;
    PCL_ADD_NORMAL4D;
    PCL_MAKE_ALIGNED_OPERATOR_NEW
  };
} // namespace my_robot

POINT_CLOUD_REGISTER_POINT_STRUCT (my_robot::LabelledPoint,
                                   (float, x, x) (float, y, y) (float, z, z) (float, range, range) (std::uint32_t, label, label))
POINT_CLOUD_REGISTER_POINT_STRUCT (my_robot::SurfelPoint,
                                   (float, x, x) (float, y, y) (float, z, z) (float, normal_x, normal_x) (float, normal_y,
                                   normal_y) (float, normal_z, normal_z))

TEST (PclNoPrecompile, CustomInputAndOutputPointTypes)
{
  const pcl_sparse::TriangleMesh sphere = pcl_sparse::makeIcosphere (3);
  auto cloud = std::make_shared<pcl::PointCloud<my_robot::LabelledPoint>> ();
  auto polygons = std::make_shared<std::vector<pcl::Vertices>> ();
  for (const Eigen::Vector3d& v : sphere.vertices)
  {
    my_robot::LabelledPoint p;
    p.getVector3fMap () = v.cast<float> ();
    p.range = 1.0f;
    p.label = 7;
    cloud->push_back (p);
  }
  for (const Eigen::Vector3i& t : sphere.triangles)
  {
    pcl::Vertices face;
    face.vertices = {t[0], t[1], t[2]};
    polygons->push_back (face);
  }
  pcl_sparse::SparseSurfaceEncoder<my_robot::LabelledPoint> encoder;
  encoder.setInputCloud (cloud);
  encoder.setInputPolygons (polygons);
  auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
  encoder.compute (*model);
  EXPECT_GT (model->numPatches (), 5u);

  pcl_sparse::SparseSurfaceResampling<my_robot::SurfelPoint> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (2000);
  pcl::PointCloud<my_robot::SurfelPoint> out;
  resampling.compute (out);
  ASSERT_EQ (out.size (), 2000u);
  double dot = 0.0;
  for (const my_robot::SurfelPoint& p : out)
  {
    // 56 patches of 12 atoms on a 642-vertex sphere; with face completion (issue 13) they also cover the
    // faces between them, where the farthest point is 0.022 off the sphere (0.013 without).
    EXPECT_NEAR (p.getVector3fMap ().norm (), 1.0f, 0.025f);
    dot += p.getNormalVector3fMap ().dot (p.getVector3fMap ().normalized ());
  }
  EXPECT_GT (dot / static_cast<double> (out.size ()), 0.98);
}
