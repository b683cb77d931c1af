#include <pcl_sparse/common/error.h>
#include <pcl_sparse/normals/mesh_normal_estimation.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_sparse;

TEST (MeshNormals, CubeFaceNormalsPointOutwardAndAreasSumUp)
{
  const TriangleMesh mesh = makeCube (5, 1.0);
  const auto normals = computeFaceNormals (mesh);
  const auto areas = computeFaceAreas (mesh);
  double total = 0.0;
  for (std::size_t f = 0; f < mesh.numTriangles (); ++f)
  {
    const auto& t = mesh.triangles[f];
    const Eigen::Vector3d centroid = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
    int axis;
    centroid.cwiseAbs ().maxCoeff (&axis);
    Eigen::Vector3d expected = Eigen::Vector3d::Zero ();
    expected[axis] = centroid[axis] > 0 ? 1.0 : -1.0;
    EXPECT_NEAR ((normals[f] - expected).norm (), 0.0, 1e-12);
    total += areas[f];
  }
  EXPECT_NEAR (total, 24.0, 1e-12);
}

TEST (MeshNormals, SphereVertexNormalsAreRadial)
{
  const TriangleMesh mesh = makeIcosphere (4, 2.0);
  const MeshTopology topo = buildMeshTopology (mesh);
  for (NormalWeighting w : {NormalWeighting::Area, NormalWeighting::Angle})
  {
    const auto normals = computeVertexNormals (mesh, topo, w);
    for (std::size_t v = 0; v < mesh.numVertices (); ++v)
      EXPECT_GT (normals[v].dot (mesh.vertices[v].normalized ()), std::cos (0.5 * M_PI / 180.0));
  }
}

TEST (MeshNormals, AngleWeightedCubeCornerIsTheDiagonal)
{
  // Each face meets the corner with a total angle of 90 degrees, however it is triangulated, so the
  // angle-weighted normal is exactly the diagonal; the area-weighted one depends on the triangulation.
  const TriangleMesh mesh = makeCube (4, 1.0);
  const MeshTopology topo = buildMeshTopology (mesh);
  const auto normals = computeVertexNormals (mesh, topo, NormalWeighting::Angle);
  int corners = 0;
  for (std::size_t v = 0; v < mesh.numVertices (); ++v)
    if ((mesh.vertices[v].cwiseAbs ().array () - 1.0).abs ().maxCoeff () < 1e-12)
    {
      ++corners;
      EXPECT_NEAR ((normals[v] - mesh.vertices[v] / std::sqrt (3.0)).norm (), 0.0, 1e-12);
    }
  EXPECT_EQ (corners, 8);
}

TEST (MeshNormalEstimation, FillsNormalsAndPositionsLikePcl)
{
  TriangleMesh mesh = makePlaneGrid (6, 1.0);
  mesh.vertices.emplace_back (5.0, 5.0, 5.0);  // unreferenced: no normal
  auto shared = std::make_shared<TriangleMesh> (mesh);
  MeshNormalEstimation<pcl::PointXYZ> ne;
  ne.setInputMesh (shared);
  pcl::PointCloud<pcl::Normal> normals;
  ne.compute (normals);
  ASSERT_EQ (normals.size (), mesh.numVertices ());
  EXPECT_FALSE (normals.is_dense);
  for (std::size_t v = 0; v + 1 < mesh.numVertices (); ++v)
  {
    EXPECT_NEAR (normals[v].normal_z, 1.0f, 1e-6f);
    EXPECT_NEAR (normals[v].curvature, 0.0f, 1e-6f);  // flat: no surface variation
  }
  EXPECT_TRUE (std::isnan (normals.back ().normal_x));
  EXPECT_TRUE (std::isnan (normals.back ().curvature));

  pcl::PointCloud<pcl::PointNormal> points;
  ne.setWeighting (NormalWeighting::Angle);
  ne.compute (points);
  ASSERT_EQ (points.size (), mesh.numVertices ());
  EXPECT_EQ (points.width, mesh.numVertices ());
  EXPECT_EQ (points[7].getVector3fMap (), mesh.vertices[7].cast<float> ());
  EXPECT_NEAR (points[7].normal_z, 1.0f, 1e-6f);

  // Sphere: curvature (surface variation) positive and uniform-ish, normals outward and dense.
  auto sphere = std::make_shared<TriangleMesh> (makeIcosphere (3));
  ne.setInputMesh (sphere);
  ne.compute (points);
  EXPECT_TRUE (points.is_dense);
  for (const auto& p : points)
  {
    EXPECT_GT (p.getNormalVector3fMap ().dot (p.getVector3fMap ()), 0.999f);
    EXPECT_GT (p.curvature, 0.0f);
  }

  // No input: an Error naming the stage, and an empty output.
  MeshNormalEstimation<pcl::PointXYZ> empty;
  normals.resize (4);
  EXPECT_THROW (empty.compute (normals), Error);
  EXPECT_TRUE (normals.empty ());
}
