// SparseSurfaceResampling<pcl::PointNormal> on encoded meshes: generated surfaces with known geometry and the shared real
// meshes (skipped when ../shared/meshes is absent). Each cloud has 4 x the vertex count, exactly.
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <gtest/gtest.h>

#include "model_helpers.h"
#include "shared_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// Footprint angles of the encoder, as pcl_sparse_resample sets them: with the default 16 the
  /// conservative footprints overshoot open borders and sharp edges and double the distance errors.
  constexpr int footprint_angles = 64;

  struct Bounds
  {
    double rms_over_diagonal;  ///< RMS distance to the mesh / bbox diagonal
    double mean_angle;         ///< mean normal angle, degrees
    double nn_cv;              ///< nearest-neighbour CV
    double flipped_fraction;   ///< largest fraction of flipped normals (0 on clean surfaces)
    double completeness;       ///< smallest fraction of surface probes with a point within 3 spacings
  };

  struct Result
  {
    SparseSurfaceModel::Ptr model;
    pcl::PointCloud<pcl::PointNormal> cloud;
    CloudQuality quality;
  };

  Result
  encodeAndResample (const TriangleMesh::ConstPtr& mesh, std::size_t count)
  {
    Result result;
    SparseSurfaceEncoderOptions encoder_options;
    encoder_options.coding.footprint_angles = footprint_angles;
    result.model = pcl_sparse_test::encodeMesh (mesh, encoder_options);
    result.cloud = pcl_sparse_test::resampleModel (result.model, count);
    CloudQualityOptions options;
    options.probes = 20000;
    result.quality = evaluateCloudQuality (*mesh, result.cloud, options);
    return result;
  }

  /// How many points of \a cloud repeat the position of an earlier one.
  std::size_t
  repeatedPositions (const pcl::PointCloud<pcl::PointNormal>& cloud)
  {
    std::vector<std::array<float, 3>> positions;
    for (const pcl::PointNormal& point : cloud)
      positions.push_back ({point.x, point.y, point.z});
    std::sort (positions.begin (), positions.end ());
    return static_cast<std::size_t> (positions.end () - std::unique (positions.begin (), positions.end ()));
  }

  void
  checkSurface (const std::string& name, const TriangleMesh::ConstPtr& mesh, const Bounds& bounds)
  {
    const std::size_t count = 4 * mesh->numVertices ();
    const Result r = encodeAndResample (mesh, count);
    const CloudQuality& q = r.quality;
    std::cout << name << ": " << r.model->numPatches () << " patches, RMS/diag " << q.rms_distance / q.bbox_diagonal
              << ", mean angle " << q.mean_normal_angle << ", flipped " << q.flipped << ", completeness "
              << q.completeness << ", largest gap " << q.largest_gap << ", NN CV " << q.nn_cv << std::endl;
    EXPECT_EQ (r.cloud.size (), count) << name;
    // A cell with more points than kept places once repeated its candidate (blade: 2 pairs).
    EXPECT_EQ (repeatedPositions (r.cloud), 0u) << name << ": points written twice";
    EXPECT_EQ (q.invalid, 0u) << name;
    EXPECT_LT (q.rms_distance / q.bbox_diagonal, bounds.rms_over_diagonal) << name;
    EXPECT_LT (q.mean_normal_angle, bounds.mean_angle) << name;
    EXPECT_LE (static_cast<double> (q.flipped), bounds.flipped_fraction * count) << name;
    EXPECT_GE (q.completeness, bounds.completeness) << name << ": holes wider than 3 spacings";
    EXPECT_LT (q.nn_cv, bounds.nn_cv) << name;
  }

  TriangleMesh::ConstPtr
  sharedMesh (const std::string& file)
  {
    const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/" + file;
    if (!std::ifstream (path).good ())
      return nullptr;
    return std::make_shared<TriangleMesh> (loadTriangleMesh (path));
  }
} // namespace

TEST (ResamplingMeshes, SphereAnalytic)
{
  auto mesh = std::make_shared<TriangleMesh> (makeIcosphere (4));
  const Result r = encodeAndResample (mesh, 4 * mesh->numVertices ());
  ASSERT_EQ (r.cloud.size (), 4 * mesh->numVertices ());
  double square = 0.0, angle = 0.0;
  for (const auto& p : r.cloud)
  {
    const Eigen::Vector3d q = p.getVector3fMap ().cast<double> ();
    square += (q.norm () - 1.0) * (q.norm () - 1.0);
    const double c = p.getNormalVector3fMap ().cast<double> ().dot (q.normalized ());
    angle += std::acos (std::min (1.0, c)) * 180.0 / M_PI;
    ASSERT_GT (c, 0.0);
  }
  const double rms = std::sqrt (square / r.cloud.size ());
  std::cout << "sphere: analytic RMS " << rms << ", mean normal angle " << angle / r.cloud.size () << std::endl;
  // The icosphere's own chord error is about 1e-3 at this resolution; the codes follow the mesh.
  EXPECT_LT (rms, 1.5e-3);
  EXPECT_LT (angle / r.cloud.size (), 3.5);
  EXPECT_LT (r.quality.nn_cv, 0.3);
  EXPECT_EQ (r.quality.completeness, 1.0);
}

// The quadric basis on a finer sphere (10242 vertices, chord sag 4.4e-5): a cap of the sphere is nearly one of
// its codes, so most resampled normals follow the true radial direction to a few hundredths of a degree; the
// cosines alone (Dct) code the caps only to about 1 %, and their normals err by degrees. Measured: mean 0.027
// degrees, 99.9th percentile 0.17, largest 0.26 (Dct: 1.78, 11.7, 24.6), RMS |r - 1| 8.7e-5 (Dct: 6.2e-4).
// With plain OMP scores (before OmpSelection::orthogonal_scores) 6 of the 208 patches took cos(pi x) cos(pi y)
// after the constant, since x^2's score was divided by its whole norm, mean included, and the monomials never
// reached 0.3 of the best score after it: mean 0.078, p99.9 3.9, largest 17.7 degrees.
TEST (ResamplingMeshes, SphereNormalsWithTheQuadric)
{
  const auto mesh = std::make_shared<TriangleMesh> (makeIcosphere (5));
  for (const CosineBasisKind basis : {CosineBasisKind::DctQuadric, CosineBasisKind::Dct})
  {
    SparseSurfaceEncoderOptions options;
    options.basis = basis;
    const pcl::PointCloud<pcl::PointNormal> cloud =
      pcl_sparse_test::resampleModel (pcl_sparse_test::encodeMesh (mesh, options), 4 * mesh->numVertices ());
    ASSERT_EQ (cloud.size (), 4 * mesh->numVertices ());
    double square = 0.0, angle = 0.0;
    std::vector<double> angles;
    for (const auto& p : cloud)
    {
      const Eigen::Vector3d q = p.getVector3fMap ().cast<double> ();
      square += (q.norm () - 1.0) * (q.norm () - 1.0);
      const double c = p.getNormalVector3fMap ().cast<double> ().dot (q.normalized ());
      ASSERT_TRUE (std::isfinite (c)) << "a NaN normal or position";  // std::min (1.0, NaN) would count it as 0 degrees
      const double a = std::acos (std::min (1.0, c)) * 180.0 / M_PI;
      angle += a;
      angles.push_back (a);
    }
    std::sort (angles.begin (), angles.end ());
    const double largest = angles.back (), p999 = angles[angles.size () * 999 / 1000];
    const double rms = std::sqrt (square / cloud.size ()), mean = angle / cloud.size ();
    std::cout << cosineBasisKindName (basis) << ": RMS |r - 1| " << rms << ", normal angle mean " << mean << ", p99.9 " << p999
              << ", largest " << largest << " degrees" << std::endl;
    if (basis == CosineBasisKind::DctQuadric)
    {
      EXPECT_LT (rms, 1.3e-4);
      EXPECT_LT (mean, 0.05);
      EXPECT_LT (p999, 0.5);
      EXPECT_LT (largest, 1.0);
    }
    else
    {
      EXPECT_GT (mean, 1.0);  // what the quadric removes
      EXPECT_GT (p999, 10.0);
    }
  }
}

TEST (ResamplingMeshes, GeneratedSurfaces)
{
  // The plane is one patch seeded at a corner: its footprint (64 angles, conservative) overshoots the
  // square's borders a little, which is all of its distance error (heights are exactly 0).
  // Measured (bounds about 1.5x): plane RMS/diag 1.55e-3 (8.2e-3 once; its bound 0.012 stayed), NN CV 0.12; paraboloid 7.5e-4, 1.05 degrees, 0.17;
  // cylinder 3.9e-4, 1.9 degrees, 0.18; cube 1.2e-4, 0 degrees, 0.19; every probe within 3 spacings.
  checkSurface ("plane", std::make_shared<TriangleMesh> (makePlaneGrid (40)), {0.0025, 0.01, 0.2, 0.0, 1.0});
  checkSurface ("paraboloid", std::make_shared<TriangleMesh> (makeHeightFieldGrid (40, 40, 1.0, 1.0, [] (double x, double y) {
                  return 0.5 * (x * x + y * y);
                })),
                {1.2e-3, 1.6, 0.25, 0.0, 1.0});
  checkSurface ("cylinder", std::make_shared<TriangleMesh> (makeCylinder (64, 32)), {6e-4, 2.5, 0.25, 0.0, 1.0});
  checkSurface ("cube", std::make_shared<TriangleMesh> (makeCube (16)), {2.5e-4, 0.5, 0.25, 0.0, 1.0});
}

TEST (ResamplingMeshes, SharedMeshes)
{
  // Measured with default options (bounds about 1.5x): fandisk RMS/diag 1.24e-4, 0.92 degrees, no flipped
  // normal; bunny-npm-1k 6.7e-4, 7.5 degrees (tiny patches on thin features), none; blade (open, thin)
  // 2.2e-4, 2.4 degrees, 8 flipped normals of 32924 (0.024 %; issue 13 asks for none: bench/results/flips.md).
  // 1 of the 20000 fandisk probes here (13 of 200000 in bench_meshes) lies 3.0-3.35 spacings from the cloud,
  // on a face of two flat patches that hold it well inside their footprints (not found why: open); p99 0.79
  // spacings.
  const std::vector<std::pair<std::string, Bounds>> cases = {{"fandisk.off", {2e-4, 1.5, 0.3, 0.0, 0.9999}},
                                                             {"bunny-npm-1k.obj", {1e-3, 9.0, 0.3, 0.0005, 1.0}},
                                                             {"blade.off", {3.5e-4, 3.5, 0.3, 0.0005, 0.999}}};
  if (!std::ifstream (std::string (PCL_SPARSE_SHARED_MESHES) + "/README.md").good ())
    GTEST_SKIP () << "shared meshes not found in " << PCL_SPARSE_SHARED_MESHES;
  for (const auto& entry : cases)
  {
    const TriangleMesh::ConstPtr mesh = sharedMesh (entry.first);
    if (!mesh)
    {
      ADD_FAILURE () << entry.first << " is missing from " << PCL_SPARSE_SHARED_MESHES;
      continue;
    }
    checkSurface (entry.first, mesh, entry.second);
  }
}

namespace
{
  /// Largest distance of any point from the mesh (cloud -> mesh) and largest hole (mesh -> cloud, from the
  /// surface probes), both / bbox diagonal, of a model resampled at 4 x the vertex count.
  std::pair<double, double>
  strayAndGap (const TriangleMesh& mesh, const SparseSurfaceModel::ConstPtr& model)
  {
    CloudQualityOptions options;
    options.probes = 20000;
    const pcl::PointCloud<pcl::PointNormal> cloud = pcl_sparse_test::resampleModel (model, 4 * mesh.numVertices ());
    EXPECT_EQ (cloud.size (), 4 * mesh.numVertices ());
    const CloudQuality q = evaluateCloudQuality (mesh, cloud, options);
    EXPECT_EQ (q.invalid, 0u) << "non-finite points are left out of the largest distance";
    return {q.max_distance / q.bbox_diagonal, q.largest_gap * q.spacing / q.bbox_diagonal};
  }

  /// Bounds of checkNoStrays, / bbox diagonal: the largest distance with 16 and with footprint_angles angles,
  /// and the largest hole (both).
  struct StrayBounds
  {
    double distance_16, distance_64, hole;
  };

  void
  checkNoStrays (const std::string& name, const TriangleMesh::ConstPtr& mesh, const StrayBounds& bounds, bool through_file = false)
  {
    for (const int angles : {16, footprint_angles})
    {
      SparseSurfaceEncoderOptions encoder_options;
      encoder_options.coding.footprint_angles = angles;
      const SparseSurfaceModel::Ptr model = pcl_sparse_test::encodeMesh (mesh, encoder_options);
      const std::pair<double, double> d = strayAndGap (*mesh, model);
      std::cout << name << " (" << angles << " angles): largest distance / diag " << d.first << ", largest hole / diag "
                << d.second << std::endl;
      const double bound = angles == 16 ? bounds.distance_16 : bounds.distance_64;
      EXPECT_LT (d.first, bound) << name << ", " << angles << " angles: points far off the surface";
      EXPECT_LT (d.second, bounds.hole) << name << ", " << angles << " angles: a hole in the cloud";
      if (!through_file)
        continue;
      // The same through a quantised file (tolerance 1e-3 of the diagonal, at most 8 angles kept).
      ModelWriteOptions write;
      write.tolerance = 1e-3;
      const std::vector<std::uint8_t> bytes = encodeModel (*model, write);
      const auto decoded = std::make_shared<SparseSurfaceModel> (decodeModel (bytes.data (), bytes.size ()));
      const std::pair<double, double> f = strayAndGap (*mesh, decoded);
      std::cout << name << " (" << angles << " angles, quantised file): largest distance / diag " << f.first
                << ", largest hole / diag " << f.second << std::endl;
      EXPECT_LT (f.first, bound) << name << ", " << angles << " angles, quantised file: points far off the surface";
      EXPECT_LT (f.second, bounds.hole) << name << ", " << angles << " angles, quantised file: a hole in the cloud";
    }
  }

  /// Mean angle (degrees) of the mesh's own area-weighted vertex normals against their nearest faces.
  double
  vertexNormalFloor (const TriangleMesh& mesh)
  {
    const std::vector<Eigen::Vector3d> normals = computeVertexNormals (mesh, buildMeshTopology (mesh));
    pcl::PointCloud<pcl::PointNormal> cloud;
    for (std::size_t v = 0; v < mesh.numVertices (); ++v)
    {
      pcl::PointNormal point;
      point.getVector3fMap () = mesh.vertices[v].cast<float> ();
      point.getNormalVector3fMap () = normals[v].cast<float> ();
      cloud.push_back (point);
    }
    CloudQualityOptions options;
    options.probes = 1000;
    return evaluateCloudQuality (mesh, cloud, options).mean_normal_angle;
  }
} // namespace

// Regression: bench_format once reported a Hausdorff distance of 0.1 - 1 x the diagonal on blub and spot
// (rho 0.001). Measured at 4 x the vertex count: blub 8.5e-3 (64 angles) / 1.1e-2 (16), spot 5.2e-3 /
// 1.6e-2, the worst points at footprint borders (centrality > 0.9) or on tiny patches whose codes
// oscillate; holes below 1.1e-2. A stray point (a code extrapolating far from its data) breaks the bound.
// Measured again (file or not): blub 5.5e-3 (64) / 2.77e-2 (16), holes 7.4e-3; spot 2.5e-3 / 6.2e-3, holes
// 4.7e-3. Bounds per mesh and angle count, about 1.5x (blub at 16 angles keeps 0.03): the one 0.03 for all
// was 5 to 12 times the 64-angle distances.
TEST (ResamplingMeshes, NoStrayPointsShared)
{
  // Skipped only when ../shared/meshes is absent; a mesh missing from it fails (as SharedMeshes).
  if (!std::ifstream (std::string (PCL_SPARSE_SHARED_MESHES) + "/README.md").good ())
    GTEST_SKIP () << "shared meshes not found in " << PCL_SPARSE_SHARED_MESHES;
  for (const auto& [name, bounds] : {std::pair<std::string, StrayBounds> {"blub.obj", {0.03, 0.0085, 0.011}},
                                      std::pair<std::string, StrayBounds> {"spot.obj", {0.01, 0.004, 0.007}}})
  {
    const TriangleMesh::ConstPtr mesh = sharedMesh (name);
    if (!mesh)
    {
      ADD_FAILURE () << name << " is missing from " << PCL_SPARSE_SHARED_MESHES;
      continue;
    }
    checkNoStrays (name, mesh, bounds, true);
  }
}

// Measured (default options, Dct atoms): torus largest distance 1.07e-2 (16 angles) / 7.3e-3 (64), holes
// 9.2e-3 (a few spacings of these coarse meshes); cube 1.98e-2 / 5.4e-3 (16 angles overshoot the sharp
// edges), holes 1.9e-2. Bounds about 1.5 x those, per angle count: the one 0.03 for all let the 64-angle
// footprints lose their edge (a cube at 16 angles' 2e-2) unnoticed.
TEST (ResamplingMeshes, NoStrayPointsGenerated)
{
  checkNoStrays ("torus", std::make_shared<TriangleMesh> (makeTorus (96, 32, 1.0, 0.25)), {0.016, 0.011, 0.014});
  // The cube at 16 angles: 0.0301 with the small patches merged into their neighbours (8 elements).
  checkNoStrays ("cube", std::make_shared<TriangleMesh> (makeCube (16)), {0.032, 0.008, 0.028});
}

// The normals' error is a property of the basis, not of resampling: the paper's atoms are even in x and y
// (h_x = 0 on x = 0, h_y = 0 on y = 0), the Dct atoms are not. Measured mean angle against the nearest face
// (64 angles): blub paper 7.27, Dct 3.52, vertex normals 3.50; spot 5.52, 2.87, 3.83.
TEST (ResamplingMeshes, DctNormalsReachTheVertexNormalFloor)
{
  // Skipped only when ../shared/meshes is absent; a mesh missing from it fails (as SharedMeshes).
  if (!std::ifstream (std::string (PCL_SPARSE_SHARED_MESHES) + "/README.md").good ())
    GTEST_SKIP () << "shared meshes not found in " << PCL_SPARSE_SHARED_MESHES;
  for (const std::string name : {"blub.obj", "spot.obj"})
  {
    const TriangleMesh::ConstPtr mesh = sharedMesh (name);
    if (!mesh)
    {
      ADD_FAILURE () << name << " is missing from " << PCL_SPARSE_SHARED_MESHES;
      continue;
    }
    SparseSurfaceEncoderOptions encoder_options;
    encoder_options.coding.footprint_angles = footprint_angles;
    encoder_options.basis = CosineBasisKind::Dct;
    const pcl::PointCloud<pcl::PointNormal> cloud =
      pcl_sparse_test::resampleModel (pcl_sparse_test::encodeMesh (mesh, encoder_options), 4 * mesh->numVertices ());
    CloudQualityOptions options;
    options.probes = 1000;
    const CloudQuality q = evaluateCloudQuality (*mesh, cloud, options);
    EXPECT_EQ (q.invalid, 0u) << name << ": non-finite points are left out of the normal angles";
    const double floor = vertexNormalFloor (*mesh);
    std::cout << name << ": Dct mean normal angle " << q.mean_normal_angle << " (median " << q.median_normal_angle << ", p90 "
              << q.p90_normal_angle << "), vertex normals " << floor << std::endl;
    EXPECT_LT (q.mean_normal_angle, 1.15 * floor) << name;
    EXPECT_LT (q.p90_normal_angle, 1.25 * 6.92) << name;  // vertex normals' p90: blub 6.69, spot 6.92
  }
}

// The slope bound of resampling (PatchOwnershipOptions::max_slope_angle). cheese-cgal.off (a CAD part full of
// small patches at sharp corners and thin walls) is where patches most often own places their code sees
// steeply: over an edge, or oscillating between few vertices. With the default 50 degrees those places go to
// the overlapping patch that sees them frontally: measured against the mesh (default options, 4 points per
// vertex), the cloud's RMS distance is 0.76 of what 75 degrees gave, the mean normal error 0.79 of it, flipped
// normals 97 instead of 139, and the probes within 3 spacings 99.22 % instead of 99.30 %
// (bench/results/max_slope.md has all 25 meshes). Since jets that tilt a patch's steepest triangle past 72
// degrees are refused as frames (patch_frame.cpp), fewer codes are steep and 75 degrees does better:
// RMS 0.85 of it, mean normal error 0.84, flipped 81 instead of 91.
TEST (ResamplingMeshes, SlopeBoundLeavesEdgesToTheFrontalPatch)
{
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/../extra-meshes/cheese-cgal.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const auto mesh = std::make_shared<const TriangleMesh> (loadTriangleMesh (path));
  SparseSurfaceEncoderOptions encoder_options;
  encoder_options.coding.footprint_angles = footprint_angles;
  const SparseSurfaceModel::Ptr model = pcl_sparse_test::encodeMesh (mesh, encoder_options);
  const std::size_t count = 4 * mesh->numVertices ();
  CloudQualityOptions quality_options;
  quality_options.probes = 50000;
  auto measure = [&] (double max_slope_angle) {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    SparseSurfaceResamplingOptions options;
    options.ownership.max_slope_angle = max_slope_angle;
    // The slope bound alone: the knife-edge clearance takes 0.06 % more probes past 3 spacings here
    // (test_opposite_clearance has its own measures).
    options.ownership.opposite_clearance = 0.0;
    resampling.setOptions (options);
    resampling.setInputModel (model);
    resampling.setPointCount (count);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    EXPECT_EQ (cloud.size (), count);
    const CloudQuality quality = evaluateCloudQuality (*mesh, cloud, quality_options);
    EXPECT_EQ (quality.invalid, 0u) << max_slope_angle << " degrees";
    return quality;
  };
  EXPECT_EQ (SparseSurfaceResamplingOptions ().ownership.max_slope_angle, 50.0);
  const CloudQuality bounded = measure (50.0), loose = measure (75.0);
  std::cout << "cheese-cgal, " << model->numPatches () << " patches, 50 (75) degrees: RMS/diag "
            << bounded.rms_distance / bounded.bbox_diagonal << " (" << loose.rms_distance / loose.bbox_diagonal
            << "), mean angle " << bounded.mean_normal_angle << " (" << loose.mean_normal_angle << "), completeness "
            << bounded.completeness << " (" << loose.completeness << "), flipped " << bounded.flipped << " ("
            << loose.flipped << ")" << std::endl;
  // Measured with the quadric basis: RMS 0.93x, mean angle 0.90x, flipped 63 / 86 (the cosines alone
  // oscillated more, and the bound gained more there: under 0.9x both).
  EXPECT_LT (bounded.rms_distance, 0.95 * loose.rms_distance);
  EXPECT_LT (bounded.mean_normal_angle, 0.95 * loose.mean_normal_angle);
  EXPECT_LT (bounded.flipped, loose.flipped);
  EXPECT_GE (bounded.completeness, loose.completeness - 0.002);
}
