#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/dct_cosine_dictionary.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include "analytic_surfaces.h"
#include "shared_data.h"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <stdexcept>
#include <string>

using namespace pcl_sparse;
using pcl_sparse_test::paraboloid;

namespace
{
  SparseSurfaceModel
  encode (const TriangleMesh& mesh, const SparseSurfaceEncoderOptions& options = SparseSurfaceEncoderOptions (),
          int threads = 0)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (std::make_shared<TriangleMesh> (mesh));
    encoder.setOptions (options);
    encoder.setNumberOfThreads (threads);
    SparseSurfaceModel model;
    encoder.compute (model);
    return model;
  }

  ModelStatistics
  encodeStatistics (const TriangleMesh& mesh, const SparseSurfaceEncoderOptions& options = SparseSurfaceEncoderOptions ())
  {
    const SparseSurfaceModel model = encode (mesh, options);
    const ModelStatistics stats = model.statistics (mesh.vertices);
    std::cout << "  N_V " << stats.num_vertices << "  M " << stats.num_patches << "  nnz " << stats.num_nonzeros
              << "  RMSE/diag " << stats.rmse_over_diagonal << "  CR " << stats.compression_ratio << std::endl;
    EXPECT_EQ (stats.uncovered, 0u);
    return stats;
  }
} // namespace

TEST (SparseSurfaceEncoder, PlaneIsExact)
{
  const ModelStatistics stats = encodeStatistics (makePlaneGrid (30, 1.0));
  EXPECT_LT (stats.rmse_over_diagonal, 1e-12);
  // A flat patch grows over the whole square (its area bound never binds: A_p / A_p^proj = 1), with no atom.
  EXPECT_EQ (stats.num_patches, 1u);
  EXPECT_EQ (stats.num_nonzeros, 0u);
}

TEST (SparseSurfaceEncoder, SphereCylinderParaboloid)
{
  EXPECT_LT (encodeStatistics (makeCylinder (96, 48, 1.0, 1.0)).rmse_over_diagonal, 1e-4);
  // Sphere and paraboloid with cosines only (Dct, as the paper's L = 12): nearly every patch uses all 12
  // atoms and stops above eps: cosines fit a cap's x^2 + y^2 only to ~1 %, and patch size is set by eta (1 %
  // flatness), not by the resolution. That leaves 1.2e-4 to 1.8e-4; twice the atoms reach the 1e-4 bound.
  const TriangleMesh sphere = makeIcosphere (4, 1.0);
  const TriangleMesh bowl = makeHeightFieldGrid (60, 60, 1.0, 1.0, paraboloid);
  // The bases compared on the same patches, all of them (the redundant ones dropped, the paraboloid keeps 37
  // of its 80 patches: RedundantPatchesOnTheParaboloid below; none merged either).
  SparseSurfaceEncoderOptions cosines;
  cosines.basis = CosineBasisKind::Dct;
  cosines.patches.drop_redundant_patches = false;
  cosines.patches.merge_own_elements = 0;
  // The radii as the patches have them: on this regular grid every patch is alike, and the radius grid's
  // up to 2.2 % larger support takes the cosines' paraboloid from 1.5e-4 to 2.5e-4 at once (support 1.015: 1.57e-4,
  // 1.02: 2.53e-4; the sphere's goes down, 1.84e-4 -> 1.70e-4, and the quadric's moves by 3 %).
  cosines.coding.radius_on_grid = false;
  SparseSurfaceEncoderOptions quadric;
  quadric.patches.drop_redundant_patches = false;
  quadric.patches.merge_own_elements = 0;
  EXPECT_LT (encodeStatistics (sphere, cosines).rmse_over_diagonal, 2e-4);
  EXPECT_LT (encodeStatistics (bowl, cosines).rmse_over_diagonal, 2e-4);
  SparseSurfaceEncoderOptions more_atoms = cosines;
  more_atoms.coding.max_atoms = 24;
  EXPECT_LT (encodeStatistics (sphere, more_atoms).rmse_over_diagonal, 1e-4);
  EXPECT_LT (encodeStatistics (bowl, more_atoms).rmse_over_diagonal, 1e-4);
  // The default basis adds the quadric's monomials: a cap is nearly a quadric, so 12 atoms reach the bound
  // (and the paraboloid's patches eps with fewer). Measured: sphere 6.6e-5 with 2064 atoms (cosines: 1.8e-4
  // with 2064), paraboloid 5.1e-5 with 632 (cosines: 1.5e-4 with 960).
  const ModelStatistics sphere_cosines = encodeStatistics (sphere, cosines), bowl_cosines = encodeStatistics (bowl, cosines);
  const ModelStatistics sphere_quadric = encodeStatistics (sphere, quadric), bowl_quadric = encodeStatistics (bowl, quadric);
  std::cout << "sphere RMSE/diag, atoms: cosines " << sphere_cosines.rmse_over_diagonal << ", " << sphere_cosines.num_nonzeros
            << "; quadric " << sphere_quadric.rmse_over_diagonal << ", " << sphere_quadric.num_nonzeros << ". Paraboloid: cosines "
            << bowl_cosines.rmse_over_diagonal << ", " << bowl_cosines.num_nonzeros << "; quadric "
            << bowl_quadric.rmse_over_diagonal << ", " << bowl_quadric.num_nonzeros << std::endl;
  EXPECT_LT (sphere_quadric.rmse_over_diagonal, 1e-4);
  EXPECT_LT (bowl_quadric.rmse_over_diagonal, 1e-4);
  EXPECT_LT (sphere_quadric.rmse_over_diagonal, 0.5 * sphere_cosines.rmse_over_diagonal);
  EXPECT_LT (bowl_quadric.rmse_over_diagonal, 0.5 * bowl_cosines.rmse_over_diagonal);
  EXPECT_LE (sphere_quadric.num_nonzeros, sphere_cosines.num_nonzeros);
  EXPECT_LT (bowl_quadric.num_nonzeros, 0.75 * bowl_cosines.num_nonzeros);
  // Our option: a basis support 1.5 times the patch radius keeps the patch off the square's sides, where
  // every cosine has zero slope; on the sphere that alone nearly halves the cosines' error with 12 atoms
  // (1.7e-4 -> 0.95e-4 when written).
  SparseSurfaceEncoderOptions wider = cosines;
  wider.coding.support_scale = 1.5;
  const SparseSurfaceModel model = encode (sphere, wider);
  EXPECT_LT (model.statistics (sphere.vertices).rmse_over_diagonal, 0.75 * encodeStatistics (sphere, cosines).rmse_over_diagonal);
  for (const PatchCode& code : model.patches)
    for (const Eigen::Vector2d& xy : code.vertex_xy)
    {
      EXPECT_LE (xy.norm (), (1.0 + 1e-6) / 1.5);
      EXPECT_TRUE (code.footprint.contains (xy.x (), xy.y ()));
    }
}

// Our option: the half-period cosine basis (both parities, same n^2 atoms). Its even atoms are the paper's
// atoms of frequency < n / 2 only, so it trades resolution of the even part for the odd part. On sphere
// and paraboloid, whose patches are nearly even caps, that does not pay: the floor there is L = 12 atoms
// against the 1 / k^2 cosine series of x^2 + y^2 (paper n = 24 does not help either), and the sphere stays
// at 1.77e-4 (not under the 1e-4 target), the paraboloid goes from 1.10e-4 to 1.66e-4. On fandisk, whose
// feature patches are one-sided (off-centre creases), it more than halves the error (Fandisk below).
// Patches are the same (the basis is chosen after them).
TEST (SparseSurfaceEncoder, DctBasisOnEvenCaps)
{
  const TriangleMesh sphere = makeIcosphere (4, 1.0);
  const TriangleMesh bowl = makeHeightFieldGrid (60, 60, 1.0, 1.0, paraboloid);
  SparseSurfaceEncoderOptions dct;
  dct.basis = CosineBasisKind::Dct;
  SparseSurfaceEncoderOptions paper = encoderPresetOptions (EncoderPreset::Paper);
  EXPECT_EQ (SparseSurfaceEncoderOptions ().basis, CosineBasisKind::DctQuadric);  // the default since 2026-12-01
  EXPECT_EQ (paper.basis, CosineBasisKind::Paper);
  // The preset's other samples and footprints set as the default's, so only the basis differs in the fit.
  paper.patches.complete_faces = dct.patches.complete_faces;
  paper.coding.triangle_samples = dct.coding.triangle_samples;
  paper.coding.clip_footprints_at_border = dct.coding.clip_footprints_at_border;
  dct.patches.drop_redundant_patches = paper.patches.drop_redundant_patches;  // the paper's patches, all kept
  dct.patches.merge_own_elements = paper.patches.merge_own_elements;
  dct.coding.radius_on_grid = paper.coding.radius_on_grid;  // false: the patches' own radii (as above)
  const SparseSurfaceModel model = encode (sphere, dct);
  EXPECT_NE (dynamic_cast<const DctCosineDictionary*> (model.basis.get ()), nullptr);
  const ModelStatistics sphere_paper = encodeStatistics (sphere, paper), sphere_dct = encodeStatistics (sphere, dct);
  EXPECT_EQ (sphere_dct.num_patches, sphere_paper.num_patches);
  EXPECT_NEAR (sphere_dct.rmse_over_diagonal, sphere_paper.rmse_over_diagonal, 0.02 * sphere_paper.rmse_over_diagonal);
  EXPECT_LT (sphere_dct.rmse_over_diagonal, 2e-4);
  const ModelStatistics bowl_paper = encodeStatistics (bowl, paper), bowl_dct = encodeStatistics (bowl, dct);
  EXPECT_EQ (bowl_dct.num_patches, bowl_paper.num_patches);
  EXPECT_GT (bowl_dct.rmse_over_diagonal, bowl_paper.rmse_over_diagonal);
  EXPECT_LT (bowl_dct.rmse_over_diagonal, 2e-4);
}

// The default options (Dct atoms) are SameModelForAnyThreadCount's; this is the paper preset's basis,
// normal cone and patches.
TEST (SparseSurfaceEncoder, PaperPresetSameModelForAnyThreadCount)
{
  const TriangleMesh mesh = makeTorus (48, 24, 1.0, 0.35);
  const SparseSurfaceEncoderOptions paper = encoderPresetOptions (EncoderPreset::Paper);
  const SparseSurfaceModel a = encode (mesh, paper, 1);
  const SparseSurfaceModel b = encode (mesh, paper, 2);
  EXPECT_NE (dynamic_cast<const CosineDictionary*> (a.basis.get ()), nullptr);
  ASSERT_EQ (a.patches.size (), b.patches.size ());
  ASSERT_GT (a.patches.size (), 64u);
  for (std::size_t p = 0; p < a.patches.size (); ++p)
  {
    EXPECT_EQ (a.patches[p].atoms, b.patches[p].atoms);
    EXPECT_EQ (a.patches[p].coefficients, b.patches[p].coefficients);
    EXPECT_EQ (a.patches[p].vertices, b.patches[p].vertices);
    EXPECT_EQ (a.patches[p].footprint.extent, b.patches[p].footprint.extent);
  }
}

TEST (SparseSurfaceEncoder, RejectsBadOptionsAndInput)
{
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  SparseSurfaceModel model;
  EXPECT_THROW (encoder.compute (model), Error);
  encoder.setInputMesh (std::make_shared<TriangleMesh> (makePlaneGrid (4)));
  SparseSurfaceEncoderOptions options;
  options.patches.rho = 0.0;
  encoder.setOptions (options);
  EXPECT_THROW (encoder.compute (model), Error);
  options = SparseSurfaceEncoderOptions ();
  options.coding.nyquist_factor = 1.5;
  encoder.setOptions (options);
  EXPECT_THROW (encoder.compute (model), Error);
  options = SparseSurfaceEncoderOptions ();
  options.coding.max_atoms = 0;
  encoder.setOptions (options);
  EXPECT_THROW (encoder.compute (model), Error);
  options = SparseSurfaceEncoderOptions ();
  options.coding.tolerance = 1.0;
  encoder.setOptions (options);
  EXPECT_THROW (encoder.compute (model), Error);
  options = SparseSurfaceEncoderOptions ();
  options.basis = static_cast<CosineBasisKind> (7);
  encoder.setOptions (options);
  EXPECT_THROW (encoder.compute (model), Error);
  for (const double preference : {-0.1, 1.5, std::nan ("")})
  {
    options = SparseSurfaceEncoderOptions ();
    options.coding.quadric_preference = preference;
    EXPECT_THROW (options.validate (), Error) << preference;
  }
  options.coding.quadric_preference = 0.0;
  EXPECT_NO_THROW (options.validate ());
  for (const double degrees : {-1.0, 181.0, std::nan ("")})
  {
    options = SparseSurfaceEncoderOptions ();
    options.coding.footprint_reach_degrees = degrees;
    EXPECT_THROW (options.validate (), Error) << degrees;
    options = SparseSurfaceEncoderOptions ();
    options.coding.footprint_reach_max_tilt_degrees = degrees;
    EXPECT_THROW (options.validate (), Error) << degrees;
  }
}

TEST (SparseSurfaceEncoder, NonFiniteVertexInFacesIsLeftUncovered)
{
  // A mesh given through the API (the file loaders refuse it) with a NaN vertex that faces use: the sampling's
  // coverage pass gave it a one-vertex patch with a NaN origin, and the model could be neither saved nor
  // resampled. The vertex is left uncovered, as a NaN vertex in no face is.
  TriangleMesh mesh = makeIcosphere (2);
  const int nan_vertex = 7;
  mesh.vertices[nan_vertex] = Eigen::Vector3d::Constant (std::nan (""));
  for (const int threads : {1, 2})
  {
    const SparseSurfaceModel model = encode (mesh, SparseSurfaceEncoderOptions (), threads);
    ASSERT_GT (model.patches.size (), 10u);
    for (const PatchCode& patch : model.patches)
      ASSERT_TRUE (patch.origin.allFinite ());
    const std::vector<std::uint8_t> bytes = encodeModel (model, ModelWriteOptions ());
    EXPECT_EQ (decodeModel (bytes.data (), bytes.size ()).patches.size (), model.patches.size ());
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (std::make_shared<const SparseSurfaceModel> (model));
    resampling.setPointCount (2000);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    ASSERT_EQ (cloud.size (), 2000u);
    // On the coarse icosphere's faces (0.01-0.02 inside the unit sphere), and beside the hole the NaN
    // vertex's faces leave (the same again at the hole's rim).
    float worst = 0.0f;
    for (const pcl::PointNormal& p : cloud)
      worst = std::max (worst, std::abs (p.getVector3fMap ().norm () - 1.0f));
    EXPECT_LT (worst, 0.04f);
    EXPECT_EQ (model.statistics (mesh.vertices).uncovered, 1u);
  }
}

// On a torus every patch border is smooth: the default reach widens footprints (never narrows one) and
// changes nothing else; with no reach they are the clipped ones of before.
TEST (SparseSurfaceEncoder, FootprintsReachAlongSmoothBorders)
{
  const TriangleMesh mesh = makeTorus (48, 24, 1.0, 0.35);
  SparseSurfaceEncoderOptions clipped_options;
  clipped_options.coding.footprint_reach_degrees = 0.0;
  const SparseSurfaceModel reached = encode (mesh), clipped = encode (mesh, clipped_options);
  ASSERT_EQ (reached.patches.size (), clipped.patches.size ());
  std::size_t extents = 0, raised = 0;
  for (std::size_t p = 0; p < reached.patches.size (); ++p)
  {
    const PatchCode &a = reached.patches[p], &b = clipped.patches[p];
    EXPECT_EQ (a.atoms, b.atoms);
    EXPECT_EQ (a.coefficients, b.coefficients);
    ASSERT_EQ (a.footprint.extent.size (), b.footprint.extent.size ());
    for (std::size_t k = 0; k < a.footprint.extent.size (); ++k)
    {
      EXPECT_GE (a.footprint.extent[k], b.footprint.extent[k]) << p << " " << k;
      ++extents;
      raised += a.footprint.extent[k] > b.footprint.extent[k] * 1.001f;
    }
  }
  EXPECT_GT (raised, extents / 10) << raised << " of " << extents;  // measured 1505 of 8448
}

TEST (SparseSurfaceEncoder, SameModelForAnyThreadCount)
{
  const TriangleMesh mesh = makeTorus (48, 24, 1.0, 0.35);
  const SparseSurfaceModel a = encode (mesh, SparseSurfaceEncoderOptions (), 1);
  const SparseSurfaceModel b = encode (mesh, SparseSurfaceEncoderOptions (), 2);
  ASSERT_EQ (a.patches.size (), b.patches.size ());
  ASSERT_GT (a.patches.size (), 64u);  // enough patches for the parallel loop to run in parallel
  for (std::size_t p = 0; p < a.patches.size (); ++p)
  {
    EXPECT_EQ (a.patches[p].atoms, b.patches[p].atoms);
    EXPECT_EQ (a.patches[p].coefficients, b.patches[p].coefficients);
    EXPECT_EQ (a.patches[p].vertices, b.patches[p].vertices);
    EXPECT_EQ (a.patches[p].footprint.extent, b.patches[p].footprint.extent);
  }
}

// A progress callback may throw to cancel, also while the patches are coded in parallel (it ended the
// program in std::terminate before).
TEST (SparseSurfaceEncoder, ProgressCallbackMayThrowToCancel)
{
  for (int threads : {1, 2})
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (std::make_shared<TriangleMesh> (makeTorus (48, 24, 1.0, 0.35)));
    encoder.setNumberOfThreads (threads);
    bool coding_seen = false;
    encoder.setProgressCallback ([&] (const std::string& stage, double fraction) {
      if (stage == "coding" && fraction > 0.0 && fraction < 1.0)
      {
        coding_seen = true;
        throw std::runtime_error ("cancelled");
      }
    });
    SparseSurfaceModel model;
    EXPECT_THROW (encoder.compute (model), std::runtime_error) << threads << " threads";
    EXPECT_TRUE (coding_seen);
  }
}

// Coding progress comes from the calling thread in fixed steps, so every thread count sees the same reports
// (reports from inside the parallel loop depended on which thread drew which patches).
TEST (SparseSurfaceEncoder, CodingProgressIsTheSameForAnyThreadCount)
{
  std::vector<std::vector<double>> seen;
  for (int threads : {1, 2, 3})
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (std::make_shared<TriangleMesh> (makeTorus (48, 24, 1.0, 0.35)));
    encoder.setNumberOfThreads (threads);
    std::vector<double> fractions;
    encoder.setProgressCallback ([&] (const std::string& stage, double fraction) {
      if (stage == "coding")
        fractions.push_back (fraction);
    });
    SparseSurfaceModel model;
    encoder.compute (model);
    seen.push_back (fractions);
  }
  ASSERT_GE (seen[0].size (), 8u);
  EXPECT_GT (seen[0].front (), 0.0);
  EXPECT_LT (seen[0].front (), 0.2);
  EXPECT_DOUBLE_EQ (seen[0].back (), 1.0);
  EXPECT_EQ (seen[1], seen[0]);
  EXPECT_EQ (seen[2], seen[0]);
}

TEST (SparseSurfaceEncoder, FootprintsContainTheirVertices)
{
  const SparseSurfaceModel model = encode (makeIcosphere (3, 1.0));
  ASSERT_FALSE (model.patches.empty ());
  std::size_t checked = 0;
  for (const PatchCode& code : model.patches)
    for (const Eigen::Vector2d& xy : code.vertex_xy)
    {
      EXPECT_TRUE (code.footprint.contains (xy.x (), xy.y ()));
      ++checked;
    }
  // Every one of the 642 vertices lies in at least one patch (an empty vertex list would check nothing).
  EXPECT_GE (checked, 642u);
}

// The paper's claim for the Nyquist cap: on a coarse mesh, plain OMP (f = 0) fits the vertices at least as
// tightly but oscillates between them; f = 0.5 is closer to the true surface at the triangles' barycentres.
TEST (SparseSurfaceEncoder, NyquistCapReducesErrorBetweenVertices)
{
  // 162 vertices; rho = 0.05 gives patches of ~10 vertices (at the paper's rho = 0.001 every patch of
  // so coarse a sphere is a single vertex: nothing to oscillate).
  const double rho = 0.05;
  const TriangleMesh mesh = makeIcosphere (2, 1.0);
  auto between_error = [&] (const SparseSurfaceModel& model, const SparseSurfaceEncoder<pcl::PointXYZ>& encoder) {
    // Each patch evaluated at the barycentres of its own triangles: distance of the point to the sphere.
    double sum = 0.0;
    std::size_t count = 0;
    const std::vector<Patch>& patches = encoder.getPatches ();
    for (std::size_t p = 0; p < patches.size (); ++p)
    {
      const Patch& patch = patches[p];
      std::map<int, int> index;
      for (std::size_t k = 0; k < patch.vertices.size (); ++k)
        index[patch.vertices[k]] = static_cast<int> (k);
      for (int f : patch.triangles)
      {
        Eigen::Vector3d c = Eigen::Vector3d::Zero ();
        for (int k = 0; k < 3; ++k)
          c += patch.local[index.at (mesh.triangles[f][k])] / 3.0;
        const double h = model.evaluate (p, c.x (), c.y ()).value;
        const Eigen::Vector3d world = model.patches[p].toWorld (Eigen::Vector3d (c.x (), c.y (), h));
        sum += std::pow (world.norm () - 1.0, 2);
        ++count;
      }
    }
    return std::sqrt (sum / count);
  };
  auto run = [&] (double f, double& vertex_rmse, double& between) {
    SparseSurfaceEncoderOptions options;
    options.coding.nyquist_factor = f;
    // The paper's samples (vertices, and extra ones only below min_samples): our samples inside every
    // triangle (triangle_samples) hold plain OMP between the vertices too, which is what this measures;
    // and the paper's patches: faces added by completion lie at the patch's edge, where both extrapolate.
    options.coding.triangle_samples = 0.0;
    options.patches.complete_faces = false;  // and the growth's triangles only, where the patches have data
    options.patches.rho = rho;
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (std::make_shared<TriangleMesh> (mesh));
    encoder.setOptions (options);
    SparseSurfaceModel model;
    encoder.compute (model);
    vertex_rmse = model.statistics (mesh.vertices).rmse;
    between = between_error (model, encoder);
  };
  double vertex_plain, between_plain, vertex_capped, between_capped;
  run (0.0, vertex_plain, between_plain);
  run (0.5, vertex_capped, between_capped);
  std::cout << "  f = 0: vertex RMSE " << vertex_plain << ", barycentre RMSE " << between_plain << "\n"
            << "  f = 0.5: vertex RMSE " << vertex_capped << ", barycentre RMSE " << between_capped << std::endl;
  EXPECT_LE (vertex_plain, vertex_capped * (1.0 + 1e-9));
  EXPECT_LT (between_capped, between_plain);
}

TEST (SparseSurfaceEncoder, Fandisk)
{
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/fandisk.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const TriangleMesh mesh = loadTriangleMesh (path);
  const ModelStatistics stats = encodeStatistics (mesh, encoderPresetOptions (EncoderPreset::Paper));
  EXPECT_EQ (stats.num_vertices, 6475u);
  // The authors' code: M = 713, CR 0.80, RMSE / diag 2.2e-4 at rho 0.001. Ours (bench/results/encode.md):
  // about M = 530, CR 0.59, RMSE / diag 2.5e-4.
  EXPECT_LT (stats.rmse_over_diagonal, 3e-4);
  EXPECT_LT (stats.compression_ratio, 0.8);
  // Our DCT-like basis (the default), same patches: 2.44e-4 -> 1.01e-4 at nearly the same CR (0.57 -> 0.58).
  SparseSurfaceEncoderOptions dct = encoderPresetOptions (EncoderPreset::Paper);
  dct.basis = CosineBasisKind::Dct;
  const ModelStatistics dct_stats = encodeStatistics (mesh, dct);
  EXPECT_EQ (dct_stats.num_patches, stats.num_patches);
  EXPECT_LT (dct_stats.rmse_over_diagonal, 0.5 * stats.rmse_over_diagonal);
  EXPECT_LT (dct_stats.compression_ratio, 1.05 * stats.compression_ratio);
  // The default adds the authors' 72-degree cone: on fandisk nearly the same patches (503 to the paper's 505),
  // 1.12e-4; drops the redundant ones (468 patches, RMSE / diag 9.4e-5) and merges the small ones: 331, 1.11e-4.
  SparseSurfaceEncoderOptions every_patch;
  every_patch.patches.drop_redundant_patches = false;
  every_patch.patches.merge_own_elements = 0;
  const ModelStatistics all_stats = encodeStatistics (mesh, every_patch), default_stats = encodeStatistics (mesh);
  EXPECT_NEAR (static_cast<double> (all_stats.num_patches), static_cast<double> (stats.num_patches), 10.0);
  EXPECT_LT (all_stats.rmse_over_diagonal, 0.5 * stats.rmse_over_diagonal);
  EXPECT_LT (default_stats.num_patches, 0.95 * all_stats.num_patches);
  EXPECT_LT (default_stats.rmse_over_diagonal, 0.5 * stats.rmse_over_diagonal);
}

// Resampling draws points only inside the footprints: every point of every patch triangle must be inside.
TEST (SparseSurfaceEncoder, FootprintsCoverTheirTrianglesOnFandisk)
{
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/fandisk.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const TriangleMesh mesh = loadTriangleMesh (path);
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (std::make_shared<TriangleMesh> (mesh));
  SparseSurfaceModel model;
  encoder.compute (model);
  const std::vector<Patch>& patches = encoder.getPatches ();
  ASSERT_EQ (patches.size (), model.patches.size ());
  std::size_t checked = 0, outside = 0;
  for (std::size_t p = 0; p < patches.size (); ++p)
  {
    std::map<int, int> index;
    for (std::size_t k = 0; k < patches[p].vertices.size (); ++k)
      index[patches[p].vertices[k]] = static_cast<int> (k);
    for (int f : patches[p].triangles)
      for (const Eigen::Vector3d& b : {Eigen::Vector3d (1, 0, 0), Eigen::Vector3d (0.5, 0.5, 0),
                                       Eigen::Vector3d (0.2, 0.3, 0.5), Eigen::Vector3d (0.05, 0.9, 0.05)})
      {
        Eigen::Vector3d world = Eigen::Vector3d::Zero ();
        for (int c = 0; c < 3; ++c)
          world += b[c] * mesh.vertices[mesh.triangles[f][c]];
        // In the code's (x', y'): its radius is the patch's on the radius grid (coding/radius_grid.h).
        const Eigen::Vector3d q = model.patches[p].toLocal (world);
        ++checked;
        outside += !model.patches[p].footprint.contains (q.x (), q.y ());
      }
  }
  EXPECT_GT (checked, 10000u);
  EXPECT_EQ (outside, 0u);
}

TEST (SparseSurfaceEncoder, NoiseLevelSmoothsInsteadOfCoding)
{
  // A plane z = 0 sampled with Gaussian noise of sigma = 0.004 (a scan's noise), 0.2 % of the diagonal.
  const double sigma = 0.004;
  TriangleMesh noisy = makeHeightFieldGrid (60, 60, 1.0, 1.0, [] (double, double) { return 0.0; });
  std::mt19937 random (42);
  std::normal_distribution<double> noise (0.0, sigma);
  for (Eigen::Vector3d& v : noisy.vertices)
    v.z () += noise (random);
  auto distanceToTruth = [&] (const SparseSurfaceModel& model) {
    double sum = 0.0;
    for (const Eigen::Vector3d& v : model.reconstructVertices (noisy.numVertices ()))
      sum += v.z () * v.z ();
    return std::sqrt (sum / static_cast<double> (noisy.numVertices ()));
  };
  // Patches of 1 % of the area (rho 0.01): ~36 samples each, enough to average the noise out.
  SparseSurfaceEncoderOptions options;
  options.patches.rho = 0.01;
  const SparseSurfaceModel coded = encode (noisy, options);
  options.coding.noise_level = sigma;
  const SparseSurfaceModel smoothed = encode (noisy, options);
  std::cout << "  M " << coded.numPatches () << ", nnz " << coded.numNonZeros () << " -> " << smoothed.numNonZeros () << ", RMS to the true plane "
            << distanceToTruth (coded) << " -> " << distanceToTruth (smoothed) << std::endl;
  // Without the noise level every patch spends its L atoms on the noise and follows it.
  EXPECT_GT (distanceToTruth (coded), 0.5 * sigma);
  EXPECT_LT (distanceToTruth (smoothed), 0.6 * distanceToTruth (coded));  // measured 0.51x
  EXPECT_LT (smoothed.numNonZeros (), coded.numNonZeros () / 5);  // measured 11x fewer
  options.coding.noise_level = -1.0;
  EXPECT_THROW (encode (noisy, options), Error);
}
