#include <pcl_sparse/geometry/quadric_fit.h>
#include <pcl_sparse/geometry/vertex_curvature.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pcl_sparse;

TEST (QuadricFit, RecoversAnExactQuadricAtAnyScale)
{
  std::mt19937 mt (42);
  std::uniform_real_distribution<double> unit (-1.0, 1.0);
  for (double scale : {1e-3, 1.0, 1e3})
  {
    HeightQuadric truth;
    for (int i = 0; i < 6; ++i)
      truth.c[i] = unit (mt);
    // Coefficients of degree d scale like scale^(1 - d) for a shape scaled by \a scale.
    truth.c[0] *= scale;
    truth.c[3] /= scale;
    truth.c[4] /= scale;
    truth.c[5] /= scale;
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 20; ++i)
    {
      const double x = scale * unit (mt), y = scale * unit (mt);
      points.emplace_back (x, y, truth.value (x, y));
    }
    HeightQuadric fitted;
    ASSERT_TRUE (fitHeightQuadric (points, fitted));
    for (int i = 0; i < 6; ++i)
      EXPECT_NEAR (fitted.c[i], truth.c[i], 1e-9 * std::max (1.0, std::abs (truth.c[i]))) << "scale " << scale << " c" << i;
  }
}

TEST (QuadricFit, RefusesUnderdeterminedLayouts)
{
  HeightQuadric q;
  q.c[0] = 7.0;
  std::vector<Eigen::Vector3d> five = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}, {2, 1, 0}};
  EXPECT_FALSE (fitHeightQuadric (five, q));
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 10; ++i)
    line.emplace_back (i, 2.0 * i, 0.1 * i * i);
  EXPECT_FALSE (fitHeightQuadric (line, q));
  std::vector<Eigen::Vector3d> same (8, Eigen::Vector3d (0.0, 0.0, 1.0));
  EXPECT_FALSE (fitHeightQuadric (same, q));
  EXPECT_EQ (q.c[0], 7.0);  // untouched on failure
}

// The noise a patch codes down to on a scan: the spread of heights about their best quadric.
TEST (QuadricFit, NoiseLevelIsTheSpreadAboutTheQuadric)
{
  std::mt19937 rng (7);
  std::uniform_real_distribution<double> uniform (-1.0, 1.0);
  std::normal_distribution<double> noise (0.0, 0.01);
  std::vector<Eigen::Vector3d> exact, noisy, stepped;
  for (int i = 0; i < 400; ++i)
  {
    const double x = uniform (rng), y = uniform (rng), z = 0.3 * x * x + 0.1 * x * y - 0.2 * y;
    exact.emplace_back (x, y, z);
    noisy.emplace_back (x, y, z + noise (rng));
    stepped.emplace_back (x, y, 0.2 * std::round (5.0 * z));  // a depth sensor's steps of 0.2
  }
  EXPECT_LT (quadricNoiseLevel (exact), 1e-9);
  EXPECT_NEAR (quadricNoiseLevel (noisy), 0.01, 0.0015);
  // Uniform rounding error of a step q has standard deviation q / sqrt (12) = 0.058; the robust
  // median-based estimate of a uniform spread is 0.5 q / 0.6745 / 2 = 0.074 for q = 0.2.
  EXPECT_GT (quadricNoiseLevel (stepped), 0.04);
  EXPECT_LT (quadricNoiseLevel (stepped), 0.1);
  noisy.resize (11);
  EXPECT_EQ (quadricNoiseLevel (noisy), 0.0);  // fewer than 12 points: no estimate
}

TEST (MongeJet, SaddleQuadricHasUnitCurvaturesOfOppositeSign)
{
  // z = (x^2 - y^2) / 2 with the normal +z: bends toward the normal along x (k = -1), away along y (+1).
  HeightQuadric q;
  q.c[3] = 1.0;
  q.c[5] = -1.0;
  const MongeJet jet = mongeJetOfQuadric (q);
  EXPECT_NEAR (jet.k1, 1.0, 1e-12);
  EXPECT_NEAR (jet.k2, -1.0, 1e-12);
  EXPECT_NEAR (std::abs (jet.d1.y ()), 1.0, 1e-12);
  EXPECT_NEAR (std::abs (jet.d2.x ()), 1.0, 1e-12);
  EXPECT_NEAR (jet.normal.z (), 1.0, 1e-12);
  EXPECT_NEAR (jet.frame ().determinant (), 1.0, 1e-12);
}

TEST (MongeJet, TiltedQuadricUsesTheTrueNormal)
{
  // A sphere of radius 2 around (0, 0, -2) written as a height over the plane tangent at its top, seen
  // from a frame tilted by the gradient: z = h(x, y) with h_x = 0.3 at the origin. The jet must undo the
  // tilt: k1 = k2 for any umbilic point. Build it by sampling the sphere in a rotated frame.
  const double r = 2.0;
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd (0.3, Eigen::Vector3d::UnitY ()).toRotationMatrix ();
  std::vector<Eigen::Vector3d> points;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j)
    {
      const double x = 0.01 * i, y = 0.01 * j;
      const Eigen::Vector3d on_sphere (x, y, std::sqrt (r * r - x * x - y * y) - r);  // outward normal +z at 0
      points.push_back (tilt * on_sphere);
    }
  MongeJet jet;
  ASSERT_TRUE (fitMongeJet (points, Eigen::Vector3d::Zero (), Eigen::Vector3d::UnitZ (), jet));
  EXPECT_NEAR (jet.k1, 1.0 / r, 1e-4);
  EXPECT_NEAR (jet.k2, 1.0 / r, 1e-4);
  EXPECT_NEAR (jet.normal.dot (tilt * Eigen::Vector3d::UnitZ ()), 1.0, 1e-6);
}

TEST (MongeJet, GivenFrameGivesTheSameJetAsTheNormalHint)
{
  // Saddle z = (x^2 - y^2) / 2 sampled around the origin; a frame rotated about the normal, and the
  // normal-hint version, must agree on curvatures and (up to sign) directions.
  std::vector<Eigen::Vector3d> points;
  for (int i = -5; i <= 5; ++i)
    for (int j = -5; j <= 5; ++j)
    {
      const double x = 0.02 * i, y = 0.02 * j;
      points.emplace_back (x, y, 0.5 * (x * x - y * y));
    }
  const Eigen::Matrix3d frame = Eigen::AngleAxisd (0.6, Eigen::Vector3d::UnitZ ()).toRotationMatrix ();
  MongeJet in_frame, hinted;
  ASSERT_TRUE (fitMongeJetInFrame (points, Eigen::Vector3d::Zero (), frame, in_frame));
  ASSERT_TRUE (fitMongeJet (points, Eigen::Vector3d::Zero (), Eigen::Vector3d::UnitZ (), hinted));
  EXPECT_NEAR (in_frame.k1, 1.0, 1e-9);
  EXPECT_NEAR (in_frame.k2, -1.0, 1e-9);
  EXPECT_NEAR (std::abs (in_frame.d1.dot (hinted.d1)), 1.0, 1e-9);
  EXPECT_NEAR (std::abs (in_frame.d1.y ()), 1.0, 1e-9);
  EXPECT_NEAR (in_frame.normal.z (), 1.0, 1e-12);
  // Flipping the frame's normal flips the jet's normal and the curvature signs.
  Eigen::Matrix3d flipped = frame;
  flipped.col (1) *= -1.0;
  flipped.col (2) *= -1.0;
  MongeJet down;
  ASSERT_TRUE (fitMongeJetInFrame (points, Eigen::Vector3d::Zero (), flipped, down));
  EXPECT_NEAR (down.k1, 1.0, 1e-9);
  EXPECT_NEAR (down.k2, -1.0, 1e-9);
  EXPECT_NEAR (down.normal.z (), -1.0, 1e-12);
  EXPECT_NEAR (std::abs (down.d1.x ()), 1.0, 1e-9);  // k = +1 is now along x
}

TEST (VertexCurvature, SphereHasUmbilicCurvatureOneOverR)
{
  const double r = 2.0;
  const TriangleMesh mesh = makeIcosphere (5, r);
  const MeshTopology topo = buildMeshTopology (mesh);
  const auto normals = computeVertexNormals (mesh, topo);
  const auto jets = computeVertexMongeJets (mesh, topo, normals, 2);
  double worst = 0.0;
  for (std::size_t v = 0; v < jets.size (); ++v)
  {
    ASSERT_TRUE (std::isfinite (jets[v].k1) && std::isfinite (jets[v].k2)) << "vertex " << v;  // max () skips NaN
    worst = std::max ({worst, std::abs (jets[v].k1 * r - 1.0), std::abs (jets[v].k2 * r - 1.0)});
    EXPECT_GT (jets[v].normal.dot (mesh.vertices[v] / r), 0.9999);
  }
  EXPECT_LT (worst, 0.02) << "largest relative curvature error";
  std::cout << "sphere: largest relative curvature error " << worst << "\n";
}

TEST (VertexCurvature, CylinderHasCurvaturesOneOverRAndZero)
{
  const double r = 0.5;
  const TriangleMesh mesh = makeCylinder (128, 64, r, 1.0);
  const MeshTopology topo = buildMeshTopology (mesh);
  const auto normals = computeVertexNormals (mesh, topo);
  const auto jets = computeVertexMongeJets (mesh, topo, normals, 2);
  double worst_k1 = 0.0, worst_k2 = 0.0, worst_dir = 0.0;
  int checked = 0;
  for (std::size_t v = 0; v < jets.size (); ++v)
  {
    if (std::abs (mesh.vertices[v].z ()) > 0.8)
      continue;  // away from the open rims
    ++checked;
    worst_k1 = std::max (worst_k1, std::abs (jets[v].k1 * r - 1.0));
    worst_k2 = std::max (worst_k2, std::abs (jets[v].k2 * r));
    worst_dir = std::max ({worst_dir, std::abs (jets[v].d1.z ()), 1.0 - std::abs (jets[v].d2.z ())});
  }
  EXPECT_GT (checked, 5000);
  EXPECT_LT (worst_k1, 0.02);
  EXPECT_LT (worst_k2, 0.02) << "k2 relative to 1 / r";
  EXPECT_LT (worst_dir, 0.01) << "d1 around, d2 along the axis";
  std::cout << "cylinder: k1 " << worst_k1 << ", k2 " << worst_k2 << ", directions " << worst_dir << "\n";
}

TEST (VertexCurvature, SaddleHeightFieldAtTheOrigin)
{
  const int n = 200;
  const TriangleMesh mesh = makeHeightFieldGrid (n, n, 1.0, 1.0, [] (double x, double y) { return 0.5 * (x * x - y * y); });
  const MeshTopology topo = buildMeshTopology (mesh);
  const auto normals = computeVertexNormals (mesh, topo);
  const auto jets = computeVertexMongeJets (mesh, topo, normals, 2);
  const int origin = (n / 2) * (n + 1) + n / 2;
  ASSERT_NEAR (mesh.vertices[origin].norm (), 0.0, 1e-12);
  const MongeJet& jet = jets[origin];
  EXPECT_NEAR (jet.k1, 1.0, 0.02);
  EXPECT_NEAR (jet.k2, -1.0, 0.02);
  EXPECT_GT (std::abs (jet.d1.y ()), 0.999);
  EXPECT_GT (std::abs (jet.d2.x ()), 0.999);
  EXPECT_GT (jet.normal.z (), 0.999);
  // Elsewhere on the saddle: Gaussian curvature K = -1 / (1 + x^2 + y^2)^2 and mean curvature
  // H = (x^2 - y^2) / (2 (1 + x^2 + y^2)^(3/2)) in the MongeJet sign convention (upward normal).
  for (int i : {60, 100, 150})
    for (int j : {40, 100, 170})
    {
      const int v = j * (n + 1) + i;
      const double x = mesh.vertices[v].x (), y = mesh.vertices[v].y ();
      const double w = 1.0 + x * x + y * y;
      EXPECT_NEAR (jets[v].k1 * jets[v].k2, -1.0 / (w * w), 0.02 / (w * w)) << x << ", " << y;
      EXPECT_NEAR (0.5 * (jets[v].k1 + jets[v].k2), (x * x - y * y) / (2.0 * std::pow (w, 1.5)), 0.01) << x << ", " << y;
    }
}

TEST (VertexCurvature, BadVerticesGetNaN)
{
  TriangleMesh mesh = makeTetrahedron ();  // 3 neighbours: too few for a quadric
  const MeshTopology topo = buildMeshTopology (mesh);
  const auto normals = computeVertexNormals (mesh, topo);
  const auto jets = computeVertexMongeJets (mesh, topo, normals, 2);
  ASSERT_EQ (jets.size (), mesh.numVertices ());  // one jet per vertex: an empty result would pass the loop
  for (const auto& jet : jets)
    EXPECT_TRUE (std::isnan (jet.k1) && std::isnan (jet.k2));
}
