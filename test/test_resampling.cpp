// Tests of SparseSurfaceResampling<pcl::PointNormal> on hand-made models with known surfaces: a flat sheet of disk
// patches and a sphere covered by overlapping caps, both coded over the CosineDictionary by least squares.
#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/memory_limit.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/patch_geometry.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/kdtree/kdtree_flann.h>

#include <gtest/gtest.h>

#include "error_message.h"

#include <Eigen/Dense>

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// A frame (T1, T2, N) with the given normal.
  Eigen::Matrix3d
  frameFromNormal (const Eigen::Vector3d& normal)
  {
    const Eigen::Vector3d n = normal.normalized ();
    const Eigen::Vector3d helper = std::abs (n.x ()) < 0.9 ? Eigen::Vector3d::UnitX () : Eigen::Vector3d::UnitY ();
    const Eigen::Vector3d t1 = (helper - helper.dot (n) * n).normalized ();
    Eigen::Matrix3d frame;
    frame << t1, n.cross (t1), n;
    return frame;
  }

  /// Codes height(x, y) over the unit disk with the cosine atoms of frequency < 8 (and a quadric basis's
  /// monomials), least squares.
  void
  codeHeight (const CosineAtoms& basis, const std::function<double (double, double)>& height, PatchCode& code)
  {
    std::vector<Eigen::Vector2d> points;
    std::vector<double> values;
    for (int a = -24; a <= 24; ++a)
      for (int b = -24; b <= 24; ++b)
      {
        const double x = a / 22.0, y = b / 22.0;
        if (x * x + y * y <= 1.0)
        {
          points.emplace_back (x, y);
          values.push_back (height (x, y));
        }
      }
    Eigen::MatrixXd all;
    basis.evaluate (points, all);
    std::vector<int> atoms;
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j)
        atoms.push_back (basis.atomIndex (i, j));
    for (int m = 0; m < basis.monomials (); ++m)
      atoms.push_back (basis.frequencies () * basis.frequencies () + m);
    Eigen::MatrixXd design (points.size (), atoms.size ());
    for (std::size_t k = 0; k < atoms.size (); ++k)
      design.col (k) = all.col (atoms[k]);
    const Eigen::VectorXd rhs = Eigen::Map<const Eigen::VectorXd> (values.data (), values.size ());
    const Eigen::VectorXd solution = design.colPivHouseholderQr ().solve (rhs);
    code.atoms = atoms;
    code.coefficients.assign (solution.data (), solution.data () + solution.size ());
  }

  PatchFootprint
  diskFootprint (double radius)
  {
    PatchFootprint footprint;
    footprint.extent.assign (32, static_cast<float> (radius));
    return footprint;
  }

  /// Flat square sheet z = 0: a 5 x 5 grid of disk patches of radius 0.4, seeds 0.5 apart.
  SparseSurfaceModel::Ptr
  makePlaneModel ()
  {
    auto model = std::make_shared<SparseSurfaceModel> ();
    model->basis = std::make_shared<CosineDictionary> (12);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j)
      {
        PatchCode code;
        code.origin = Eigen::Vector3d (-1.0 + 0.5 * i, -1.0 + 0.5 * j, 0.0);
        // Rotate each frame differently about z so the patch grids do not line up.
        const double angle = 0.37 * (5 * i + j);
        code.frame = Eigen::AngleAxisd (angle, Eigen::Vector3d::UnitZ ()).toRotationMatrix ();
        code.radius = 0.4;
        code.footprint = diskFootprint (1.0);
        model->patches.push_back (code);
      }
    model->bbox_diagonal = std::sqrt (2.0) * 2.8;
    return model;
  }

  /// Unit sphere covered by caps around the icosphere(1) vertices (42 seeds), cap radius 0.5: r_P = 0.625
  /// and footprint extent 0.8, so the footprint stays away from the square's edges, where every cosine
  /// atom has zero slope.
  SparseSurfaceModel::Ptr
  makeSphereModel (CosineBasisKind kind = CosineBasisKind::Paper)
  {
    auto model = std::make_shared<SparseSurfaceModel> ();
    const CosineAtoms::ConstPtr basis = makeCosineBasis (kind, 12);
    model->basis = basis;
    const TriangleMesh seeds = makeIcosphere (1);
    const double r = 0.625;
    for (const Eigen::Vector3d& s : seeds.vertices)
    {
      PatchCode code;
      code.origin = s;
      code.frame = frameFromNormal (s);
      code.radius = r;
      // The sphere seen from its tangent plane at s, in local units: z' = (sqrt(1 - r^2 |x|^2) - 1) / r.
      codeHeight (*basis, [r] (double x, double y) { return (std::sqrt (std::max (0.0, 1.0 - r * r * (x * x + y * y))) - 1.0) / r; },
                  code);
      code.footprint = diskFootprint (0.8);
      model->patches.push_back (code);
    }
    model->bbox_diagonal = 2.0 * std::sqrt (3.0);
    return model;
  }

  /// |(x, y)| / extent, from PatchFootprint's own interpolation (the unit disk when empty).
  double
  footprintCentralityReference (const PatchFootprint& footprint, double x, double y)
  {
    const double r = std::hypot (x, y);
    return footprint.extent.empty () ? r : r / footprint.extentAt (std::atan2 (y, x));
  }

  /// Nearest-neighbour distances of every point.
  std::vector<double>
  nearestDistances (const pcl::PointCloud<pcl::PointNormal>::ConstPtr& cloud)
  {
    pcl::KdTreeFLANN<pcl::PointNormal> tree;
    tree.setInputCloud (cloud);
    std::vector<int> index (2);
    std::vector<float> d2 (2);
    std::vector<double> distances;
    for (const auto& p : *cloud)
    {
      tree.nearestKSearch (p, 2, index, d2);
      distances.push_back (std::sqrt (d2[1]));
    }
    return distances;
  }

  double
  coefficientOfVariation (const std::vector<double>& values)
  {
    double mean = 0.0, square = 0.0;
    for (double v : values)
      mean += v;
    mean /= values.size ();
    for (double v : values)
      square += (v - mean) * (v - mean);
    return std::sqrt (square / values.size ()) / mean;
  }

  pcl::PointCloud<pcl::PointNormal>::Ptr
  resample (const SparseSurfaceModel::Ptr& model, std::size_t count, int threads = 0, std::uint64_t seed = 42)
  {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (count);
    SparseSurfaceResamplingOptions options;
    options.seed = seed;
    resampling.setOptions (options);
    resampling.setNumberOfThreads (threads);
    pcl::PointCloud<pcl::PointNormal>::Ptr cloud (new pcl::PointCloud<pcl::PointNormal>);
    resampling.compute (*cloud);
    return cloud;
  }
} // namespace

TEST (PatchGeometry, MeanCurvatureOfSphereCap)
{
  // z = r h(x / r, y / r) with h(x, y) = (sqrt(1 - r^2 |x|^2) - 1) / r: sphere of radius 1 below its
  // tangent plane, normal outward: H = +1 at the seed.
  PatchCode code;
  code.radius = 0.5;
  HeightSample h;
  h.hessian << -0.5, 0.0, 0.0, -0.5;  // h_xx = -r at the centre
  EXPECT_NEAR (patchMeanCurvature (code, h), 1.0, 1e-12);
  EXPECT_NEAR (patchAreaElement (code, h), 0.25, 1e-12);
}

TEST (PatchEvaluator, MatchesTheBasis)
{
  // Every cosine basis has the fast tables: the paper's, the half-period one, and with the quadric.
  for (const CosineBasisKind kind : {CosineBasisKind::Paper, CosineBasisKind::Dct, CosineBasisKind::DctQuadric})
  {
    SCOPED_TRACE (cosineBasisKindName (kind));
    const auto model = makeSphereModel (kind);
    // Some extents, so the footprint path is exercised too.
    model->patches[0].footprint.extent = {0.5f, 1.0f, 0.25f, 0.75f};
    const PatchEvaluator evaluator (*model);
    std::mt19937 random (42);
    std::uniform_real_distribution<double> uniform (-1.6, 1.6);
    for (int k = 0; k < 2000; ++k)
    {
      const std::size_t p = k % model->numPatches ();
      const double x = uniform (random), y = uniform (random);
      const HeightSample expected = model->evaluate (p, x, y);
      const HeightSample fast = evaluator.sample (p, x, y);
      ASSERT_NEAR (fast.value, expected.value, 1e-12);
      ASSERT_NEAR (evaluator.height (p, x, y), expected.value, 1e-12);
      ASSERT_NEAR ((fast.gradient - expected.gradient).norm (), 0.0, 1e-10);
      ASSERT_NEAR ((fast.hessian - expected.hessian).norm (), 0.0, 1e-9);
      ASSERT_NEAR (PatchEvaluator::fastAtan2 (y, x), std::atan2 (y, x), 1e-9);
      ASSERT_NEAR (evaluator.centrality (p, x, y), footprintCentralityReference (model->patches[p].footprint, x, y), 1e-8);
    }
  }
}

TEST (PatchEvaluator, BlockEqualsPointByPointBitForBit)
{
  // The block evaluation (vectorised, maybe AVX2) must give the same bits as sample, so that the resampled
  // cloud does not depend on which path made a point: the sphere's codes, and random codes on all atoms,
  // for every cosine basis.
  for (const CosineBasisKind kind : {CosineBasisKind::Paper, CosineBasisKind::Dct, CosineBasisKind::DctQuadric})
  {
    SCOPED_TRACE (cosineBasisKindName (kind));
    const auto model = makeSphereModel (kind);
    std::mt19937 random (7);
    std::uniform_real_distribution<double> coefficient (-0.3, 0.3);
    for (int k = 0; k < 3; ++k)
    {
      PatchCode code = model->patches[k];
      code.atoms.clear ();
      code.coefficients.clear ();
      for (int atom = 0; atom < model->basis->size (); atom += 1 + k)
      {
        code.atoms.push_back (atom);
        code.coefficients.push_back (coefficient (random));
      }
      model->patches.push_back (code);
    }
    const PatchEvaluator evaluator (*model);
    std::uniform_real_distribution<double> uniform (-1.6, 1.6);
    PatchEvaluator::Block block;
    for (std::size_t p = 0; p < model->numPatches (); ++p)
      for (int round = 0; round < 4; ++round)
      {
        for (int b = 0; b < PatchEvaluator::Block::size; ++b)
        {
          block.x[b] = uniform (random);
          block.y[b] = round == 3 ? 0.25 * b : uniform (random);  // quarter turns: every quadrant of sinCosPi
        }
        evaluator.sampleBlock (p, block);
        for (int b = 0; b < PatchEvaluator::Block::size; ++b)
        {
          const HeightSample expected = evaluator.sample (p, block.x[b], block.y[b]);
          const HeightSample got = block.sample (b);
          ASSERT_EQ (std::memcmp (&got.value, &expected.value, sizeof (double)), 0) << p << " " << b;
          ASSERT_EQ (std::memcmp (got.gradient.data (), expected.gradient.data (), 2 * sizeof (double)), 0);
          ASSERT_EQ (std::memcmp (got.hessian.data (), expected.hessian.data (), 4 * sizeof (double)), 0);
        }
      }
  }
}

TEST (Resampling, ReusedOutputCloudGivesTheSameBytes)
{
  // With a count, the output is constructed while the candidate pass runs (one thread) and every point is
  // then overwritten: a cloud holding other points of the same size, or of another size, must end up with
  // the bytes of a fresh compute, for 1 and 2 threads.
  const auto model = makeSphereModel ();
  auto run = [&] (int threads, pcl::PointCloud<pcl::PointNormal>& cloud) {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (30000);
    resampling.setNumberOfThreads (threads);
    resampling.compute (cloud);
  };
  pcl::PointCloud<pcl::PointNormal> fresh;
  run (1, fresh);
  ASSERT_EQ (fresh.size (), 30000u);
  for (int threads : {1, 2})
    for (std::size_t size : {std::size_t (30000), std::size_t (12345)})
    {
      pcl::PointCloud<pcl::PointNormal> reused;
      reused.resize (size);
      for (auto& p : reused)
        p.x = p.y = p.z = p.normal_x = p.normal_y = p.normal_z = p.curvature = 7.0f;
      run (threads, reused);
      ASSERT_EQ (reused.size (), fresh.size ());
      EXPECT_EQ (reused.width, fresh.width);
      EXPECT_EQ (std::memcmp (reused.data (), fresh.data (), fresh.size () * sizeof (pcl::PointNormal)), 0)
        << threads << " threads, reused size " << size;
    }
}

TEST (Resampling, PlaneExactCountOnSurfaceUniform)
{
  const auto model = makePlaneModel ();
  const auto cloud = resample (model, 20000);
  ASSERT_EQ (cloud->size (), 20000u);
  for (const auto& p : *cloud)
  {
    ASSERT_NEAR (p.z, 0.0, 1e-6);
    ASSERT_NEAR (p.normal_z, 1.0, 1e-6);
    ASSERT_NEAR (p.curvature, 0.0, 1e-6);
  }
  // Area of the union of the disks by a fine grid; the density must match it (no double counting).
  double inside = 0.0;
  const int n = 1000;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
    {
      const double x = -1.5 + 3.0 * (a + 0.5) / n, y = -1.5 + 3.0 * (b + 0.5) / n;
      bool covered = false;
      for (const auto& code : model->patches)
        covered = covered || (Eigen::Vector2d (x, y) - code.origin.head<2> ()).norm () <= code.radius;
      inside += covered ? 1.0 : 0.0;
    }
  const double area = inside * 9.0 / (n * n);
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setDensity (10000.0);
  pcl::PointCloud<pcl::PointNormal> by_density;
  resampling.compute (by_density);
  EXPECT_NEAR (resampling.getEstimatedArea (), area, 0.01 * area);
  EXPECT_NEAR (static_cast<double> (by_density.size ()), 10000.0 * area, 0.01 * 10000.0 * area);
  // The inner square [-0.75, 0.75]^2 (covered by several patches everywhere) holds its share of points.
  std::size_t in_square = 0;
  for (const auto& p : by_density)
    in_square += (std::abs (p.x) < 0.75 && std::abs (p.y) < 0.75) ? 1 : 0;
  EXPECT_NEAR (static_cast<double> (in_square), 10000.0 * 2.25, 0.01 * 10000.0 * 2.25);
  const double cv = coefficientOfVariation (nearestDistances (cloud));
  std::cout << "plane nearest-neighbour CV " << cv << std::endl;
  EXPECT_LT (cv, 0.25);
}

TEST (Resampling, SphereOnSurfaceNormalsCompleteUniform)
{
  const auto model = makeSphereModel ();
  const std::size_t n = 30000;
  const auto cloud = resample (model, n);
  ASSERT_EQ (cloud->size (), n);
  double square = 0.0, curvature = 0.0, worst_normal = 1.0;
  std::array<std::size_t, 8> octants {};
  for (const auto& p : *cloud)
  {
    const Eigen::Vector3d q (p.x, p.y, p.z);
    square += (q.norm () - 1.0) * (q.norm () - 1.0);
    const double cosine = Eigen::Vector3d (p.normal_x, p.normal_y, p.normal_z).dot (q.normalized ());
    ASSERT_TRUE (std::isfinite (cosine)) << "a NaN normal or position";  // std::min would keep the old value
    worst_normal = std::min (worst_normal, cosine);
    curvature += p.curvature;
    ++octants[(q.x () > 0) + 2 * (q.y () > 0) + 4 * (q.z () > 0)];
  }
  // Bounds of the test model's own least-squares code (its error is about 5e-4 near the footprint edge).
  EXPECT_LT (std::sqrt (square / n), 1e-3);
  EXPECT_GT (worst_normal, std::cos (3.0 * M_PI / 180.0));
  EXPECT_NEAR (curvature / n, 1.0, 0.05);
  for (std::size_t count : octants)  // equal areas, equal counts: overlaps are not double counted
    EXPECT_NEAR (static_cast<double> (count), n / 8.0, 0.03 * n / 8.0);

  const std::vector<double> distances = nearestDistances (cloud);
  const double cv = coefficientOfVariation (distances);
  std::cout << "sphere nearest-neighbour CV " << cv << std::endl;
  EXPECT_LT (cv, 0.25);

  // No holes: every point of a dense Fibonacci sampling of the sphere has a point within 3 spacings.
  const double spacing = std::sqrt (4.0 * M_PI / n);
  pcl::KdTreeFLANN<pcl::PointNormal> tree;
  tree.setInputCloud (cloud);
  std::vector<int> index (1);
  std::vector<float> d2 (1);
  double worst = 0.0;
  const int probes = 100000;
  for (int k = 0; k < probes; ++k)
  {
    const double z = 1.0 - 2.0 * (k + 0.5) / probes, rho = std::sqrt (1.0 - z * z), phi = k * M_PI * (3.0 - std::sqrt (5.0));
    pcl::PointNormal probe;
    probe.x = static_cast<float> (rho * std::cos (phi));
    probe.y = static_cast<float> (rho * std::sin (phi));
    probe.z = static_cast<float> (z);
    tree.nearestKSearch (probe, 1, index, d2);
    worst = std::max (worst, std::sqrt (static_cast<double> (d2[0])));
  }
  EXPECT_LT (worst, 3.0 * spacing);
}

TEST (Resampling, PointsLieOnTheirPatchCode)
{
  const auto model = makeSphereModel ();
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (3000);
  pcl::PointCloud<pcl::PointNormal> cloud;
  resampling.compute (cloud);
  ASSERT_EQ (cloud.size (), 3000u);  // an empty cloud would pass the loop below
  ASSERT_EQ (resampling.getPointPatches ().size (), cloud.size ());
  for (std::size_t i = 0; i < cloud.size (); ++i)
  {
    const PatchCode& code = model->patches[resampling.getPointPatches ()[i]];
    const Eigen::Vector3d q (cloud[i].x, cloud[i].y, cloud[i].z);
    const Eigen::Vector3d local = code.frame.transpose () * (q - code.origin) / code.radius;
    ASSERT_LE (local.head<2> ().norm (), 0.8 + 1e-5);  // inside its own footprint
    const HeightSample h = model->evaluate (resampling.getPointPatches ()[i], local.x (), local.y ());
    ASSERT_NEAR (local.z (), h.value, 1e-5);
    const Eigen::Vector3d normal = patchNormal (code, h);
    ASSERT_GT (normal.dot (Eigen::Vector3d (cloud[i].normal_x, cloud[i].normal_y, cloud[i].normal_z)), 1.0 - 1e-5);
  }
}

TEST (Resampling, DeterministicForAnyThreadCount)
{
  const auto model = makeSphereModel ();
  const auto one = resample (model, 5000, 1);
  const auto two = resample (model, 5000, 2);
  const auto again = resample (model, 5000, 2);
  const auto other_seed = resample (model, 5000, 2, 7);
  ASSERT_EQ (one->size (), 5000u);
  ASSERT_EQ (two->size (), one->size ());
  ASSERT_EQ (again->size (), one->size ());
  ASSERT_EQ (other_seed->size (), one->size ());
  bool differs = false;
  for (std::size_t i = 0; i < one->size (); ++i)
  {
    ASSERT_EQ (0, std::memcmp (&(*one)[i], &(*two)[i], sizeof (pcl::PointNormal)));
    ASSERT_EQ (0, std::memcmp (&(*two)[i], &(*again)[i], sizeof (pcl::PointNormal)));
    differs = differs || (*one)[i].x != (*other_seed)[i].x;
  }
  EXPECT_TRUE (differs);
}

TEST (Resampling, HighDensityBlocksDeterministicUniform)
{
  // About 4800 points per patch: cells are classified by blocks (quadtree), the fast path.
  const auto model = makeSphereModel ();
  const std::size_t n = 200000;
  const auto one = resample (model, n, 1);
  const auto two = resample (model, n, 2);
  ASSERT_EQ (one->size (), n);
  ASSERT_EQ (two->size (), n);
  ASSERT_EQ (0, std::memcmp (one->data (), two->data (), n * sizeof (pcl::PointNormal)));
  std::array<std::size_t, 8> octants {};
  double square = 0.0;
  for (const auto& p : *one)
  {
    const Eigen::Vector3d q (p.x, p.y, p.z);
    square += (q.norm () - 1.0) * (q.norm () - 1.0);
    ++octants[(q.x () > 0) + 2 * (q.y () > 0) + 4 * (q.z () > 0)];
  }
  EXPECT_LT (std::sqrt (square / n), 1e-3);
  for (std::size_t count : octants)
    EXPECT_NEAR (static_cast<double> (count), n / 8.0, 0.01 * n / 8.0);
  const double cv = coefficientOfVariation (nearestDistances (one));
  std::cout << "sphere at 200k points: nearest-neighbour CV " << cv << std::endl;
  EXPECT_LT (cv, 0.25);
}

// A progress callback may throw to cancel: the exception reaches the caller from inside the parallel loops
// (it ended the program in std::terminate before), for a count, a density and a stream.
TEST (Resampling, ProgressCallbackMayThrowToCancel)
{
  const auto model = makeSphereModel ();
  for (int mode = 0; mode < 3; ++mode)
    for (int threads : {1, 2})
    {
      SCOPED_TRACE ("mode " + std::to_string (mode) + ", threads " + std::to_string (threads));
      SparseSurfaceResampling<pcl::PointNormal> resampling;
      resampling.setInputModel (model);
      resampling.setNumberOfThreads (threads);
      if (mode == 1)
        resampling.setDensity (20000.0 / (4.0 * M_PI));
      else
        resampling.setPointCount (20000);
      int calls = 0;
      resampling.setProgressCallback ([&] (const std::string&, double fraction) {
        ++calls;
        if (fraction > 0.0 && fraction < 1.0)
          throw std::runtime_error ("cancelled");
      });
      pcl::PointCloud<pcl::PointNormal> cloud;
      if (mode == 2)
        EXPECT_THROW (resampling.compute ([] (const ResampledBlock<pcl::PointNormal>&) {}), std::runtime_error);
      else
        EXPECT_THROW (resampling.compute (cloud), std::runtime_error);
      EXPECT_GT (calls, 0);
    }
}

TEST (Resampling, SmallCountsAreExact)
{
  const auto model = makeSphereModel ();
  for (std::size_t n : {1u, 7u, 41u, 42u, 43u, 1000u})
    EXPECT_EQ (resample (model, n)->size (), n);
}

// A cloud beyond this machine's memory is refused with the reason before it is built (setDensity (3e8) on
// fandisk ran 16 s, then std::bad_alloc; without a limit, an OOM kill). Blocks stream any count.
TEST (Resampling, CloudBeyondTheMachinesMemoryIsRefused)
{
  const double physical = physicalMemoryBytes ();
  const std::size_t count = SparseSurfaceResampling<pcl::PointNormal>::max_points;
  if (!(physical > 0.0 && physical < 90.0 * static_cast<double> (count)))
    GTEST_SKIP () << "this machine holds 1e9 points (" << physical / 1e9 << " GB)";
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (makePlaneModel ());
  resampling.setPointCount (count);
  pcl::PointCloud<pcl::PointNormal> cloud;
  const auto start = std::chrono::steady_clock::now ();
  try
  {
    resampling.compute (cloud);
    ADD_FAILURE () << "a cloud of 1e9 points was built";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("more than this machine's"), std::string::npos) << e.what ();
  }
  EXPECT_LT (std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count (), 5.0);
  EXPECT_TRUE (cloud.empty ());
}

TEST (Resampling, RefusesBadSetup)
{
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  pcl::PointCloud<pcl::PointNormal> cloud;
  // Each message names the method, as stage_base.h's error policy says, and the value given.
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { resampling.compute (cloud); }),
             "[SparseSurfaceResampling::compute] no input model (setInputModel)");
  resampling.setInputModel (makePlaneModel ());
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { resampling.compute (cloud); }),
             "[SparseSurfaceResampling::compute] no density given (setPointCount, setDensity or setSpacing)");
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { resampling.setPointCount (0); }),
             "[SparseSurfaceResampling::setPointCount] point count must be in [1, " +
               std::to_string (SparseSurfaceResampling<pcl::PointNormal>::max_points) + "], got 0");
  EXPECT_THROW (resampling.setPointCount (SparseSurfaceResampling<pcl::PointNormal>::max_points + 1), Error);
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { resampling.setDensity (-0.5); }),
             "[SparseSurfaceResampling::setDensity] density must be a positive number of points per unit area, got -0.5");
  EXPECT_THROW (resampling.setDensity (std::nan ("")), Error);
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] { resampling.setSpacing (0.0); }),
             "[SparseSurfaceResampling::setSpacing] spacing must be a positive length, got 0");
  // 1 / spacing^2 overflows to infinity or underflows to 0: the error names the spacing given.
  for (const auto& [spacing, text] : {std::pair (1e-200, "spacing 1e-200 gives"), std::pair (1e200, "spacing 1e+200 gives")})
    try
    {
      resampling.setSpacing (spacing);
      ADD_FAILURE () << "spacing " << spacing << " accepted";
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find (text), std::string::npos) << e.what ();
    }
  resampling.setDensity (1e12);  // about 4e12 points on the unit sphere (area 4 pi), over the limit
  EXPECT_THROW (resampling.compute (cloud), Error);
  auto empty = std::make_shared<SparseSurfaceModel> ();
  empty->basis = std::make_shared<CosineDictionary> (12);
  resampling.setInputModel (empty);
  resampling.setDensity (1.0);
  EXPECT_THROW (resampling.compute (cloud), Error);

  // A model built in memory with a patch that is no surface is refused, naming it (a NaN seed aborted in
  // the kd-tree; an atom outside the basis wrote past the evaluator's tables; a NaN frame gave NaN points).
  const std::vector<std::pair<std::string, std::function<void (PatchCode&)>>> broken = {
    {"patch 3 origin is not finite", [] (PatchCode& c) { c.origin.x () = std::nan (""); }},
    {"patch 3 frame is not finite", [] (PatchCode& c) { c.frame (1, 2) = std::nan (""); }},
    {"patch 3 frame is not orthonormal", [] (PatchCode& c) { c.frame (0, 0) = 2.0; }},
    {"patch 3 radius is not positive", [] (PatchCode& c) { c.radius = -1.0; }},
    {"patch 3 has atom index 200 outside the basis", [] (PatchCode& c) { c.atoms = {200}, c.coefficients = {0.1}; }},
    {"patch 3 repeats atom 5", [] (PatchCode& c) { c.atoms = {5, 5}, c.coefficients = {0.1, 0.2}; }},
    {"patch 3 coefficient is not finite", [] (PatchCode& c) { c.atoms = {5}, c.coefficients = {INFINITY}; }},
    {"patch 3 footprint extent is negative", [] (PatchCode& c) { c.footprint.extent[2] = -0.5f; }},
    {"beyond the range of float coordinates", [] (PatchCode& c) { c.origin.z () = 1e35; }},
  };
  for (const auto& [message, breakIt] : broken)
  {
    auto model = makePlaneModel ();
    breakIt (model->patches[3]);
    resampling.setInputModel (model);
    resampling.setPointCount (100);
    try
    {
      resampling.compute (cloud);
      ADD_FAILURE () << "accepted: " << message;
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find (message), std::string::npos) << e.what ();
    }
  }
}

namespace
{
  /// The message compute (cloud), then the streamed compute, throw with \a options on the plane model;
  /// empty if compute gives its 100 points.
  std::string
  refusal (const SparseSurfaceResamplingOptions& options, bool streamed = false)
  {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (makePlaneModel ());
    resampling.setPointCount (100);
    resampling.setOptions (options);
    try
    {
      std::size_t points = 0;
      if (streamed)
        resampling.compute ([&] (const ResampledBlock<pcl::PointNormal>& block) { points += block.cloud.size (); });
      else
      {
        pcl::PointCloud<pcl::PointNormal> cloud;
        resampling.compute (cloud);
        points = cloud.size ();
      }
      return points == 100 ? "" : std::to_string (points) + " points";
    }
    catch (const Error& e)
    {
      return e.what ();
    }
  }
} // namespace

TEST (Resampling, RefusesOptionsOutOfRange)
{
  const double nan = std::numeric_limits<double>::quiet_NaN ();
  const double inf = std::numeric_limits<double>::infinity ();
  using Set = std::function<void (SparseSurfaceResamplingOptions&)>;
  // Each bad value is refused by compute with a message naming the field.
  const std::vector<std::pair<std::string, std::vector<Set>>> bad = {
    {"jitter", {[] (auto& o) { o.jitter = -0.01; }, [] (auto& o) { o.jitter = 1.01; }, [&] (auto& o) { o.jitter = nan; }}},
    {"max_area_weight",
     {[] (auto& o) { o.max_area_weight = 0.99; }, [&] (auto& o) { o.max_area_weight = nan; },
      [&] (auto& o) { o.max_area_weight = inf; }}},
    {"area_pass_cells", {[] (auto& o) { o.area_pass_cells = 0; }, [] (auto& o) { o.area_pass_cells = -1; }}},
    {"height_tolerance",
     {[] (auto& o) { o.ownership.height_tolerance = -0.01; }, [&] (auto& o) { o.ownership.height_tolerance = nan; },
      [&] (auto& o) { o.ownership.height_tolerance = inf; }}},
    {"min_normal_cosine",
     {[] (auto& o) { o.ownership.min_normal_cosine = -1.01; }, [] (auto& o) { o.ownership.min_normal_cosine = 1.01; },
      [&] (auto& o) { o.ownership.min_normal_cosine = nan; }}},
    {"max_height",
     {[] (auto& o) { o.ownership.max_height = 0.0; }, [] (auto& o) { o.ownership.max_height = -1.0; },
      [&] (auto& o) { o.ownership.max_height = nan; }, [&] (auto& o) { o.ownership.max_height = inf; }}},
    {"max_slope_angle",
     {[] (auto& o) { o.ownership.max_slope_angle = 0.0; }, [] (auto& o) { o.ownership.max_slope_angle = -10.0; },
      [] (auto& o) { o.ownership.max_slope_angle = std::nextafter (90.0, 91.0); },
      [] (auto& o) { o.ownership.max_slope_angle = 91.0; }, [&] (auto& o) { o.ownership.max_slope_angle = nan; }}},
    {"opposite_clearance",
     {[] (auto& o) { o.ownership.opposite_clearance = -0.01; }, [&] (auto& o) { o.ownership.opposite_clearance = nan; },
      [&] (auto& o) { o.ownership.opposite_clearance = inf; }}},
  };
  for (const auto& [field, sets] : bad)
    for (std::size_t k = 0; k < sets.size (); ++k)
    {
      SparseSurfaceResamplingOptions options;
      sets[k] (options);
      EXPECT_THROW (options.validate (), Error) << field << " #" << k;
      for (bool streamed : {false, true})
      {
        const std::string message = refusal (options, streamed);
        EXPECT_NE (message.find (field + " = "), std::string::npos) << field << " #" << k << ": " << message;
        EXPECT_NE (message.find ("out of range"), std::string::npos) << field << " #" << k << ": " << message;
      }
    }
  // The boundary values are accepted, and the defaults (every tool and node starts from them).
  const std::vector<Set> good = {
    [] (auto&) {},
    [] (auto& o) { o.jitter = 0.0; },
    [] (auto& o) { o.jitter = 1.0; },
    [] (auto& o) { o.max_area_weight = 1.0; },
    [] (auto& o) { o.area_pass_cells = 1; },
    [] (auto& o) { o.ownership.height_tolerance = 0.0; },
    [] (auto& o) { o.ownership.min_normal_cosine = -1.0; },
    [] (auto& o) { o.ownership.min_normal_cosine = 1.0; },
    [] (auto& o) { o.ownership.max_height = 1e-3; },
    [] (auto& o) { o.ownership.max_slope_angle = 90.0; },
    [] (auto& o) { o.ownership.max_slope_angle = 1e-3; },
    [] (auto& o) { o.ownership.opposite_clearance = 0.0; },
  };
  for (std::size_t k = 0; k < good.size (); ++k)
  {
    SparseSurfaceResamplingOptions options;
    good[k] (options);
    EXPECT_NO_THROW (options.validate ()) << "#" << k;
    EXPECT_EQ (refusal (options), "") << "#" << k;
  }
}

TEST (Resampling, DensityBelowAPointAPatchKeepsTheArea)
{
  // The unit sphere (area 4 pi) in 42 caps of 1.2 units^2: below a point a cap, a patch smaller than a cell
  // once kept a whole cell of area wherever its middle lay inside (10 points per unit^2: 44 points and an
  // area of 4.4 per the model, 0.25: 42 points and 168).
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (makeSphereModel ());
  pcl::PointCloud<pcl::PointNormal> cloud;
  for (const double density : {0.25, 1.0, 3.0, 10.0, 1000.0})
  {
    resampling.setDensity (density);
    resampling.compute (cloud);
    const double expected = 4.0 * M_PI * density;
    EXPECT_NEAR (resampling.getEstimatedArea (), 4.0 * M_PI, 0.04 * 4.0 * M_PI) << "density " << density;
    // Each patch rounds its expected count up or down at random: the total is within a few standard deviations.
    EXPECT_NEAR (static_cast<double> (cloud.size ()), expected, 4.0 * std::sqrt (expected) + 1.0) << "density " << density;
  }
}

TEST (Resampling, DensityTooLowForTheModelSaysSo)
{
  // The sphere of tangent discs (about 17 units^2) at 1e-6 points per unit^2: no cell keeps a point. The
  // message names the density rather than claiming the model has no surface.
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (makeSphereModel ());
  resampling.setDensity (1e-6);
  pcl::PointCloud<pcl::PointNormal> cloud;
  try
  {
    resampling.compute (cloud);
    FAIL () << "no error, " << cloud.size () << " points";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("at density 1e-06 points per unit area"), std::string::npos) << e.what ();
  }
  // A density that gives points still does.
  resampling.setDensity (10.0);
  resampling.compute (cloud);
  EXPECT_GT (cloud.size (), 100u);
}

// A sliver 10000 median edges long among small triangles: the cover of each triangle that finds nearest faces
// grew with the square of its length (5e7 points here; found by a review), now with its area and
// length. The distance to the sliver's far end stays exact.
TEST (CloudQuality, LongSliverIsCoveredAlongItsLength)
{
  TriangleMesh mesh = makePlaneGrid (40, 0.2);
  const int v = static_cast<int> (mesh.vertices.size ());
  mesh.vertices.emplace_back (0.3, 0.0, 0.0);
  mesh.vertices.emplace_back (150.3, 0.0, 0.0);
  mesh.vertices.emplace_back (0.3, 0.001, 0.0);
  mesh.triangles.emplace_back (v, v + 1, v + 2);
  pcl::PointCloud<pcl::PointNormal> cloud;
  pcl::PointNormal point;
  point.x = 150.0f;
  point.y = 0.0f;
  point.z = 0.25f;  // above the sliver near its far end
  point.normal_x = point.normal_y = 0.0f;
  point.normal_z = 1.0f;
  cloud.push_back (point);
  CloudQualityOptions options;
  options.probes = 1000;
  const auto start = std::chrono::steady_clock::now ();
  const CloudQuality q = evaluateCloudQuality (mesh, cloud, options);
  const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  EXPECT_NEAR (q.max_distance, 0.25, 1e-6);
  EXPECT_LT (seconds, 1.5);  // about 0.01 s now
}

TEST (CloudQuality, NearestFaceIsExactNextToLargeTriangles)
{
  // A large floor triangle (centroid 30 units away) under a strip of 32 small triangles facing down, half
  // a unit above the query. The 16 triangles with the nearest centroids are all small ones; a point on
  // the floor with the floor's normal was measured against them and counted as flipped (sword, cheese-cgal).
  TriangleMesh mesh;
  mesh.vertices = {Eigen::Vector3d (-10, -10, 0), Eigen::Vector3d (90, -10, 0), Eigen::Vector3d (-10, 90, 0)};
  mesh.triangles.emplace_back (0, 1, 2);
  for (int i = 0; i < 32; ++i)
  {
    const int v = static_cast<int> (mesh.vertices.size ());
    const double x = -1.6 + 0.1 * i;
    mesh.vertices.emplace_back (x, -0.05, 0.5);
    mesh.vertices.emplace_back (x + 0.1, -0.05, 0.5);
    mesh.vertices.emplace_back (x, 0.05, 0.5);
    mesh.triangles.emplace_back (v, v + 2, v + 1);  // normal -z
  }
  pcl::PointCloud<pcl::PointNormal> cloud;
  pcl::PointNormal point;
  point.x = 0.0f;
  point.y = 0.0f;
  point.z = 0.01f;
  point.normal_x = 0.0f;
  point.normal_y = 0.0f;
  point.normal_z = 1.0f;
  cloud.push_back (point);
  CloudQualityOptions options;
  options.probes = 100;
  const CloudQuality quality = evaluateCloudQuality (mesh, cloud, options);
  EXPECT_EQ (quality.flipped, 0u);
  EXPECT_NEAR (quality.max_distance, 0.01, 1e-6);
  EXPECT_LT (quality.mean_normal_angle, 1e-3);
}

TEST (CloudQuality, BrokenMeshesAreRefusedAndEmptyOnesGiveZeros)
{
  pcl::PointCloud<pcl::PointNormal> cloud;
  pcl::PointNormal point;
  point.x = point.y = point.z = 0.25f;
  point.normal_x = point.normal_y = 0.0f;
  point.normal_z = 1.0f;
  cloud.push_back (point);
  TriangleMesh nan_corner = makePlaneGrid (3, 0.5);
  nan_corner.vertices[4].z () = std::nan ("");
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { evaluateCloudQuality (nan_corner, cloud); }).find ("non-finite corner"),
             std::string::npos);
  TriangleMesh out_of_range = makePlaneGrid (3, 0.5);
  out_of_range.triangles[2][0] = 100000000;  // far out: reading it would crash, not only mislead
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { evaluateCloudQuality (out_of_range, cloud); }).find ("out of range"),
             std::string::npos);
  const CloudQuality empty = evaluateCloudQuality (TriangleMesh (), cloud);
  EXPECT_EQ (empty.max_distance, 0.0);
  EXPECT_EQ (empty.flipped, 0u);
  // The same point over a sound grid: a quarter above it.
  EXPECT_NEAR (evaluateCloudQuality (makePlaneGrid (3, 0.5), cloud).max_distance, 0.25, 1e-7);
}

TEST (CloudQuality, PointPastAKnifeEdgeMatchesEitherFace)
{
  // A 20-degree wedge: two faces meet at the edge x = 0 (along y), their normals 160 degrees apart. A
  // point just past the edge is equally near both faces (its nearest surface point is the edge), so the
  // surface normal there is either face's: with either normal it is not flipped, whichever face comes
  // first in the mesh (the nearest face used to be the one with the lower index). A point above face A
  // with the opposite of A's normal still is.
  const double half = 10.0 * M_PI / 180.0;
  for (bool a_first : {true, false})
  {
    TriangleMesh mesh;
    mesh.vertices = {Eigen::Vector3d (0, -1, 0), Eigen::Vector3d (0, 1, 0),
                     Eigen::Vector3d (-std::cos (half), 0, std::sin (half)), Eigen::Vector3d (-std::cos (half), 0, -std::sin (half))};
    const Eigen::Vector3i face_a (0, 1, 2), face_b (0, 3, 1);  // A on top (normal about +z), B below (about -z)
    mesh.triangles = a_first ? std::vector<Eigen::Vector3i>{face_a, face_b} : std::vector<Eigen::Vector3i>{face_b, face_a};
    const std::vector<Eigen::Vector3d> normals = computeFaceNormals (mesh);
    const Eigen::Vector3d normal_a = normals[a_first ? 0 : 1], normal_b = normals[a_first ? 1 : 0];
    ASSERT_GT (normal_a.z (), 0.9);
    ASSERT_NEAR (std::acos (normal_a.dot (normal_b)) * 180.0 / M_PI, 160.0, 1e-9);
    pcl::PointCloud<pcl::PointNormal> cloud;
    auto add = [&] (const Eigen::Vector3d& position, const Eigen::Vector3d& normal) {
      pcl::PointNormal point;
      point.getVector3fMap () = position.cast<float> ();
      point.getNormalVector3fMap () = normal.cast<float> ();
      cloud.push_back (point);
    };
    const Eigen::Vector3d past_edge (0.001, 0.0, 0.0);
    add (past_edge, normal_a);
    add (past_edge, normal_b);
    add (Eigen::Vector3d (-0.5, 0.0, 0.5 * std::tan (half) + 0.001), -normal_a);  // on A, facing into the wedge
    CloudQualityOptions options;
    options.probes = 100;
    const CloudQuality quality = evaluateCloudQuality (mesh, cloud, options);
    EXPECT_EQ (quality.flipped, 1u) << (a_first ? "face A first" : "face B first");
    EXPECT_NEAR (quality.max_distance, 0.001, 1e-5);
  }
}

// The yardstick itself on a known answer (the resampling tests' completeness, largest gap, NN CV, RMS and
// normal statistics all come from evaluateCloudQuality): the square [-1, 1]^2 at z = 0, sampled on its left
// half only by a 20 x 40 grid of spacing 0.05 (x = -0.975 .. -0.025), columns alternately 0.01 and 0.03 above
// it, normals 10 degrees off except every tenth point (flipped), and 5 NaN points.
TEST (CloudQuality, KnownAnswersOnAHalfSampledSquare)
{
  const TriangleMesh mesh = makePlaneGrid (8, 1.0);
  pcl::PointCloud<pcl::PointNormal> cloud;
  const double tilt = 10.0 * M_PI / 180.0;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 40; ++j)
    {
      pcl::PointNormal p;
      p.x = static_cast<float> (-1.0 + 0.05 * (i + 0.5));
      p.y = static_cast<float> (-1.0 + 0.05 * (j + 0.5));
      p.z = i % 2 == 0 ? 0.01f : 0.03f;
      const bool flip = (40 * i + j) % 10 == 9;
      p.normal_x = 0.0f;
      p.normal_y = flip ? 0.0f : static_cast<float> (std::sin (tilt));
      p.normal_z = flip ? -1.0f : static_cast<float> (std::cos (tilt));
      cloud.push_back (p);
    }
  for (int k = 0; k < 5; ++k)
  {
    pcl::PointNormal p;
    p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN ();
    p.normal_x = p.normal_y = 0.0f;
    p.normal_z = 1.0f;
    cloud.push_back (p);
  }
  const CloudQuality q = evaluateCloudQuality (mesh, cloud);  // 50000 probes, holes beyond 3 spacings
  std::cout << "half-sampled square: completeness " << q.completeness << ", largest gap " << q.largest_gap
            << " spacings, NN CV " << q.nn_cv << std::endl;
  EXPECT_EQ (q.invalid, 5u);
  EXPECT_NEAR (q.bbox_diagonal, 2.0 * std::sqrt (2.0), 1e-12);
  // Distances: half the points 0.01 off, half 0.03.
  EXPECT_NEAR (q.mean_distance, 0.02, 1e-7);
  EXPECT_NEAR (q.rms_distance, std::sqrt (0.0005), 1e-7);
  EXPECT_NEAR (q.max_distance, 0.03, 1e-7);
  // Angles: 720 points at 10 degrees, 80 at 180: mean 27, median 10, the 90th percentile the first flip.
  EXPECT_EQ (q.flipped, 80u);
  EXPECT_NEAR (q.mean_normal_angle, 27.0, 1e-3);
  EXPECT_NEAR (q.median_normal_angle, 10.0, 1e-3);
  EXPECT_NEAR (q.p90_normal_angle, 180.0, 1e-3);
  // A regular grid: every nearest neighbour 0.05 away (along y, same height).
  EXPECT_LT (q.nn_cv, 1e-4);
  // Spacing sqrt(area 4 / 800 valid points); a probe is covered within 3 spacings = 0.212: the left half and
  // x <= -0.025 + sqrt(0.212^2 - 0.03^2) = 0.185 on the right, (1 + 0.185) / 2 = 0.5925 of the square. The
  // farthest probes, at x = 1, are 1.0257 = 14.51 spacings from the last column.
  EXPECT_NEAR (q.spacing, std::sqrt (4.0 / 800.0), 1e-12);
  EXPECT_NEAR (q.completeness, 0.5925, 0.01);
  EXPECT_NEAR (q.largest_gap, 14.5, 0.1);
  // Covered everywhere by the same grid over the whole square.
  pcl::PointCloud<pcl::PointNormal> whole;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
    {
      pcl::PointNormal p;
      p.x = static_cast<float> (-1.0 + 0.05 * (i + 0.5));
      p.y = static_cast<float> (-1.0 + 0.05 * (j + 0.5));
      p.z = 0.0f;
      p.normal_x = p.normal_y = 0.0f;
      p.normal_z = 1.0f;
      whole.push_back (p);
    }
  // Four points on a line, 0.1, 0.3 and 0.5 apart: nearest-neighbour distances 0.1, 0.1, 0.3, 0.5, mean 0.25,
  // standard deviation sqrt(0.0275), CV 0.6633; spacing sqrt(4 / 4).
  pcl::PointCloud<pcl::PointNormal> line;
  for (const float x : {0.0f, 0.1f, 0.4f, 0.9f})
  {
    pcl::PointNormal p;
    p.x = x;
    p.y = p.z = 0.0f;
    p.normal_x = p.normal_y = 0.0f;
    p.normal_z = 1.0f;
    line.push_back (p);
  }
  const CloudQuality spread = evaluateCloudQuality (mesh, line);
  EXPECT_NEAR (spread.nn_cv, std::sqrt (0.0275) / 0.25, 1e-5);
  EXPECT_NEAR (spread.spacing, 1.0, 1e-12);
  EXPECT_EQ (spread.max_distance, 0.0);
  const CloudQuality full = evaluateCloudQuality (mesh, whole);
  EXPECT_EQ (full.completeness, 1.0);
  EXPECT_LT (full.largest_gap, 0.7072);  // a probe is at most 0.025 sqrt 2 = 0.7071 spacings of 0.05 from a point
  EXPECT_EQ (full.flipped, 0u);
  EXPECT_NEAR (full.mean_normal_angle, 0.0, 1e-6);
}
