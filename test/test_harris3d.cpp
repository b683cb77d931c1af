#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/geometry/sharp_edges.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/keypoints/harris_keypoint3d_mesh.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "error_message.h"
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>

#include "shared_data.h"

using namespace pcl_sparse;

namespace
{
  /// R of a quadric with no linear term, by hand: E = 2 H^2 with H = [[a, b], [b, c]].
  double
  responseOfHessian (double a, double b, double c, double k)
  {
    const double A = 2.0 * (a * a + b * b), B = 2.0 * (b * b + c * c), C = 2.0 * (a * b + b * c);
    return A * B - C * C - k * (A + B) * (A + B);
  }

  bool
  isCubeCorner (const Eigen::Vector3d& p, double half)
  {
    return (p.cwiseAbs ().array () - half).abs ().maxCoeff () < 1e-12;
  }

  TriangleMesh
  bumpyTorus ()
  {
    TriangleMesh mesh = makeTorus (96, 48, 1.0, 0.35);
    std::mt19937 mt (7);
    std::normal_distribution<double> noise (0.0, 0.004);
    for (auto& p : mesh.vertices)
      p += Eigen::Vector3d (noise (mt), noise (mt), noise (mt));
    return mesh;
  }
} // namespace

TEST (Harris3D, ResponseOfQuadricMatchesHandComputation)
{
  // p1 = 1, p2 = 0.5, p3 = -2, p4 = 0.3, p5 = -0.1: A = 2.59, B = 8.51, C = -1.03,
  // det E = 20.98, tr E = 11.1, R = 20.98 - 0.04 * 123.21 = 16.0516.
  HeightQuadric q;
  q.c << 5.0, 0.3, -0.1, 1.0, 0.5, -2.0;
  EXPECT_NEAR (harris3DResponseOfQuadric (q, 0.04), 16.0516, 1e-12);
  EXPECT_NEAR (harris3DResponseOfQuadric (q, 0.0), 20.98, 1e-12);
  // A plane has E = p p^T: det 0, R = -k |p|^4.
  HeightQuadric plane;
  plane.c << 0.0, 3.0, 4.0, 0.0, 0.0, 0.0;
  EXPECT_NEAR (harris3DResponseOfQuadric (plane, 0.04), -0.04 * 625.0, 1e-12);
}

TEST (Harris3D, AnalyticQuadricMatchesClosedFormUnderRigidMotion)
{
  // z = a x^2 / 2 + b x y + c y^2 / 2 sampled on a grid, then rotated and moved. The 2-ring of the
  // origin vertex is centrally symmetric, so its PCA normal is the quadric's axis and the fit is exact:
  // R is the closed form of (a, b, c) with no linear terms, whatever the rigid motion.
  const double a = 0.8, b = 0.3, c = -0.5;
  const int n = 100;
  TriangleMesh mesh = makeHeightFieldGrid (n, n, 1.0, 1.0, [&] (double x, double y) { return 0.5 * a * x * x + b * x * y + 0.5 * c * y * y; });
  const Eigen::Affine3d motion = Eigen::Translation3d (3.0, -1.0, 2.0) *
                                 Eigen::AngleAxisd (0.7, Eigen::Vector3d (1.0, 2.0, 0.5).normalized ());
  for (auto& p : mesh.vertices)
    p = motion * p;
  const MeshTopology topo = buildMeshTopology (mesh);
  const int origin = (n / 2) * (n + 1) + n / 2;
  Harris3DOptions options;
  options.rings = 2;
  const std::vector<int> only = {origin};
  const std::vector<double> r = computeHarris3DResponses (mesh, topo, options, only);
  const double expected = responseOfHessian (a, b, c, 0.04);
  EXPECT_NEAR (r[origin], expected, 1e-9 * std::abs (expected));
  EXPECT_TRUE (std::isnan (r[origin + 1]));  // not requested
  // Also with the adaptive neighbourhood (radius 0.01 x diagonal here: 1 ring, 8 neighbours).
  options.rings = 0;
  const std::vector<double> adaptive = computeHarris3DResponses (mesh, topo, options, only);
  EXPECT_NEAR (adaptive[origin], expected, 1e-9 * std::abs (expected));
}

TEST (Harris3D, SphereResponsesAreNearlyUniform)
{
  // Sphere of radius r: H = I / r, no linear term, so R = (4 - 16 k) / r^4 everywhere.
  const double r = 1.5;
  const TriangleMesh mesh = makeIcosphere (4, r);
  const MeshTopology topo = buildMeshTopology (mesh);
  const std::vector<double> responses = computeHarris3DResponses (mesh, topo);
  const auto [lo, hi] = std::minmax_element (responses.begin (), responses.end ());
  double mean = 0.0;
  for (double x : responses)
    mean += x;
  mean /= static_cast<double> (responses.size ());
  const double expected = (4.0 - 16.0 * 0.04) / std::pow (r, 4);
  EXPECT_NEAR (mean, expected, 0.02 * expected);
  EXPECT_LT ((*hi - *lo) / std::abs (mean), 0.05) << "spread of the responses over the sphere";
  std::cout << "sphere: mean " << mean << " (closed form " << expected << "), spread " << (*hi - *lo) / std::abs (mean) << "\n";
}

TEST (Harris3D, CubeCornersRankTop)
{
  const double half = 1.0;
  const TriangleMesh mesh = makeCube (10, half);
  const MeshTopology topo = buildMeshTopology (mesh);
  // Default (adaptive) neighbourhood: the 8 corners are the 8 largest responses.
  const std::vector<double> responses = computeHarris3DResponses (mesh, topo);
  const std::vector<int> order = orderVerticesByResponse (responses);
  for (int i = 0; i < 8; ++i)
    EXPECT_TRUE (isCubeCorner (mesh.vertices[order[i]], half)) << "rank " << i;
  EXPECT_FALSE (isCubeCorner (mesh.vertices[order[8]], half));

  // Fixed 2 rings: makeCube splits every quad along the same diagonal, so 6 corners have 4 neighbours
  // and a lopsided 2-ring; there the strongest vertex sits one edge off the corner. The 8 keypoints
  // still mark the 8 corners, each within 1 ring of a different corner.
  Harris3DOptions two_rings;
  two_rings.rings = 2;
  const std::vector<double> ring_responses = computeHarris3DResponses (mesh, topo, two_rings);
  two_rings.selection_fraction = 8.0 / static_cast<double> (mesh.numVertices ());
  const std::vector<int> keys = selectHarris3DKeypoints (mesh, topo, ring_responses, two_rings, mesh.numVertices ());
  ASSERT_EQ (keys.size (), 8u);
  std::vector<int> corners_hit;
  for (int v : keys)
    for (int u : kRing (topo, v, 1))
      if (isCubeCorner (mesh.vertices[u], half))
        corners_hit.push_back (u);
  std::sort (corners_hit.begin (), corners_hit.end ());
  corners_hit.erase (std::unique (corners_hit.begin (), corners_hit.end ()), corners_hit.end ());
  EXPECT_EQ (corners_hit.size (), 8u);

  // The stage: keep 8 keypoints (fraction 8 / #V): exactly the corners, in decreasing response.
  auto shared = std::make_shared<TriangleMesh> (mesh);
  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputMesh (shared);
  harris.setSelectionFraction (8.0 / static_cast<double> (mesh.numVertices ()));
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  ASSERT_EQ (keypoints.size (), 8u);
  const auto& indices = harris.getKeypointsIndices ()->indices;
  ASSERT_EQ (indices.size (), 8u);
  for (std::size_t i = 0; i < 8; ++i)
  {
    EXPECT_TRUE (isCubeCorner (mesh.vertices[indices[i]], half));
    EXPECT_EQ (keypoints[i].getVector3fMap (), mesh.vertices[indices[i]].cast<float> ());
    EXPECT_EQ (keypoints[i].intensity, static_cast<float> (harris.getResponses ()[indices[i]]));
    if (i > 0)
      EXPECT_GE (keypoints[i - 1].intensity, keypoints[i].intensity);
  }
  EXPECT_EQ (harris.getResponses ().size (), mesh.numVertices ());
}

TEST (Harris3D, ClusteringKeepsKeypointsApart)
{
  const TriangleMesh mesh = makeCube (12, 1.0);
  auto shared = std::make_shared<TriangleMesh> (mesh);
  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputMesh (shared);
  harris.setClustering (0.2);  // 0.2 x 2 sqrt 3 = 0.69
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  const double radius = 0.2 * boundingBoxDiagonal (mesh);
  ASSERT_GE (keypoints.size (), 8u);
  for (std::size_t i = 0; i < keypoints.size (); ++i)
    for (std::size_t j = i + 1; j < keypoints.size (); ++j)
      EXPECT_GE ((keypoints[i].getVector3fMap () - keypoints[j].getVector3fMap ()).norm (), radius * (1 - 1e-6));
  int corners = 0;
  for (int v : harris.getKeypointsIndices ()->indices)
    corners += isCubeCorner (mesh.vertices[v], 1.0);
  EXPECT_EQ (corners, 8);
}

TEST (Harris3D, KeypointsAreLocalMaximaAndTheFractionIsRespected)
{
  const TriangleMesh mesh = bumpyTorus ();
  const MeshTopology topo = buildMeshTopology (mesh);
  const std::vector<double> responses = computeHarris3DResponses (mesh, topo);
  Harris3DOptions options;
  const std::vector<int> keys = selectHarris3DKeypoints (mesh, topo, responses, options, mesh.numVertices ());
  EXPECT_EQ (keys.size (), static_cast<std::size_t> (std::lround (0.01 * mesh.numVertices ())));
  for (std::size_t i = 0; i < keys.size (); ++i)
  {
    EXPECT_TRUE (isHarris3DLocalMaximum (topo, responses, keys[i]));
    for (int u : topo.neighborsOf (keys[i]))
      EXPECT_GE (responses[keys[i]], responses[u]);
    if (i > 0)
      EXPECT_GE (responses[keys[i - 1]], responses[keys[i]]);
  }
  // orderVerticesByResponse: a permutation, decreasing.
  const std::vector<int> order = orderVerticesByResponse (responses);
  ASSERT_EQ (order.size (), mesh.numVertices ());
  for (std::size_t i = 1; i < order.size (); ++i)
    EXPECT_TRUE (responses[order[i - 1]] > responses[order[i]] ||
                 (responses[order[i - 1]] == responses[order[i]] && order[i - 1] < order[i]));
}

TEST (Harris3D, SortByRankIsTheOrderOfRanksBefore)
{
  // More vertices than are sorted on one thread; equal responses, -0 and 0, NaN and infinities (no
  // response) in a shuffled subset.
  std::mt19937 random (7);
  std::vector<double> responses (200000);
  for (double& r : responses)
    r = static_cast<double> (random () % 1000) - 500.0;
  const double specials[] = {0.0, -0.0, std::nan (""), INFINITY, -INFINITY};
  for (std::size_t i = 0; i < responses.size (); i += 7)
    responses[i] = specials[(i / 7) % 5];
  std::vector<int> vertices (150000);
  std::iota (vertices.begin (), vertices.end (), 30000);
  std::shuffle (vertices.begin (), vertices.end (), random);
  std::vector<int> expected = vertices;
  std::sort (expected.begin (), expected.end (), [&responses] (int a, int b) { return harris3DRanksBefore (responses, a, b); });
  for (const int threads : {1, 2})
  {
    std::vector<int> sorted = vertices;
    sortByHarris3DRank (responses, sorted, threads);
    EXPECT_EQ (sorted, expected) << threads << " threads";
  }
}

TEST (Harris3D, SameOutputForAnyThreadCount)
{
  const auto mesh = std::make_shared<TriangleMesh> (bumpyTorus ());
  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputMesh (mesh);
  pcl::PointCloud<pcl::PointXYZI> one, two, explicit_two;
  omp_set_num_threads (1);
  harris.compute (one);
  const std::vector<double> responses_one = harris.getResponses ();
  omp_set_num_threads (2);
  harris.compute (two);
  const std::vector<double> responses_two = harris.getResponses ();
  harris.setNumberOfThreads (2);
  harris.compute (explicit_two);
  ASSERT_EQ (responses_one.size (), responses_two.size ());
  EXPECT_EQ (0, std::memcmp (responses_one.data (), responses_two.data (), responses_one.size () * sizeof (double)));
  EXPECT_EQ (0, std::memcmp (responses_one.data (), harris.getResponses ().data (), responses_one.size () * sizeof (double)));
  ASSERT_EQ (one.size (), two.size ());
  ASSERT_EQ (one.size (), explicit_two.size ());
  for (std::size_t i = 0; i < one.size (); ++i)
  {
    EXPECT_EQ (one[i].getVector4fMap (), two[i].getVector4fMap ());
    EXPECT_EQ (one[i].intensity, two[i].intensity);
    EXPECT_EQ (one[i].intensity, explicit_two[i].intensity);
  }
}

TEST (Harris3D, IndicesRestrictDetection)
{
  const auto mesh = std::make_shared<TriangleMesh> (bumpyTorus ());
  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputMesh (mesh);
  pcl::PointCloud<pcl::PointXYZI> all, some;
  harris.compute (all);
  const std::vector<double> full = harris.getResponses ();
  auto indices = std::make_shared<std::vector<int>> ();
  for (int v = 0; v < static_cast<int> (mesh->numVertices ()); v += 3)
    indices->push_back (v);
  harris.setIndices (indices);
  harris.compute (some);
  const std::vector<double>& partial = harris.getResponses ();
  for (int v = 0; v < static_cast<int> (mesh->numVertices ()); ++v)
  {
    if (v % 3 == 0)
      EXPECT_EQ (partial[v], full[v]);
    else
      EXPECT_TRUE (std::isnan (partial[v]));
  }
  EXPECT_EQ (some.size (), static_cast<std::size_t> (std::lround (0.01 * indices->size ())));
  for (int v : harris.getKeypointsIndices ()->indices)
    EXPECT_EQ (v % 3, 0);
  // Repeated indices are harmless.
  auto repeated = std::make_shared<std::vector<int>> (*indices);
  repeated->insert (repeated->end (), indices->begin (), indices->end ());
  harris.setIndices (repeated);
  pcl::PointCloud<pcl::PointXYZI> twice;
  harris.compute (twice);
  for (int v = 0; v < static_cast<int> (mesh->numVertices ()); v += 3)
    EXPECT_EQ (harris.getResponses ()[v], full[v]);
  EXPECT_EQ (twice.size (), some.size ());  // the fraction counts distinct vertices
  // Indices given as all vertices: the same as none (PCL's setIndices cannot be unset).
  auto every = std::make_shared<std::vector<int>> (mesh->numVertices ());
  std::iota (every->begin (), every->end (), 0);
  harris.setIndices (every);
  harris.compute (some);
  ASSERT_EQ (some.size (), all.size ());
  for (std::size_t i = 0; i < all.size (); ++i)
    EXPECT_EQ (some[i].intensity, all[i].intensity);
}

TEST (Harris3D, TooFewNeighboursGiveNoResponseAndBadInputIsRefused)
{
  const auto tetra = std::make_shared<TriangleMesh> (makeTetrahedron ());
  HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
  harris.setInputMesh (tetra);
  pcl::PointCloud<pcl::PointXYZI> keypoints;
  harris.compute (keypoints);
  EXPECT_TRUE (keypoints.empty ());
  ASSERT_EQ (harris.getResponses ().size (), 4u);
  for (double r : harris.getResponses ())
    EXPECT_TRUE (std::isnan (r));

  HarrisKeypoint3DMesh<pcl::PointXYZ> no_input;
  keypoints.resize (3);
  EXPECT_THROW (no_input.compute (keypoints), Error);
  EXPECT_TRUE (keypoints.empty ());

  HarrisKeypoint3DMesh<pcl::PointXYZ> bad_index;
  bad_index.setInputMesh (std::make_shared<TriangleMesh> (makeCube (4)));
  bad_index.setIndices (std::make_shared<std::vector<int>> (std::vector<int>{0, 100000}));
  keypoints.resize (3);
  EXPECT_THROW (bad_index.compute (keypoints), Error);
  EXPECT_TRUE (keypoints.empty ());

  const TriangleMesh cube = makeCube (4);
  const MeshTopology topo = buildMeshTopology (cube);
  Harris3DOptions options;
  options.selection_fraction = 0.0;
  EXPECT_THROW (computeHarris3DResponses (cube, topo, options), Error);
  options = Harris3DOptions ();
  options.rings = -1;
  EXPECT_THROW (computeHarris3DResponses (cube, topo, options), Error);
  options = Harris3DOptions ();
  options.adaptive_fraction = 0.0;
  EXPECT_THROW (computeHarris3DResponses (cube, topo, options), Error);
  // The message names the field and its value as the other options structs' do.
  options = Harris3DOptions ();
  options.k = 0.3;
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { computeHarris3DResponses (cube, topo, options); }),
             "Harris3DOptions: k = 0.3 is out of range (0 <= k <= 0.25)");
}

TEST (Harris3D, FandiskTopKeypointsLieOnSharpEdges)
{
  const std::filesystem::path path = std::filesystem::path (PCL_SPARSE_SHARED_MESHES) / "fandisk.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path.string ()));
  ASSERT_EQ (mesh->numVertices (), 6475u);
  const MeshTopology topo = buildMeshTopology (*mesh);
  const std::vector<bool> near = verticesNearSharpEdges (*mesh, topo, 60.0, 2);
  // Nearly half of fandisk's vertices lie that near a sharp edge, so a bound must be well above chance.
  const double chance = static_cast<double> (std::count (near.begin (), near.end (), true)) / near.size ();
  EXPECT_NEAR (chance, 0.476, 0.001);

  for (int rings : {0, 2})
  {
    HarrisKeypoint3DMesh<pcl::PointXYZ> harris;
    harris.setInputMesh (mesh);
    harris.setRings (rings);
    pcl::PointCloud<pcl::PointXYZI> keypoints;
    harris.compute (keypoints);
    const auto& indices = harris.getKeypointsIndices ()->indices;
    EXPECT_EQ (indices.size (), 65u);  // round (0.01 x 6475)
    int on_edges = 0;
    for (int v : indices)
      on_edges += near[v];
    const double fraction = static_cast<double> (on_edges) / static_cast<double> (indices.size ());
    EXPECT_GE (fraction, 0.95) << "rings " << rings;  // measured 63 / 65 and 65 / 65
    std::cout << "fandisk (rings " << rings << "): " << on_edges << " / " << indices.size () << " keypoints within 2 rings of a sharp edge\n";
  }
}

TEST (SharpEdges, CubeEdgesAreSharpAndSpheresHaveNone)
{
  const TriangleMesh cube = makeCube (4, 1.0);
  const MeshTopology topo = buildMeshTopology (cube);
  const std::vector<int> sharp = findSharpEdges (cube, topo, 60.0);
  EXPECT_EQ (sharp.size (), 12u * 4u);  // 12 cube edges of 4 segments, dihedral 90 degrees
  for (int e : sharp)
  {
    const Eigen::Vector3d mid = 0.5 * (cube.vertices[topo.edges[e][0]] + cube.vertices[topo.edges[e][1]]);
    EXPECT_EQ ((mid.cwiseAbs ().array () > 1.0 - 1e-12).count (), 2);  // on two cube faces at once
  }
  EXPECT_TRUE (findSharpEdges (cube, topo, 90.5).empty ());
  const std::vector<bool> near = verticesNearSharpEdges (cube, topo, 60.0, 0);
  EXPECT_EQ (std::count (near.begin (), near.end (), true), 12 * 3 + 8);  // edge vertices and corners
  const TriangleMesh sphere = makeIcosphere (3);
  EXPECT_TRUE (findSharpEdges (sphere, buildMeshTopology (sphere), 60.0).empty ());
}
