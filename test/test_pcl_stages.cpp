// The stages as PCL classes (issue 11): every instantiated point type, PCL's input (cloud + polygons) against
// the library's mesh, setIndices, the error policy, and the output point types of resampling.
#include "error_message.h"
#include "robustness_cases.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/scan_conversion.h>
#include <pcl_sparse/keypoints/harris_keypoint3d_mesh.h>
#include <pcl_sparse/normals/mesh_normal_estimation.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/sub_mesh.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numeric>
#include <string>

using namespace pcl_sparse;

namespace
{
  template <typename PointT>
  typename pcl::PointCloud<PointT>::Ptr
  cloudOf (const TriangleMesh& mesh);

  /// A mesh with features (cube corners and edges, a bump), its coordinates exactly representable in float so
  /// that PCL's float clouds carry the same surface as the double mesh. (Rounded through a float cloud:
  /// GCC 12 at -O2 drops a double -> float -> double round trip done in registers.)
  TriangleMesh
  floatExactMesh ()
  {
    TriangleMesh mesh = makeCube (6);
    for (Eigen::Vector3d& v : mesh.vertices)
      v.z () += 0.1 * std::exp (-4.0 * v.squaredNorm ());
    mesh.vertices = cloudPositions (*cloudOf<pcl::PointXYZ> (mesh));
    return mesh;
  }

  template <typename PointT>
  typename pcl::PointCloud<PointT>::Ptr
  cloudOf (const TriangleMesh& mesh)
  {
    auto cloud = std::make_shared<pcl::PointCloud<PointT>> ();
    cloud->resize (mesh.vertices.size ());
    for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
    {
      (*cloud)[i].x = static_cast<float> (mesh.vertices[i].x ());
      (*cloud)[i].y = static_cast<float> (mesh.vertices[i].y ());
      (*cloud)[i].z = static_cast<float> (mesh.vertices[i].z ());
    }
    return cloud;
  }

  std::shared_ptr<std::vector<pcl::Vertices>>
  polygonsOf (const TriangleMesh& mesh)
  {
    auto polygons = std::make_shared<std::vector<pcl::Vertices>> (mesh.triangles.size ());
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
      (*polygons)[f].vertices = {mesh.triangles[f][0], mesh.triangles[f][1], mesh.triangles[f][2]};
    return polygons;
  }

  std::vector<std::uint8_t>
  modelBytes (const SparseSurfaceModel& model)
  {
    return encodeModel (model);
  }
} // namespace

template <typename PointT>
class StagesOnEveryPointType : public ::testing::Test
{
};
using InputPointTypes = ::testing::Types<pcl::PointXYZ, pcl::PointXYZI, pcl::PointXYZRGB, pcl::PointXYZRGBA,
                                         pcl::PointNormal, pcl::PointXYZRGBNormal>;
TYPED_TEST_SUITE (StagesOnEveryPointType, InputPointTypes);

TYPED_TEST (StagesOnEveryPointType, CloudAndPolygonsGiveTheMeshModel)
{
  const auto mesh = std::make_shared<TriangleMesh> (floatExactMesh ());
  SparseSurfaceEncoder<pcl::PointXYZ> reference;
  reference.setInputMesh (mesh);
  SparseSurfaceModel expected;
  reference.compute (expected);

  typename SparseSurfaceEncoder<TypeParam>::Ptr encoder = std::make_shared<SparseSurfaceEncoder<TypeParam>> ();
  encoder->setInputCloud (cloudOf<TypeParam> (*mesh));
  encoder->setInputPolygons (polygonsOf (*mesh));
  SparseSurfaceModel model;
  encoder->compute (model);
  EXPECT_EQ (encoder->getClassName (), "SparseSurfaceEncoder");
  ASSERT_GT (model.numPatches (), 10u);
  // Colour and intensity fields come along as attribute channels (r g b [a], intensity); the geometry is the
  // mesh's model, byte for byte.
  const std::size_t channels = (pcl::traits::has_color_v<TypeParam> ? 3 : 0) +
                               (pcl::traits::has_field<TypeParam, pcl::fields::rgba>::value ? 1 : 0) +
                               (pcl::traits::has_intensity_v<TypeParam> ? 1 : 0);
  EXPECT_EQ (model.attribute_channels.size (), channels);
  model.attribute_channels.clear ();
  model.attribute_basis.reset ();
  for (PatchCode& patch : model.patches)
    patch.attributes.clear ();
  EXPECT_EQ (modelBytes (model), modelBytes (expected));

  // The other stages take the same input and give what they give on the mesh itself (float-exact).
  HarrisKeypoint3DMesh<TypeParam> harris;
  harris.setInputCloud (cloudOf<TypeParam> (*mesh));
  harris.setInputPolygons (polygonsOf (*mesh));
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  EXPECT_EQ (keypoints.size (), static_cast<std::size_t> (std::lround (0.01 * mesh->numVertices ())));
  HarrisKeypoint3DMesh<pcl::PointXYZ> mesh_harris;
  mesh_harris.setInputMesh (mesh);
  pcl::PointCloud<pcl::PointXYZI> mesh_keypoints;
  mesh_harris.compute (mesh_keypoints);
  EXPECT_EQ (harris.getResponses (), mesh_harris.getResponses ());
  EXPECT_EQ (harris.getKeypointsIndices ()->indices, mesh_harris.getKeypointsIndices ()->indices);

  MeshNormalEstimation<TypeParam> normals;
  normals.setInputCloud (cloudOf<TypeParam> (*mesh));
  normals.setInputPolygons (polygonsOf (*mesh));
  pcl::PointCloud<pcl::PointNormal> with_normals;
  normals.compute (with_normals);
  ASSERT_EQ (with_normals.size (), mesh->numVertices ());
  EXPECT_GT (with_normals[0].getNormalVector3fMap ().dot (with_normals[0].getVector3fMap ().normalized ()), 0.5f);
  MeshNormalEstimation<pcl::PointXYZ> mesh_normals;
  mesh_normals.setInputMesh (mesh);
  pcl::PointCloud<pcl::PointNormal> expected_normals;
  mesh_normals.compute (expected_normals);
  for (std::size_t i = 0; i < mesh->numVertices (); ++i)
  {
    ASSERT_EQ (with_normals[i].getVector3fMap (), expected_normals[i].getVector3fMap ()) << i;
    ASSERT_EQ (with_normals[i].getNormalVector3fMap (), expected_normals[i].getNormalVector3fMap ()) << i;
  }

  FeatureAwarePatchSampling<TypeParam> sampling;
  sampling.setInputCloud (cloudOf<TypeParam> (*mesh));
  sampling.setInputPolygons (polygonsOf (*mesh));
  std::vector<Patch> patches;
  sampling.compute (patches);
  EXPECT_EQ (patches.size (), model.numPatches ());
  FeatureAwarePatchSampling<pcl::PointXYZ> mesh_sampling;
  mesh_sampling.setInputMesh (mesh);
  std::vector<Patch> expected_patches;
  mesh_sampling.compute (expected_patches);
  ASSERT_EQ (patches.size (), expected_patches.size ());
  for (std::size_t p = 0; p < patches.size (); ++p)
    ASSERT_EQ (patches[p].vertices, expected_patches[p].vertices) << p;
}

TEST (PclStages, QuadsAreFannedIntoTriangles)
{
  // A unit square as one quad: two triangles, so the normals of its corners are +z.
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  for (const auto& p : {Eigen::Vector3f (0, 0, 0), Eigen::Vector3f (1, 0, 0), Eigen::Vector3f (1, 1, 0), Eigen::Vector3f (0, 1, 0)})
    cloud->push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
  auto quad = std::make_shared<std::vector<pcl::Vertices>> (1);
  (*quad)[0].vertices = {0, 1, 2, 3};
  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputCloud (cloud);
  ne.setInputPolygons (quad);
  pcl::PointCloud<pcl::Normal> normals;
  ne.compute (normals);
  ASSERT_EQ (normals.size (), 4u);
  for (const pcl::Normal& n : normals)
    EXPECT_FLOAT_EQ (n.normal_z, 1.0f);
}

TEST (PclStages, IndicesCropTheEncoderAndSelectForNormalsAndKeypoints)
{
  const TriangleMesh mesh = floatExactMesh ();
  // The upper half of the cube (z >= 0) and the bump.
  auto upper = std::make_shared<pcl::Indices> ();
  for (int v = 0; v < static_cast<int> (mesh.numVertices ()); ++v)
    if (mesh.vertices[v].z () >= 0.0)
      upper->push_back (v);
  ASSERT_GT (upper->size (), 20u);
  ASSERT_LT (upper->size (), mesh.numVertices ());

  // Encoder and sampling (CropSurface): the indexed part of the surface, as if it were the whole input.
  SparseSurfaceEncoder<pcl::PointXYZ> cropped;
  cropped.setInputCloud (cloudOf<pcl::PointXYZ> (mesh));
  cropped.setInputPolygons (polygonsOf (mesh));
  cropped.setIndices (upper);
  SparseSurfaceModel model;
  cropped.compute (model);
  SparseSurfaceEncoder<pcl::PointXYZ> part;
  part.setInputMesh (std::make_shared<TriangleMesh> (extractSubMesh (mesh, *upper, "test")));
  SparseSurfaceModel expected;
  part.compute (expected);
  EXPECT_EQ (model.num_input_vertices, upper->size ());
  EXPECT_EQ (modelBytes (model), modelBytes (expected));
  // Without indices again (a new stage: PCL's setIndices cannot be unset), the whole cube.
  SparseSurfaceEncoder<pcl::PointXYZ> whole;
  whole.setInputMesh (std::make_shared<TriangleMesh> (mesh));
  SparseSurfaceModel all;
  whole.compute (all);
  EXPECT_EQ (all.num_input_vertices, mesh.numVertices ());
  EXPECT_GT (all.numPatches (), model.numPatches ());

  // Normals (SelectPoints): one output per index, equal to the whole surface's normal of that point.
  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputMesh (std::make_shared<TriangleMesh> (mesh));
  pcl::PointCloud<pcl::PointNormal> every, selected;
  ne.compute (every);
  ne.setIndices (upper);
  ne.compute (selected);
  ASSERT_EQ (selected.size (), upper->size ());
  for (std::size_t i = 0; i < upper->size (); ++i)
  {
    EXPECT_EQ (selected[i].getVector3fMap (), every[(*upper)[i]].getVector3fMap ());
    EXPECT_EQ (selected[i].getNormalVector3fMap (), every[(*upper)[i]].getNormalVector3fMap ());
  }

  // Keypoints (SelectPoints): only indexed vertices, responses equal to the whole surface's.
  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputMesh (std::make_shared<TriangleMesh> (mesh));
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  const std::vector<double> full = harris.getResponses ();
  harris.setIndices (upper);
  harris.compute (keypoints);
  for (int v : harris.getKeypointsIndices ()->indices)
    EXPECT_GE (mesh.vertices[v].z (), 0.0);
  for (int v : *upper)
    EXPECT_TRUE (harris.getResponses ()[v] == full[v] || (std::isnan (full[v]) && std::isnan (harris.getResponses ()[v])));
}

namespace
{
  /// A wavy n x n grid of points about 0.1 apart at height z (a scan without polygons).
  pcl::PointCloud<pcl::PointXYZ>::Ptr
  wavyGridCloud (int n, float z)
  {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        cloud->push_back (pcl::PointXYZ (0.1f * i + 0.003f * (j % 3), 0.1f * j, z + 0.01f * std::sin (0.3f * i)));
    return cloud;
  }
} // namespace

// The last input set wins: a stage used for a scan, then a cloud, works on the cloud (it kept the scan,
// sized its output by the cloud and wrote past it), and indices are taken as points of the scan.
TEST (PclStages, ScanThenCloudAndIndicesOfAScan)
{
  auto scan = std::make_shared<ScanCloud> ();
  toScanCloud (*wavyGridCloud (60, 1.0f), *scan);  // none at the sensor origin (0, 0, 0), which cleaning drops
  ASSERT_EQ (scan->size (), 3600u);
  const auto small = wavyGridCloud (10, 5.0f);

  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputScan (scan);
  ne.setInputCloud (small);
  pcl::PointCloud<pcl::PointNormal> normals;
  ne.compute (normals);
  ASSERT_EQ (normals.size (), small->size ());
  for (std::size_t i = 0; i < small->size (); ++i)
    EXPECT_EQ (normals[i].getVector3fMap (), (*small)[i].getVector3fMap ()) << i;

  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputScan (scan);
  harris.setInputCloud (small);
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  EXPECT_EQ (harris.getResponses ().size (), small->size ());

  // Indices with a scan: SelectPoints picks its points; CropSurface is refused with the reason.
  MeshNormalEstimation<pcl::PointXYZ> selected;
  selected.setInputScan (scan);
  selected.setIndices (std::make_shared<pcl::Indices> (pcl::Indices{0, 7, 3599}));
  pcl::PointCloud<pcl::PointNormal> three;
  selected.compute (three);
  ASSERT_EQ (three.size (), 3u);
  EXPECT_NEAR ((three[1].getVector3fMap () - (scan->origin + scan->positions[7]).cast<float> ()).norm (), 0.0f, 1e-5f);
  EXPECT_GT (std::abs (three[2].normal_z), 0.9f);  // the grid is nearly flat
  selected.setIndices (std::make_shared<pcl::Indices> (pcl::Indices{3600}));
  EXPECT_THROW (selected.compute (three), Error);

  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputScan (scan);
  encoder.setIndices (std::make_shared<pcl::Indices> (pcl::Indices{0, 1, 2}));
  SparseSurfaceModel model;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { encoder.compute (model); }).find ("crop the scan itself"), std::string::npos);
}

// A scan with every point stored twice (as some drivers write them): cleaning merges each pair, and the
// point it drops takes the normal of the one it keeps. It was left without a vertex, and half of the
// normals were NaN (room_scan1.pcd: 56,427 of its 112,586 points).
TEST (PclStages, DuplicatePointsTakeTheNormalOfTheirTwin)
{
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i)
      cloud->push_back (pcl::PointXYZ (1.0f + 0.1f * i, 0.1f * j, 0.05f * std::sin (0.3f * i) * std::cos (0.2f * j)));
  const std::size_t once = cloud->size ();
  for (std::size_t i = 0; i < once; ++i)
    cloud->push_back ((*cloud)[i]);
  cloud->push_back (pcl::PointXYZ (std::nanf (""), 0.0f, 0.0f));  // still no normal: it has no place
  (*cloud)[5].z = -0.0f;  // -0 and 0 are one position; its twin keeps +0
  (*cloud)[once + 5].z = 0.0f;

  MeshNormalEstimation<pcl::PointXYZ> estimation;
  estimation.setInputCloud (cloud);
  pcl::PointCloud<pcl::PointNormal> normals;
  estimation.compute (normals);
  ASSERT_EQ (normals.size (), cloud->size ());
  EXPECT_EQ (estimation.getCleaningReport ().duplicates_merged, once);
  EXPECT_FALSE (normals.is_dense);
  std::size_t finite = 0;
  for (std::size_t i = 0; i < once; ++i)
  {
    const pcl::PointNormal& first = normals[i];
    const pcl::PointNormal& second = normals[once + i];
    finite += std::isfinite (first.normal_z) && std::isfinite (second.normal_z);
    EXPECT_EQ (first.getNormalVector3fMap (), second.getNormalVector3fMap ()) << i;
    EXPECT_EQ (first.curvature, second.curvature) << i;
  }
  EXPECT_EQ (finite, once);
  EXPECT_TRUE (std::isnan (normals.back ().normal_x));

  // Selected by index: a duplicate alone gives its twin's normal.
  estimation.setIndices (std::make_shared<pcl::Indices> (pcl::Indices{static_cast<int> (once + 210), 210}));
  pcl::PointCloud<pcl::PointNormal> two;
  estimation.compute (two);
  ASSERT_EQ (two.size (), 2u);
  EXPECT_TRUE (two.is_dense);
  EXPECT_EQ (two[0].getNormalVector3fMap (), normals[210].getNormalVector3fMap ());
  EXPECT_EQ (two[1].getNormalVector3fMap (), normals[210].getNormalVector3fMap ());
  EXPECT_GT (std::abs (two[0].normal_z), 0.9f);
}

// A vertex no face uses is not part of the surface: it set the model's scale (a file's quantisation step and
// Harris's radius are fractions of it), 1.7e6 instead of 3.46 here, and moved the patches.
TEST (PclStages, AVertexNoFaceUsesDoesNotSetTheScale)
{
  const auto mesh = std::make_shared<TriangleMesh> (floatExactMesh ());
  auto stray = std::make_shared<TriangleMesh> (*mesh);
  stray->vertices.push_back (Eigen::Vector3d (1e6, 1e6, 1e6));
  SparseSurfaceModel without, with;
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (mesh);
  encoder.compute (without);
  encoder.setInputMesh (stray);
  encoder.compute (with);
  EXPECT_NEAR (without.bbox_diagonal, 2.0 * std::sqrt (3.0), 0.2);
  EXPECT_EQ (with.bbox_diagonal, without.bbox_diagonal);
  ASSERT_EQ (with.patches.size (), without.patches.size ());
  for (std::size_t p = 0; p < with.patches.size (); ++p)
    EXPECT_EQ (with.patches[p].origin, without.patches[p].origin) << p;
}

TEST (PclStages, CropIndicesOfEveryPointInAnotherOrder)
{
  // A cloud cropped with as many indices as it has points, in another order (here reversed): the surface's
  // vertices are the indexed points and getSurfaceInputIndices names each. pcl::copyPointCloud copies the
  // whole cloud unchanged for such indices, and every vertex was mapped to another point.
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      cloud->push_back (pcl::PointXYZ (1.0f + 0.1f * i, 0.1f * j, 0.05f * std::sin (0.3f * i) * std::cos (0.2f * j)));
  auto reversed = std::make_shared<pcl::Indices> ();
  for (int v = static_cast<int> (cloud->size ()) - 1; v >= 0; --v)
    reversed->push_back (v);
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputCloud (cloud);
  encoder.setIndices (reversed);
  SparseSurfaceModel model;
  encoder.compute (model);
  const std::vector<std::size_t>& from = encoder.getSurfaceInputIndices ();
  const TriangleMesh& surface = *encoder.getSurface ();
  ASSERT_EQ (from.size (), surface.vertices.size ());
  ASSERT_EQ (from.size (), cloud->size ());
  std::size_t misplaced = 0;
  for (std::size_t k = 0; k < from.size (); ++k)
    misplaced += ((surface.vertices[k] + encoder.getSurfaceOrigin ()).cast<float> () - (*cloud)[from[k]].getVector3fMap ())
                   .norm () > 1e-5f;
  EXPECT_EQ (misplaced, 0u);
}

TEST (PclStages, OneErrorPolicyNamingTheClass)
{
  const TriangleMesh mesh = floatExactMesh ();
  SparseSurfaceModel model;

  SparseSurfaceEncoder<pcl::PointXYZ> no_input;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { no_input.compute (model); }).find ("[SparseSurfaceEncoder::compute] no input"), std::string::npos);

  // A cloud without polygons is a scan; one whose every point is unusable is refused, naming the reason.
  auto unusable = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  unusable->push_back (pcl::PointXYZ (NAN, 0.0f, 0.0f));
  unusable->push_back (pcl::PointXYZ (0.0f, 0.0f, 0.0f));  // at the sensor origin: a lidar's "no return"
  SparseSurfaceEncoder<pcl::PointXYZ> no_points;
  no_points.setInputCloud (unusable);
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { no_points.compute (model); }).find ("[SparseSurfaceEncoder::compute] the cloud has no usable point"),
             std::string::npos);

  auto bad = polygonsOf (mesh);
  bad->back ().vertices[2] = static_cast<pcl::index_t> (mesh.numVertices ());
  SparseSurfaceEncoder<pcl::PointXYZ> out_of_range;
  out_of_range.setInputCloud (cloudOf<pcl::PointXYZ> (mesh));
  out_of_range.setInputPolygons (bad);
  const std::string out_of_range_error = pcl_sparse_test::errorMessage ([&] { out_of_range.compute (model); });
  EXPECT_EQ (out_of_range_error.rfind ("[SparseSurfaceEncoder::compute] ", 0), 0u) << out_of_range_error;
  EXPECT_NE (out_of_range_error.find ("out of range"), std::string::npos) << out_of_range_error;

  auto nan_cloud = cloudOf<pcl::PointXYZ> (mesh);
  (*nan_cloud)[mesh.triangles[0][1]].y = NAN;
  HarrisKeypoint3DMesh<pcl::PointXYZ> nan_corner;
  nan_corner.setInputCloud (nan_cloud);
  nan_corner.setInputPolygons (polygonsOf (mesh));
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { nan_corner.compute (keypoints); }).find ("[HarrisKeypoint3DMesh::compute] polygon corner"),
             std::string::npos);

  auto twice = std::make_shared<pcl::Indices> (pcl::Indices{0, 1, 1});
  FeatureAwarePatchSampling<pcl::PointXYZ> sampling;
  sampling.setInputMesh (std::make_shared<TriangleMesh> (mesh));
  sampling.setIndices (twice);
  std::vector<Patch> patches;
  const std::string twice_error = pcl_sparse_test::errorMessage ([&] { sampling.compute (patches); });
  EXPECT_EQ (twice_error.rfind ("[FeatureAwarePatchSampling::compute] ", 0), 0u) << twice_error;
  EXPECT_NE (twice_error.find ("listed twice"), std::string::npos) << twice_error;

  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputMesh (std::make_shared<TriangleMesh> (mesh));
  ne.setIndices (std::make_shared<pcl::Indices> (pcl::Indices{-1}));
  pcl::PointCloud<pcl::Normal> normals;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { ne.compute (normals); }).find ("[MeshNormalEstimation::compute] setIndices: index -1 out of range"),
             std::string::npos);

  SparseSurfaceResampling<pcl::PointXYZ> resampling;
  pcl::PointCloud<pcl::PointXYZ> cloud;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { resampling.compute (cloud); }).find ("[SparseSurfaceResampling::compute] no input model"),
             std::string::npos);
}

TEST (PclStages, ResamplingFillsEveryOutputPointType)
{
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (std::make_shared<TriangleMesh> (makeIcosphere (3)));
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);

  auto resample = [&] (auto& cloud) {
    SparseSurfaceResampling<typename std::decay_t<decltype (cloud)>::PointType> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (3000);
    resampling.compute (cloud);
  };
  pcl::PointCloud<pcl::PointNormal> reference;
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::PointCloud<pcl::PointXYZRGBNormal> rgb_normal;
  pcl::PointCloud<pcl::PointXYZINormal> intensity_normal;
  pcl::PointCloud<pcl::PointXYZRGB> rgb;
  resample (reference);
  resample (xyz);
  resample (rgb_normal);
  resample (intensity_normal);
  resample (rgb);
  ASSERT_EQ (reference.size (), 3000u);
  ASSERT_EQ (xyz.size (), 3000u);
  ASSERT_EQ (rgb.size (), 3000u);
  ASSERT_EQ (rgb_normal.size (), 3000u);
  ASSERT_EQ (intensity_normal.size (), 3000u);
  for (std::size_t i = 0; i < reference.size (); ++i)
  {
    EXPECT_EQ (xyz[i].getVector3fMap (), reference[i].getVector3fMap ());
    EXPECT_EQ (rgb[i].getVector3fMap (), reference[i].getVector3fMap ());
    EXPECT_EQ (rgb_normal[i].getVector3fMap (), reference[i].getVector3fMap ());
    EXPECT_EQ (rgb_normal[i].getNormalVector3fMap (), reference[i].getNormalVector3fMap ());
    EXPECT_EQ (rgb_normal[i].curvature, reference[i].curvature);
    EXPECT_EQ (intensity_normal[i].getVector3fMap (), reference[i].getVector3fMap ());
    EXPECT_EQ (intensity_normal[i].getNormalVector3fMap (), reference[i].getNormalVector3fMap ());
    EXPECT_NEAR (reference[i].getVector3fMap ().norm (), 1.0f, 0.03f);  // 642 vertices; dct measured 0.024
  }
}

// A mesh made from an organized cloud keeps its NaN points, used by no polygon. Each got a one-vertex patch
// with a NaN origin, and the model could be neither saved nor resampled (found by a review).
TEST (PclStages, UnreferencedNaNPointsAreLeftOut)
{
  const TriangleMesh mesh = floatExactMesh ();
  auto cloud = cloudOf<pcl::PointXYZ> (mesh);
  for (int k = 0; k < 3; ++k)
    cloud->push_back (pcl::PointXYZ (NAN, NAN, NAN));
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputCloud (cloud);
  encoder.setInputPolygons (polygonsOf (mesh));
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  for (const PatchCode& patch : model->patches)
    ASSERT_TRUE (patch.origin.allFinite ());
  std::vector<Eigen::Vector3d> vertices = mesh.vertices;
  vertices.resize (cloud->size (), Eigen::Vector3d::Zero ());
  EXPECT_EQ (model->statistics (vertices).uncovered, 3u);
  EXPECT_FALSE (encodeModel (*model).empty ());
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (2000);
  pcl::PointCloud<pcl::PointNormal> out;
  resampling.compute (out);
  EXPECT_EQ (out.size (), 2000u);
}

// As PCL's features and keypoints: the input's frame and stamp on the output, and an organized input's
// width x height on its normals (they came back as one row with an empty frame; found by a review).
TEST (PclStages, OutputsKeepTheInputsHeaderAndGrid)
{
  const TriangleMesh grid = makeHeightFieldGrid (11, 8, 1.0, 1.0, [] (double x, double y) { return 0.1 * x * y; });
  auto cloud = cloudOf<pcl::PointXYZ> (grid);
  cloud->width = 12;
  cloud->height = 9;
  ASSERT_EQ (cloud->size (), 108u) << "the grid's vertices are its 12 x 9 points";
  cloud->header.frame_id = "camera";
  cloud->header.stamp = 12345;
  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputCloud (cloud);
  ne.setInputPolygons (polygonsOf (grid));
  pcl::PointCloud<pcl::Normal> normals;
  ne.compute (normals);
  EXPECT_EQ (normals.header.frame_id, "camera");
  EXPECT_EQ (normals.header.stamp, 12345u);
  EXPECT_EQ (normals.width, 12u);
  EXPECT_EQ (normals.height, 9u);
  ne.setIndices (std::make_shared<pcl::Indices> (pcl::Indices{0, 5, 7}));
  ne.compute (normals);
  EXPECT_EQ (normals.width, 3u);  // a selection is a list, as in PCL
  EXPECT_EQ (normals.height, 1u);
  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputCloud (cloud);
  harris.setInputPolygons (polygonsOf (grid));
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  EXPECT_EQ (keypoints.header.frame_id, "camera");
  EXPECT_EQ (harris.getKeypointsIndices ()->header.frame_id, "camera");
}

// Misuse found by a review, each refused with the reason instead of crashing, reading out of bounds or
// giving a model nothing can save.
TEST (PclStages, MisuseIsRefusedWithTheReason)
{
  const TriangleMesh mesh = floatExactMesh ();
  SparseSurfaceEncoder<pcl::PointXYZRGB> encoder;
  auto cloud = cloudOf<pcl::PointXYZRGB> (mesh);
  for (auto& p : *cloud)
    p.r = p.g = p.b = static_cast<std::uint8_t> (128.0f + 100.0f * p.z);
  encoder.setInputCloud (cloud);
  encoder.setInputPolygons (polygonsOf (mesh));
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_FALSE (model->attribute_channels.empty ());

  // An attribute atom outside the basis was read past the evaluator's tables when resampling.
  SparseSurfaceResampling<pcl::PointXYZRGB> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (500);
  pcl::PointCloud<pcl::PointXYZRGB> out;
  resampling.compute (out);
  ASSERT_EQ (out.size (), 500u);
  SparseCode& code = model->patches[0].attributes[0];
  code.atoms.push_back (model->attribute_basis->size ());
  code.coefficients.push_back (1.0);
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { resampling.compute (out); }).find ("attribute atom 144 outside the basis"), std::string::npos);
  EXPECT_TRUE (out.empty ()) << "a failed compute leaves no stale result";

  // Options that gave a model the file format cannot hold.
  SparseSurfaceEncoderOptions options;
  options.coding.footprint_angles = 5000;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { options.validate (); }).find ("coding.footprint_angles = 5000 is out of range"), std::string::npos);
  options = SparseSurfaceEncoderOptions ();
  options.coding.triangle_samples = 1e9;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { options.validate (); }).find ("coding.triangle_samples = 1e+09 is out of range"), std::string::npos);
  options = SparseSurfaceEncoderOptions ();
  options.dictionary_frequencies = 64;
  options.coding.min_samples = 100000;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { options.validate (); }).find ("min samples x atoms"), std::string::npos);
  options = SparseSurfaceEncoderOptions ();
  options.patches.rho = 0.0;  // std::to_string wrote "got 0.000000"
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { options.validate (); }),
             "SparseSurfaceEncoderOptions: patches.rho = 0 is out of range (rho > 0)");
  options = SparseSurfaceEncoderOptions ();
  options.coding.tolerance = 1e-12;  // valid: no message
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { options.validate (); }), "");
  options.coding.noise_level = -1e-9;
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { options.validate (); }),
             "SparseSurfaceEncoderOptions: coding.noise_level = -1e-09 is out of range (noise_level >= 0, finite)");
  // Values in their exact form (std::to_string wrote an int 0 as 0.000000 and 1e-9 as 0.000000).
  PatchOptions patch_options;
  patch_options.min_patch_size = 0;
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { patch_options.validate (); }),
             "PatchOptions: min_patch_size = 0 is out of range (min_patch_size >= 1)");
  patch_options = PatchOptions ();
  patch_options.rho = -1e-9;
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { patch_options.validate (); }), "PatchOptions: rho = -1e-09 is out of range (rho >= 0, finite)");

  // Thread counts out of range are refused by the setter, naming it.
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { encoder.setNumberOfThreads (-1); }).find ("[SparseSurfaceEncoder::setNumberOfThreads]"),
             std::string::npos);
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { encoder.setNumberOfThreads (100000); }).find ("in [0, 1024]"), std::string::npos);

  // Empty crop indices are named as such.
  SparseSurfaceEncoder<pcl::PointXYZ> cropped;
  cropped.setInputMesh (std::make_shared<TriangleMesh> (mesh));
  cropped.setIndices (std::make_shared<pcl::Indices> ());
  SparseSurfaceModel none;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { cropped.compute (none); }).find ("setIndices: the indices are empty"), std::string::npos);
}

// A tiny clustering radius made the grid's int cells overflow (undefined behaviour); the cells are 64-bit
// from the box's corner now, and a radius below every distance keeps every maximum, as no clustering does.
TEST (PclStages, HarrisClusteringAtATinyRadius)
{
  const auto mesh = std::make_shared<TriangleMesh> (floatExactMesh ());
  auto keypointsWith = [&] (double fraction) {
    HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
    harris.setInputMesh (mesh);
    Harris3DOptions options;
    options.selection = Harris3DSelection::Clustering;
    options.cluster_fraction = fraction;
    harris.setOptions (options);
    pcl::PointCloud<pcl::PointXYZI> keypoints;
    harris.compute (keypoints);
    return harris.getKeypointsIndices ()->indices;
  };
  const auto none = keypointsWith (0.0);
  ASSERT_GT (none.size (), 8u);
  EXPECT_EQ (keypointsWith (1e-12), none);
  EXPECT_LT (keypointsWith (0.5).size (), none.size ());
}

// A cloud read with the wrong byte order (a big-endian PointCloud2 taken as little-endian) holds values up to
// 3e38: the encoder's range check came after the scan's kd-tree, which aborted in FLANN (found by a review
// of the ROS node). It is refused with the reason now.
TEST (PclStages, CloudInTheWrongByteOrderIsRefused)
{
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  auto swapped = [] (float v) {
    std::uint32_t bits = 0;
    std::memcpy (&bits, &v, 4);
    bits = __builtin_bswap32 (bits);
    std::memcpy (&v, &bits, 4);
    return v;
  };
  for (int i = 0; i < 3000; ++i)
    cloud->push_back (pcl::PointXYZ (swapped (0.01f * static_cast<float> (i % 60)), swapped (0.01f * static_cast<float> (i / 60)),
                                     swapped (0.0f)));
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputCloud (cloud);
  SparseSurfaceModel model;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { encoder.compute (model); }).find ("beyond the 1e30 that float clouds hold"), std::string::npos);
}

// A scan's scale is its surface's: one stray return 1000 away set the model's diagonal, and with it a
// file's quantisation step, 1300x too coarse (found by a review of the ROS node's ~model bytes).
TEST (PclStages, StrayPointDoesNotSetTheScansScale)
{
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  for (int i = 0; i < 3000; ++i)
    cloud->push_back (pcl::PointXYZ (0.01f * static_cast<float> (i % 60), 0.01f * static_cast<float> (i / 60),
                                     0.05f * std::sin (0.1f * static_cast<float> (i % 60))));
  auto encode = [] (const pcl::PointCloud<pcl::PointXYZ>::Ptr& input) {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputCloud (input);
    encoder.setViewPoint (0.3f, 0.25f, 2.0f);
    SparseSurfaceModel model;
    encoder.compute (model);
    return model;
  };
  const SparseSurfaceModel clean = encode (cloud);
  ASSERT_GT (clean.bbox_diagonal, 0.7);
  ASSERT_LT (clean.bbox_diagonal, 0.8);
  auto stray = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> (*cloud);
  stray->push_back (pcl::PointXYZ (1000.0f, 0.0f, 0.0f));
  EXPECT_DOUBLE_EQ (encode (stray).bbox_diagonal, clean.bbox_diagonal);
}

// A triangle soup (faces sharing no vertex, as PCL's VTK OBJ reader makes of a file with per-corner
// normals) gave one patch per face without an atom; it is refused, saying how to weld it.
TEST (PclStages, TriangleSoupIsRefusedWithTheRemedy)
{
  const TriangleMesh mesh = floatExactMesh ();
  const TriangleMesh soup = robustness::triangleSoup (mesh);
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputCloud (cloudOf<pcl::PointXYZ> (soup));
  encoder.setInputPolygons (polygonsOf (soup));
  SparseSurfaceModel model;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { encoder.compute (model); }).find ("share no vertex (a triangle soup"), std::string::npos);
  encoder.setInputCloud (cloudOf<pcl::PointXYZ> (mesh));  // the same faces welded
  encoder.setInputPolygons (polygonsOf (mesh));
  encoder.compute (model);
  EXPECT_GT (model.numNonZeros (), 0u);
}

// Repeated faces (the same three vertices, in any order or winding) add no surface, but each copy used to be
// counted again: in area-weighted normals, in Harris neighbourhoods, and as one more patch (3000 copies of one
// triangle gave 3000 stacked patches and a file 30 times the mesh). Every stage now leaves the copies out.
TEST (PclStages, RepeatedFacesAreCountedOnce)
{
  const auto mesh = std::make_shared<TriangleMesh> (floatExactMesh ());
  auto repeated = std::make_shared<TriangleMesh> (*mesh);
  std::size_t copies = 0;
  for (std::size_t f = 0; f < mesh->triangles.size (); f += 7, ++copies)
  {
    const Eigen::Vector3i& t = mesh->triangles[f];
    // Same winding rotated, reversed winding, and the same face many times over.
    repeated->triangles.push_back (copies % 3 == 0 ? Eigen::Vector3i (t[1], t[2], t[0])
                                   : copies % 3 == 1 ? Eigen::Vector3i (t[0], t[2], t[1])
                                                     : t);
  }
  for (int k = 0; k < 200; ++k, ++copies)
    repeated->triangles.push_back (mesh->triangles[5]);
  ASSERT_GT (copies, 250u);

  SparseSurfaceEncoder<pcl::PointXYZ> reference;
  reference.setInputMesh (mesh);
  SparseSurfaceModel expected;
  reference.compute (expected);
  EXPECT_EQ (reference.getDuplicateFaces (), 0u);

  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (repeated);
  // A topology built over the copies is not the one the stage works on: it is rebuilt.
  encoder.setTopology (std::make_shared<const MeshTopology> (buildMeshTopology (*repeated)));
  SparseSurfaceModel model;
  encoder.compute (model);
  EXPECT_EQ (encoder.getDuplicateFaces (), copies);
  EXPECT_EQ (encoder.getSurface ()->triangles.size (), mesh->triangles.size ());
  EXPECT_EQ (model.numPatches (), expected.numPatches ());
  EXPECT_EQ (modelBytes (model), modelBytes (expected));

  // PCL's input (cloud and polygons) and the other stages alike.
  MeshNormalEstimation<pcl::PointXYZ> normals;
  normals.setInputCloud (cloudOf<pcl::PointXYZ> (*repeated));
  normals.setInputPolygons (polygonsOf (*repeated));
  pcl::PointCloud<pcl::PointNormal> with_copies;
  normals.compute (with_copies);
  EXPECT_EQ (normals.getDuplicateFaces (), copies);
  normals.setInputPolygons (polygonsOf (*mesh));
  pcl::PointCloud<pcl::PointNormal> without;
  normals.compute (without);
  ASSERT_EQ (with_copies.size (), without.size ());
  for (std::size_t i = 0; i < without.size (); ++i)
    ASSERT_EQ (with_copies[i].getNormalVector3fMap (), without[i].getNormalVector3fMap ()) << i;

  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputMesh (repeated);
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  HarrisKeypoint3DMesh<pcl::PointXYZ> clean_harris;
  clean_harris.setInputMesh (mesh);
  pcl::PointCloud<pcl::PointXYZI> clean_keypoints;
  clean_harris.compute (clean_keypoints);
  EXPECT_EQ (harris.getKeypointsIndices ()->indices, clean_harris.getKeypointsIndices ()->indices);
}
