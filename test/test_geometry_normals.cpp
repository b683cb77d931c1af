#include <pcl_sparse/common/error.h>
#include <pcl_sparse/normals/mesh_normal_estimation.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

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
  // The surface variation of a vertex and its k neighbours all at angle theta on the unit sphere, a regular
  // ring: heights 0 and h = 1 - cos theta, radii r = sin theta, so lambda0 / (lambda0 + lambda1 + lambda2) =
  // h^2 / (h^2 + (k + 1) r^2), about theta^2 / (4 (k + 1)) (7e-4 at this level's theta = 0.14). The
  // icosphere's rings are nearly regular: theta is each ring's mean angle.
  const MeshTopology sphere_topology = buildMeshTopology (*sphere);
  double lowest = 1e9, highest = 0.0;
  for (std::size_t v = 0; v < points.size (); ++v)
  {
    const auto& p = points[v];
    EXPECT_GT (p.getNormalVector3fMap ().dot (p.getVector3fMap ()), 0.999f);
    const auto ring = sphere_topology.neighborsOf (static_cast<int> (v));
    double theta = 0.0;
    for (int u : ring)
      theta += std::acos (std::min (1.0, sphere->vertices[v].dot (sphere->vertices[u]))) / static_cast<double> (ring.size ());
    const double h = 1.0 - std::cos (theta), r = std::sin (theta);
    const double ratio = p.curvature / (h * h / (h * h + static_cast<double> (ring.size () + 1) * r * r));
    lowest = std::min (lowest, ratio);
    highest = std::max (highest, ratio);
  }
  std::cout << "sphere surface variation / regular-ring value: " << lowest << " .. " << highest << std::endl;
  EXPECT_GT (lowest, 0.9);  // measured 0.994 .. 1.112
  EXPECT_LT (highest, 1.2);

  // No input: an Error naming the stage, and an empty output.
  MeshNormalEstimation<pcl::PointXYZ> empty;
  normals.resize (4);
  EXPECT_THROW (empty.compute (normals), Error);
  EXPECT_TRUE (normals.empty ());
}
