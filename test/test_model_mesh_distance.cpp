// The Chamfer distance between a model and the mesh it codes (resampling/model_mesh_distance.h), which
// bench/bench_format and the default file's choice measure with.
#include "model_helpers.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/model_mesh_distance.h>

#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

using namespace pcl_sparse;
using namespace pcl_sparse_test;

TEST (ModelMeshDistance, KnownDistancesToAPlaneAndASphere)
{
  // A unit square at z = 0: points above it are their height away, points beside it their distance to the edge.
  const TriangleMesh square = makePlaneGrid (4, 0.5);
  const MeshSurfaceDistance to_square (square);
  EXPECT_NEAR (to_square (Eigen::Vector3d (0.1, -0.2, 0.3)), 0.3, 1e-12);
  EXPECT_NEAR (to_square (Eigen::Vector3d (0.1, -0.2, -0.05)), 0.05, 1e-12);
  EXPECT_NEAR (to_square (Eigen::Vector3d (0.9, 0.0, 0.0)), 0.4, 1e-12);
  std::vector<Eigen::Vector3d> samples;
  std::vector<int> triangles;
  sampleMeshSurface (square, 1000, 3, samples, &triangles);
  ASSERT_EQ (samples.size (), 1000u);
  ASSERT_EQ (triangles.size (), 1000u);
  for (const Eigen::Vector3d& p : samples)
  {
    EXPECT_LE (p.cwiseAbs ().maxCoeff (), 0.5 + 1e-12);
    EXPECT_EQ (p.z (), 0.0);
  }

  // A sphere of radius 1 coded by the encoder: a point at radius 1.2 is 0.2 from the model, to the model's error.
  const auto sphere = std::make_shared<const TriangleMesh> (makeIcosphere (3));
  const SparseSurfaceModel::ConstPtr model = encodeMesh (sphere);
  std::vector<Eigen::Vector3d> resampled;
  for (const pcl::PointNormal& p : resampleModel (model, 20000))
    resampled.emplace_back (p.x, p.y, p.z);
  const ModelSurfaceDistance to_model (*model, resampled);
  for (const Eigen::Vector3d& direction : {Eigen::Vector3d (1, 0, 0), Eigen::Vector3d (0.3, -0.5, 0.8).normalized ()})
  {
    EXPECT_NEAR (to_model (1.2 * direction), 0.2, 0.01);
    EXPECT_NEAR (to_model (0.9 * direction), 0.1, 0.01);
  }
  // The model's Chamfer distance to its own mesh is its coding error: far below a sphere's size, far above 0
  // (the icosphere's flat faces against the codes' curved patches).
  const double chamfer = chamferOf (model, *sphere, 20000);
  EXPECT_GT (chamfer, 1e-5);
  EXPECT_LT (chamfer, 5e-3);
  // Against a sphere 1 % larger, the distance grows by about 0.01.
  TriangleMesh larger = *sphere;
  for (Eigen::Vector3d& v : larger.vertices)
    v *= 1.01;
  EXPECT_NEAR (chamferOf (model, larger, 20000), 0.01, 0.003);
}

TEST (ModelMeshDistance, MeshDistanceIsTheNearestFace)
{
  // Against every face, exactly: points off a curved surface, measured exactly and among the triangles of the
  // nearest samples of a sampling (where the k nearest samples hold a face several times, a face measured once
  // is the same minimum).
  const TriangleMesh sphere = makeIcosphere (2);
  const MeshSurfaceDistance to_sphere (sphere);
  const MeshSurfaceDistance sampled (sphere, MeshSurfaceDistance::Sampling {2 * sphere.triangles.size () + 5000});
  std::vector<Eigen::Vector3d> probes;
  sampleMeshSurface (sphere, 200, 5, probes);
  for (std::size_t i = 0; i < probes.size (); ++i)
  {
    const Eigen::Vector3d p = probes[i] * (i % 2 ? 1.05 : 0.97);
    double exact = std::numeric_limits<double>::infinity ();
    for (const Eigen::Vector3i& f : sphere.triangles)
      exact = std::min (exact, pointTriangleDistance (p, sphere.vertices[f[0]], sphere.vertices[f[1]], sphere.vertices[f[2]]));
    EXPECT_EQ (to_sphere (p), exact) << i;
    EXPECT_EQ (sampled (p), exact) << i;
  }
}

TEST (ModelMeshDistance, EmptyInputsAreRefused)
{
  EXPECT_THROW (MeshSurfaceDistance {TriangleMesh ()}, Error);
  // A face with a non-finite corner (a mesh given through the API; the loaders refuse it) has no distance.
  TriangleMesh broken = makePlaneGrid (2, 0.5);
  broken.vertices[0].x () = std::nan ("");
  EXPECT_THROW (MeshSurfaceDistance {broken}, Error);
  EXPECT_THROW (MeshSurfaceDistance (TriangleMesh (), MeshSurfaceDistance::Sampling {100}), Error);
  EXPECT_THROW (MeshSurfaceDistance (broken, MeshSurfaceDistance::Sampling {100}), Error);
  // An infinite corner makes the total area not finite and the draws land on sound faces: refused all the same.
  TriangleMesh infinite = makeIcosphere (2);
  infinite.vertices[3].y () = std::numeric_limits<double>::infinity ();
  EXPECT_THROW (MeshSurfaceDistance (infinite, MeshSurfaceDistance::Sampling {2 * infinite.triangles.size () + 50000}), Error);  // the write's count
  TriangleMesh out_of_range = makePlaneGrid (2, 0.5);
  out_of_range.triangles[0][1] = static_cast<int> (out_of_range.vertices.size ());
  EXPECT_THROW (MeshSurfaceDistance (out_of_range, MeshSurfaceDistance::Sampling {100}), Error);
  SparseSurfaceModel empty;
  EXPECT_THROW (ModelSurfaceDistance (empty, {Eigen::Vector3d::Zero ()}), Error);
}

// The distances run on the threads asked for: 1 means one (the encoder's -threads 1 ran them on every core),
// and the mean and largest do not depend on the count.
TEST (ModelMeshDistance, DistancesRunOnTheThreadsAskedFor)
{
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 20000; ++i)
    points.emplace_back (0.001 * i, 0.0, 0.0);
  for (const int threads : {1, 2})
  {
    int widest = 0;
    auto distance = [&] (const Eigen::Vector3d& p) {
#pragma omp critical
      widest = std::max (widest, omp_get_num_threads ());
      return p.x ();
    };
    double mean = 0.0, largest = 0.0;
    meanAndLargestDistance (points, distance, mean, largest, threads);
    EXPECT_EQ (widest, threads);
    EXPECT_NEAR (mean, 0.001 * 19999 / 2.0, 1e-9);
    EXPECT_DOUBLE_EQ (largest, 19.999);
  }
}

// The Chamfer distance builds the model half's k-d tree on one thread while the others measure the model half
// (model_mesh_distance.cpp): the same numbers as the two halves measured one after the other, on any count.
TEST (ModelMeshDistance, ChamferIsItsHalvesMeasuredInTurnOnAnyThreadCount)
{
  const auto sphere = std::make_shared<const TriangleMesh> (makeIcosphere (3));
  const SparseSurfaceModel::ConstPtr model = encodeMesh (sphere);
  const MeshSurfaceDistance to_mesh (*sphere);
  std::vector<Eigen::Vector3d> on_mesh;
  sampleMeshSurface (*sphere, 5000, 7, on_mesh);
  const std::size_t points = 20000;

  std::vector<Eigen::Vector3d> on_model;
  for (const pcl::PointNormal& p : resampleModel (model, points))
    on_model.emplace_back (p.x, p.y, p.z);
  const ModelSurfaceDistance to_model (*model, on_model);
  double model_to_mesh = 0.0, mesh_to_model = 0.0, largest_a = 0.0, largest_b = 0.0;
  meanAndLargestDistance (on_model, to_mesh, model_to_mesh, largest_a, 1);
  meanAndLargestDistance (on_mesh, to_model, mesh_to_model, largest_b, 1);
  ASSERT_GT (model_to_mesh, 0.0);
  ASSERT_GT (mesh_to_model, 0.0);

  for (const int threads : {1, 2, 3})
  {
    const ChamferDistance chamfer =
      modelChamferDistance (model, to_mesh, on_mesh, points, SparseSurfaceResamplingOptions (), threads);
    EXPECT_EQ (chamfer.model_points, on_model.size ()) << threads;
    EXPECT_EQ (chamfer.model_to_mesh, model_to_mesh) << threads;
    EXPECT_EQ (chamfer.mesh_to_model, mesh_to_model) << threads;
    EXPECT_EQ (chamfer.largest, std::max (largest_a, largest_b)) << threads;
  }
}

// Every patch is measured within its own reach, however its reach compares with the others' (patches found
// by a grid of the reach balls): the same distances as measuring every patch, on a model whose reaches spread
// over 5x (a tenth of the patches with footprints 5 times as wide).
TEST (ModelMeshDistance, ModelDistanceMeasuresEveryPatchWithinItsReach)
{
  const auto sphere = std::make_shared<const TriangleMesh> (makeIcosphere (3));
  auto model = std::make_shared<SparseSurfaceModel> (*encodeMesh (sphere));
  for (std::size_t p = 0; p < model->patches.size (); p += 10)
    for (float& e : model->patches[p].footprint.extent)
      e *= 5.0f;
  std::vector<Eigen::Vector3d> resampled;
  for (const pcl::PointNormal& p : resampleModel (model, 5000))
    resampled.emplace_back (p.x, p.y, p.z);
  const ModelSurfaceDistance to_model (*model, resampled);
  // Every patch, as the class documents it: within 1.5 r max (1, largest extent) of its seed, the projection in
  // its footprint, the first-order height difference; capped by the nearest resampled point.
  auto everyPatch = [&] (const Eigen::Vector3d& q) {
    double best = std::numeric_limits<double>::infinity ();
    for (std::size_t i = 0; i < model->patches.size (); ++i)
    {
      const PatchCode& patch = model->patches[i];
      double e = 1.0;
      for (float x : patch.footprint.extent)
        e = std::max (e, static_cast<double> (x));
      if ((q - patch.origin).norm () > 1.5 * patch.radius * e)
        continue;
      const Eigen::Vector3d local = patch.toLocal (q);
      if (!patch.footprint.contains (local.x (), local.y ()))
        continue;
      const HeightSample h = model->evaluate (i, local.x (), local.y ());
      best = std::min (best, std::abs (local.z () - h.value) * patch.radius / std::sqrt (1.0 + h.gradient.squaredNorm ()));
    }
    for (const Eigen::Vector3d& r : resampled)
      best = std::min (best, (q - r).norm ());
    return best;
  };
  std::mt19937 random (11);
  std::uniform_real_distribution<double> unit (-1.0, 1.0), radius (0.7, 1.4);
  for (int k = 0; k < 400; ++k)
  {
    const Eigen::Vector3d q = radius (random) * Eigen::Vector3d (unit (random), unit (random), unit (random)).normalized ();
    const double expected = everyPatch (q);
    EXPECT_NEAR (to_model (q), expected, 1e-9 + 1e-6 * expected);
  }
}
