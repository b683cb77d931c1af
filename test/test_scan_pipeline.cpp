// Scans through the whole pipeline (issue 12): a PCL cloud without polygons encoded and resampled (noise
// smoothed), normals and keypoints of a scan lined up with its input points, the real Stanford scan bun000
// against the mesh it lies on, and a simulated lidar street against its truth.
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/scan_conversion.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/keypoints/harris_keypoint3d_mesh.h>
#include <pcl_sparse/normals/mesh_normal_estimation.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>
#include <pcl_sparse/tiles/memory_tile_source.h>

#include <pcl/io/pcd_io.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "generated_clouds.h"
#include "shared_data.h"

using namespace pcl_sparse;

namespace
{
  /// A unit sphere sampled uniformly with Gaussian noise of \a sigma along the radius, plus a NaN point and
  /// a "no return" at the origin (the sensor), as a driver writes them.
  pcl::PointCloud<pcl::PointXYZ>::Ptr
  noisySphere (std::size_t count, double sigma, std::uint32_t seed)
  {
    std::mt19937 random (seed);
    std::normal_distribution<double> normal (0.0, 1.0);
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    for (std::size_t i = 0; i < count; ++i)
    {
      Eigen::Vector3d d (normal (random), normal (random), normal (random));
      d.normalize ();
      const Eigen::Vector3f p = (d * (1.0 + sigma * normal (random))).cast<float> ();
      cloud->push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
    }
    cloud->push_back (pcl::PointXYZ (NAN, NAN, NAN));
    cloud->push_back (pcl::PointXYZ (0.0f, 0.0f, 0.0f));
    cloud->is_dense = true;  // as drivers claim
    return cloud;
  }

  /// \a count points resampled from \a model.
  pcl::PointCloud<pcl::PointNormal>
  resampleModel (const SparseSurfaceModel::ConstPtr& model, std::size_t count)
  {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (count);
    pcl::PointCloud<pcl::PointNormal> out;
    resampling.compute (out);
    return out;
  }

  double
  meanRadiusError (const pcl::PointCloud<pcl::PointNormal>& cloud)
  {
    double sum = 0.0;
    for (const pcl::PointNormal& p : cloud)
      sum += std::abs (p.getVector3fMap ().norm () - 1.0);
    return sum / static_cast<double> (cloud.size ());
  }
} // namespace

TEST (ScanPipeline, NoisySphereCloudIsSmoothedNotCoded)
{
  const double sigma = 0.005;
  const auto cloud = noisySphere (20000, sigma, 7);
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputCloud (cloud);
  // An in-memory cloud's sensor_origin_ is (0, 0, 0), here the sphere's centre: normals would face
  // inward, toward that "sensor". Consistent orientation makes them face out.
  CloudSurfaceOptions surface_options;
  surface_options.orientation = NormalOrientation::SpanningTree;
  encoder.setCloudSurfaceOptions (surface_options);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_TRUE (encoder.getCloudSurface ());
  EXPECT_EQ (encoder.getCleaningReport ().non_finite, 1u);
  EXPECT_EQ (encoder.getCleaningReport ().at_sensor_origin, 1u);
  EXPECT_EQ (model->num_input_vertices, 20000u);
  // The estimated noise is the true one within 30 %.
  EXPECT_NEAR (encoder.getCloudSurface ()->noise, sigma, 0.3 * sigma);

  const pcl::PointCloud<pcl::PointNormal> out = resampleModel (model, 20000);
  ASSERT_EQ (out.size (), 20000u);
  // The scan's own points are sigma * sqrt(2 / pi) = 0.8 sigma from the sphere on average.
  const double input_error = 0.8 * sigma;
  const double output_error = meanRadiusError (out);
  std::size_t outward = 0;
  for (const pcl::PointNormal& p : out)
    outward += p.getNormalVector3fMap ().dot (p.getVector3fMap ()) > 0.0f;
  std::cout << "  mean |r - 1|: scan " << input_error << ", resampled " << output_error << "; outward normals "
            << outward << " of " << out.size () << std::endl;
  // Measured 0.39x since patches grow on the PCA normals and code to their own noise (0.54x before); 0.42x
  // while scans drew extra samples on their triangles (SparseCodingOptions::triangle_samples).
  EXPECT_LT (output_error, 0.41 * input_error);
  // Consistently oriented, outward on a closed surface.
  EXPECT_GE (outward, out.size () - out.size () / 1000);
}

TEST (ScanPipeline, NormalsAndKeypointsLineUpWithTheInputPoints)
{
  const auto cloud = noisySphere (3000, 0.0, 3);
  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputCloud (cloud);
  ne.setViewPoint (0.0f, 0.0f, 0.0f);  // inside: every normal faces the centre
  pcl::PointCloud<pcl::PointNormal> normals;
  ne.compute (normals);
  ASSERT_EQ (normals.size (), cloud->size ());  // one per input point, as PCL's NormalEstimation
  EXPECT_FALSE (normals.is_dense);
  for (std::size_t i = 0; i < 3000; ++i)
  {
    EXPECT_EQ (normals[i].getVector3fMap (), (*cloud)[i].getVector3fMap ());
    EXPECT_LT (normals[i].getNormalVector3fMap ().dot ((*cloud)[i].getVector3fMap ()), -0.99f) << i;
  }
  EXPECT_TRUE (std::isnan (normals[3000].normal_x));  // the NaN point
  EXPECT_TRUE (std::isnan (normals[3001].normal_x));  // the "no return"

  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputCloud (cloud);
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  // The default selection fraction, 1 % of the 3000 valid points (the NaN and "no return" points have none).
  ASSERT_EQ (keypoints.size (), 30u);
  ASSERT_EQ (keypoints.size (), harris.getKeypointsIndices ()->indices.size ());
  for (std::size_t k = 0; k < keypoints.size (); ++k)
    EXPECT_EQ (keypoints[k].getVector3fMap (), (*cloud)[harris.getKeypointsIndices ()->indices[k]].getVector3fMap ());
}

TEST (ScanPipeline, StanfordScanResamplesOntoTheBunny)
{
  const std::string scan_path = std::string (PCL_SPARSE_SHARED_CLOUDS) + "/bun000.ply";
  const std::string mesh_path = std::string (PCL_SPARSE_SHARED_MESHES) + "/stanford-bunny.obj";
  PCL_SPARSE_NEED_SHARED_FILE (scan_path);
  PCL_SPARSE_NEED_SHARED_FILE (mesh_path);
  auto scan = std::make_shared<ScanCloud> ();
  loadScanCloud (scan_path, *scan);
  const TriangleMesh bunny = loadTriangleMesh (mesh_path);

  auto resample = [&] (CosineBasisKind basis, std::shared_ptr<const CloudSurface>& surface) {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputScan (scan);
    SparseSurfaceEncoderOptions options;
    options.basis = basis;
    encoder.setOptions (options);
    auto model = std::make_shared<SparseSurfaceModel> ();
    encoder.compute (*model);
    surface = encoder.getCloudSurface ();
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (scan->size ());
    pcl::PointCloud<pcl::PointNormal> out;
    resampling.compute (out);
    return out;
  };
  std::shared_ptr<const CloudSurface> surface;
  const pcl::PointCloud<pcl::PointNormal> out = resample (CosineBasisKind::Paper, surface);
  const pcl::PointCloud<pcl::PointNormal> out_dct = resample (CosineBasisKind::Dct, surface);
  // The bounds below are per point (a few points could sit anywhere), and flipped < size / 1000.
  ASSERT_EQ (out.size (), scan->size ());
  ASSERT_EQ (out_dct.size (), scan->size ());

  // The scan's own points with its normals, measured the same way.
  pcl::PointCloud<pcl::PointNormal> own;
  for (std::size_t i = 0; i < scan->size (); ++i)
  {
    pcl::PointNormal p;
    p.getVector3fMap () = (scan->origin + scan->positions[i]).cast<float> ();
    p.getNormalVector3fMap () = surface->normals[i].cast<float> ();
    if (surface->normals[i].squaredNorm () > 0.0)
      own.push_back (p);
  }
  CloudQualityOptions options;
  options.probes = 1000;  // completeness is not the question: the scan sees one side
  const CloudQuality scan_quality = evaluateCloudQuality (bunny, own, options);
  const CloudQuality quality = evaluateCloudQuality (bunny, out, options);
  const CloudQuality quality_dct = evaluateCloudQuality (bunny, out_dct, options);
  std::cout << "  bun000: mean distance to the bunny: scan " << scan_quality.mean_distance << ", resampled "
            << quality.mean_distance << " (dct basis " << quality_dct.mean_distance << "); flipped normals: scan "
            << scan_quality.flipped << ", resampled " << quality.flipped << " (dct " << quality_dct.flipped << ") of "
            << out.size () << "; mean normal angle " << quality.mean_normal_angle << " (dct "
            << quality_dct.mean_normal_angle << ") degrees" << std::endl;
  // The scan lies on the mesh up to its noise and the registration of the ten scans the mesh was zippered
  // from (measured 9.0e-5, 0.04 % of the diagonal): that offset is not noise and no smoothing removes it.
  // Measured: resampled 1.21e-4 (paper basis), 1.02e-4 (dct, then the default); flipped 2 and 0 of 40256. Measured
  // again 2026-12-06: 1.031e-4 with the default basis and with dct, 1.150 x the scan's (1.149 x just before the
  // radii went on their grid, coding/radius_grid.h). Patches
  // grown with the scan's PCA normals are large (median 65 points): the paper's even-only atoms cannot code
  // the tilt left between a patch's frame and its points, the dct's can (mean normal angle 17 vs 7.6 degrees).
  EXPECT_EQ (quality.invalid, 0u);
  EXPECT_EQ (quality_dct.invalid, 0u);
  EXPECT_LT (scan_quality.mean_distance, 1.2e-4);
  EXPECT_LT (quality.mean_distance, 1.17 * scan_quality.mean_distance);
  EXPECT_LT (quality_dct.mean_distance, 1.17 * scan_quality.mean_distance);
  EXPECT_LT (quality.flipped, out.size () / 1000);
  EXPECT_LT (quality_dct.flipped, out.size () / 1000);
  EXPECT_LT (quality_dct.mean_normal_angle, 10.0);
}

// office1.pcd, a Kinect-class frame whose depth comes in steps 5.5 pixel spacings wide (7.5 cm at 5 m): with
// the steps kept, normals followed the terraces and risers, 29512 patches, and 5516 resampled normals faced more
// than 10 degrees away from the sensor (2.2 %). The steps are taken out first now (remove_depth_steps): 14456
// patches, 845 such normals, and the output covers the de-stepped surface as before.
TEST (ScanPipeline, KinectDepthStepsAreTakenOut)
{
  const std::string scan_path = std::string (PCL_SPARSE_SHARED_CLOUDS) + "/office1.pcd";
  PCL_SPARSE_NEED_SHARED_FILE (scan_path);
  auto scan = std::make_shared<ScanCloud> ();
  loadScanCloud (scan_path, *scan);
  ASSERT_TRUE (scan->has_sensor_pose);
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputScan (scan);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_TRUE (encoder.getCloudSurface ()->depth_steps_removed);
  EXPECT_GT (encoder.getCloudSurface ()->depth_levels, 100u);
  EXPECT_LT (model->numPatches (), 18000u);
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (scan->size ());
  pcl::PointCloud<pcl::PointNormal> out;
  resampling.compute (out);
  ASSERT_EQ (out.size (), scan->size ());  // away < size / 200: a cloud of few points would pass
  const Eigen::Vector3d sensor = scan->sensor_origin;
  std::size_t away = 0;
  for (const pcl::PointNormal& p : out)
  {
    const Eigen::Vector3d to_sensor = (sensor - p.getVector3fMap ().cast<double> ()).normalized ();
    const double cosine = p.getNormalVector3fMap ().cast<double> ().dot (to_sensor);
    ASSERT_TRUE (std::isfinite (cosine)) << "a NaN point or normal";  // NaN < -0.17 is false: not counted as away
    away += cosine < -0.17 ? 1 : 0;
  }
  EXPECT_LT (away, out.size () / 200) << away << " of " << out.size () << " normals face away from the sensor";
}

TEST (ScanPipeline, MergedScansFaceTheirOwnViewpoints)
{
  // A sphere seen by two sensors, at x = +10 and x = -10, each keeping the half it sees; merged, with each
  // point's viewpoint in vp_x vp_y vp_z (pcl::PointWithViewpoint). Every normal faces its own sensor, so
  // outward; the cloud's sensor_origin_ (0, 0, 0, the centre) would turn them all inward.
  std::mt19937 random (11);
  std::normal_distribution<double> normal (0.0, 1.0);
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointWithViewpoint>> ();
  for (int i = 0; i < 4000; ++i)
  {
    Eigen::Vector3d d (normal (random), normal (random), normal (random));
    d.normalize ();
    const float side = d.x () >= 0.0 ? 10.0f : -10.0f;
    cloud->push_back (pcl::PointWithViewpoint (static_cast<float> (d.x ()), static_cast<float> (d.y ()),
                                               static_cast<float> (d.z ()), side, 0.0f, 0.0f));
  }
  // Through a PCD file with vp_x vp_y vp_z fields, as a merged map is stored.
  const std::string file = (std::filesystem::temp_directory_path () / ("merged_" + std::to_string (::getpid ()) + ".pcd")).string ();
  ASSERT_EQ (pcl::io::savePCDFileBinary (file, *cloud), 0);
  auto scan = std::make_shared<ScanCloud> ();
  loadScanCloud (file, *scan);
  std::filesystem::remove (file);
  ASSERT_EQ (scan->viewpoints.size (), cloud->size ());
  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputScan (scan);
  pcl::PointCloud<pcl::PointNormal> normals;
  ne.compute (normals);
  ASSERT_EQ (normals.size (), cloud->size ());
  std::size_t outward = 0;
  for (const pcl::PointNormal& p : normals)
    outward += p.getNormalVector3fMap ().dot (p.getVector3fMap ()) > 0.9f;
  EXPECT_EQ (outward, normals.size ());
}

// A scan's hole (a shadow, missing depth) stays a hole: patches on a flat scan grow large (the PCA normals
// agree) and may grow around it, but their footprints stop at its rim (clip_footprints_at_holes).
TEST (ScanPipeline, HolesAreNotFilled)
{
  std::mt19937 random (11);
  std::uniform_real_distribution<double> uniform (0.0, 1.0);
  std::normal_distribution<double> noise (0.0, 0.001);
  const Eigen::Vector2d hole (0.6, 0.5);
  const double hole_radius = 0.1;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  while (cloud->size () < 20000)
  {
    const Eigen::Vector2d p (uniform (random), uniform (random));
    if ((p - hole).norm () > hole_radius)
      cloud->push_back (pcl::PointXYZ (p.x (), p.y (), noise (random)));
  }
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputCloud (cloud);
  encoder.setViewPoint (0.5f, 0.5f, 2.0f);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  const pcl::PointCloud<pcl::PointNormal> out = resampleModel (model, 20000);
  ASSERT_EQ (out.size (), 20000u);
  std::size_t in_hole = 0, facing = 0;
  for (const pcl::PointNormal& p : out)
  {
    in_hole += (Eigen::Vector2d (p.x, p.y) - hole).norm () < 0.5 * hole_radius;
    facing += p.normal_z > 0.9f;
  }
  std::cout << "  " << model->numPatches () << " patches; points in the hole " << in_hole << ", normals within 25 deg of +z "
            << facing << " of " << out.size () << std::endl;
  // Filled, the inner half of the hole would hold about 160 points; footprints are cut on 64 rays and
  // interpolated between them, so a few may reach in where a ray only grazes the hole (measured 7).
  EXPECT_LE (in_hole, 20u);
  EXPECT_GE (facing, out.size () - out.size () / 1000);  // measured 19999 of 20000
  // Patches stop at 4096 vertices on scans (max_patch_vertices): measured 19 patches here, 7 unbounded.
  EXPECT_GE (model->numPatches (), 5u);
}

TEST (ScanPipeline, AScanWithNoPointLeftSaysWhy)
{
  // A frame of no-returns only: what cleaning dropped is the reason, in the library's message as in the tools'.
  pcl::PointCloud<pcl::PointXYZ> frame;
  for (int i = 0; i < 3; ++i)
    frame.push_back (pcl::PointXYZ (NAN, NAN, NAN));
  frame.push_back (pcl::PointXYZ (0.0f, 0.0f, 0.0f));
  auto scan = std::make_shared<ScanCloud> ();
  toScanCloud (frame, *scan);
  ASSERT_EQ (scan->size (), 0u);
  const std::string why = "no point left after cleaning (3 non-finite, 1 at the sensor origin)";
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputScan (scan);
  SparseSurfaceModel model;
  try
  {
    encoder.compute (model);
    ADD_FAILURE () << "an empty scan was encoded";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find (why), std::string::npos) << e.what ();
  }
  try
  {
    MemoryTileSource source (scan, TileGridOptions ());
    ADD_FAILURE () << "an empty scan was cut into tiles";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find (why), std::string::npos) << e.what ();
  }
}

// A spinning lidar's rings lie far apart compared with the points along them (32 rings 1.33 degrees apart,
// 0.17-degree azimuth steps here, as the shared HDL-32E frames). The normals' window of 5 x 5 pixels of the
// ring image was a strip 8 times higher than wide; the noise across it turned normals about the vertical,
// and patch frames with them (fast_gicp_251370668.pcd: a wall facing the sensor had its patch's frame at 90
// degrees from the line of sight). With windows that reach along the rings the normals are smooth enough
// that growth at 30 degrees of smooth variation crossed the corner between the road and a wall through the
// triangles joining their rings, so PatchOptions::lidar_delta (10 degrees) replaces it there. Measured on
// this street: mean distance to the truth 0.0251 -> 0.0185, median normal angle to it 0.58 -> 0.26 degrees,
// points more than 120 degrees from its normal 36 -> 3, more than 10 degrees past perpendicular to the line
// of sight 517 -> 34.
TEST (ScanPipeline, LidarStreetResamplesNearTheTruth)
{
  const pcl_sparse_test::LidarStreet street = pcl_sparse_test::lidarStreet ();
  auto scan = std::make_shared<ScanCloud> (street.scan);
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputScan (scan);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_EQ (encoder.getCloudSurface ()->neighborhood, CloudNeighborhood::LidarRings);
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (scan->size ());
  pcl::PointCloud<pcl::PointNormal> out;
  resampling.compute (out);
  ASSERT_EQ (out.size (), scan->size ());
  CloudQualityOptions options;
  options.probes = 1000;  // one view: completeness against the whole truth is not the question
  const CloudQuality q = evaluateCloudQuality (street.truth, out, options);
  EXPECT_LT (q.mean_distance, 0.021);
  EXPECT_LT (q.median_normal_angle, 0.4);
  EXPECT_LE (q.flipped, 5u);
  std::size_t away = 0;
  for (const pcl::PointNormal& p : out)
  {
    const Eigen::Vector3d to_sensor = (scan->sensor_origin - p.getVector3fMap ().cast<double> ()).normalized ();
    away += p.getNormalVector3fMap ().cast<double> ().dot (to_sensor) < -0.17 ? 1 : 0;
  }
  EXPECT_LT (away, 150u);
}
