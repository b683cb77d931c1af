/// Never bigger than the input (issue 13 point 2): SparseSurfaceEncoderOptions::max_compression_ratio, the
/// growth floor (PatchOptions::min_growth_vertices) and the atom budget (coding/atom_budget.h).

#include <pcl_sparse/coding/atom_budget.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/face_completion.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>
#include <pcl_sparse/tiles/memory_tile_source.h>
#include <pcl_sparse/tiles/tile_encoding.h>

#include <gtest/gtest.h>

#include "model_helpers.h"
#include "shared_data.h"

#include <fstream>
#include <iostream>
#include <numeric>

using namespace pcl_sparse;

namespace
{
  SparseSurfaceModel
  encode (const TriangleMesh::ConstPtr& mesh, const SparseSurfaceEncoderOptions& options, int threads = 1,
          std::vector<Patch>* patches = nullptr)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (mesh);
    encoder.setOptions (options);
    encoder.setNumberOfThreads (threads);
    SparseSurfaceModel model;
    encoder.compute (model);
    if (patches)
      *patches = encoder.getPatches ();
    return model;
  }

  std::size_t
  totalAtoms (const SparseSurfaceModel& model)
  {
    return model.numNonZeros ();
  }
} // namespace

TEST (AtomBudget, GainsAreWeightedSquaredResidualDecrements)
{
  // ||r|| 2 -> 1 -> 0.5 over 4 samples, radius 3, share 2: gains (4 - 1) / 4 * 9 * 2 and (1 - 0.25) / 4 * 18.
  const std::vector<double> gains = patchAtomGains ({2.0, 1.0, 0.5}, 3.0, 2.0, 4);
  ASSERT_EQ (gains.size (), 2u);
  EXPECT_DOUBLE_EQ (gains[0], 13.5);
  EXPECT_DOUBLE_EQ (gains[1], 3.375);
  EXPECT_TRUE (patchAtomGains ({1.0}, 1.0, 1.0, 1).empty ());  // no atom, nothing to gain
}

TEST (AtomBudget, GreedyAcrossPatchesInCodeOrder)
{
  // Patch 0's atoms buy 10, 1, 1; patch 1's 5, 4; patch 2's 0.5. Four atoms: 10, 5, 4, then 1 (patch 0).
  const AtomGains gains = {{10.0, 1.0, 1.0}, {5.0, 4.0}, {0.5}};
  EXPECT_EQ (allocateAtoms (gains, 4), (std::vector<int>{2, 2, 0}));
  EXPECT_EQ (allocateAtoms (gains, 0), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ (allocateAtoms (gains, -3), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ (allocateAtoms (gains, 100), (std::vector<int>{3, 2, 1}));  // every code whole
  // Ties go to the lower patch index.
  EXPECT_EQ (allocateAtoms ({{1.0}, {1.0}, {1.0}}, 2), (std::vector<int>{1, 1, 0}));
}

TEST (GrowthFloor, WaivesOnlyTheAreaBound)
{
  // An icosphere with 320 faces: each face is 1/320 of the area, so at rho = 0.001 no second face fits
  // and patches stop at the seed's fan. A floor of 20 vertices grows them on (the sphere is smooth, so
  // smooth variation and the cone allow it); on a cube the floor cannot cross the edges (delta).
  const TriangleMesh sphere = makeIcosphere (2);
  const MeshTopology topology = buildMeshTopology (sphere);
  PatchOptions options;
  auto sizes = [&] (const TriangleMesh& mesh, const MeshTopology& t, int floor) {
    options.min_growth_vertices = floor;
    const std::vector<Patch> patches = sampleFeatureAwarePatches (mesh, t, options, {}, {}, 1, nullptr).patches;
    std::size_t smallest = mesh.vertices.size ();
    std::size_t kept = 0;
    for (const Patch& p : patches)
    {
      smallest = std::min (smallest, p.size ());
      ++kept;
    }
    return std::make_pair (kept, smallest);
  };
  const auto plain = sizes (sphere, topology, 0);
  const auto floored = sizes (sphere, topology, 20);
  EXPECT_LT (floored.first, plain.first) << "fewer patches";
  EXPECT_GE (floored.second, 20u) << "every patch reaches the floor on a smooth closed surface";

  const TriangleMesh cube = makeCube (2);
  const MeshTopology cube_topology = buildMeshTopology (cube);
  options.min_growth_vertices = 1000;
  for (const Patch& p : sampleFeatureAwarePatches (cube, cube_topology, options, {}, {}, 1, nullptr).patches)
  {
    // No patch triangle is more than delta away from the seed's side: the floor does not cross edges.
    for (int f : p.triangles)
    {
      const Eigen::Vector3i& t = cube.triangles[f];
      const Eigen::Vector3d n = (cube.vertices[t[1]] - cube.vertices[t[0]]).cross (cube.vertices[t[2]] - cube.vertices[t[0]]).normalized ();
      const Eigen::Vector3i& t0 = cube.triangles[p.triangles.front ()];
      const Eigen::Vector3d n0 =
        (cube.vertices[t0[1]] - cube.vertices[t0[0]]).cross (cube.vertices[t0[2]] - cube.vertices[t0[0]]).normalized ();
      EXPECT_GT (n.dot (n0), 0.99);
    }
  }
  options.min_growth_vertices = -1;
  EXPECT_THROW (options.validate (), Error);
}

TEST (CompressionBound, CoarseMeshGetsTheCheaperCode)
{
  // A 162-vertex sphere at rho 0.001: every patch is a 7-vertex fan costing 13 frame values and up to 12
  // atoms for the 3 x ~3 values of the vertices it adds: the paper's configuration is bigger than its input.
  const auto mesh = std::make_shared<const TriangleMesh> (makeIcosphere (2));
  SparseSurfaceEncoderOptions unbounded;
  unbounded.max_compression_ratio = 0.0;
  std::vector<Patch> patches, unbounded_patches;
  const SparseSurfaceModel big = encode (mesh, unbounded, 1, &unbounded_patches);
  const SparseSurfaceModel model = encode (mesh, SparseSurfaceEncoderOptions (), 1, &patches);
  const ModelStatistics before = big.statistics (mesh->vertices), after = model.statistics (mesh->vertices);
  std::cout << "icosphere(2): CR " << before.compression_ratio << " -> " << after.compression_ratio << ", M "
            << before.num_patches << " -> " << after.num_patches << ", RMSE/diag " << before.rmse_over_diagonal
            << " -> " << after.rmse_over_diagonal << std::endl;
  ASSERT_GT (before.compression_ratio, 1.0) << "the case must exceed the bound without it";
  EXPECT_LE (after.compression_ratio, 1.0);
  EXPECT_LT (after.num_patches, before.num_patches) << "fewer frames";
  EXPECT_EQ (after.uncovered, 0u);
  // Fewer, larger patches must still cover the surface. The kept candidate (lowest RMSE) leaves 4 of the
  // 320 faces out of every patch's triangle list (another candidate of 12 patches, 3 % less accurate, leaves
  // none; with the cosines alone it was the one kept), but footprints reach over them: every probe of the
  // sphere has a resampled point within 2 spacings (largest gap measured: 1.3).
  std::cout << "faces in no patch: " << facesInNoPatch (*mesh, unbounded_patches).size () << " -> "
            << facesInNoPatch (*mesh, patches).size () << std::endl;
  const auto shared_model = std::make_shared<const SparseSurfaceModel> (model);
  const pcl::PointCloud<pcl::PointNormal> cloud = pcl_sparse_test::resampleModel (shared_model, 4 * mesh->vertices.size ());
  CloudQualityOptions quality_options;
  quality_options.hole_spacings = 2.0;
  const CloudQuality quality = evaluateCloudQuality (*mesh, cloud, quality_options);
  EXPECT_EQ (quality.completeness, 1.0);
  EXPECT_EQ (quality.flipped, 0u);
  // Measured: CR 2.31 -> 0.62, M 45 -> 12 (only the 32-vertex floor's frames fit), RMSE/diag 8.8e-4 ->
  // 1.05e-3 (the cosines alone: 4.0e-4 -> 2.1e-3), below the mesh's own chord error (edges of 0.3 on a unit
  // sphere stand 1.1e-2 off it, 3.3e-3 of the diagonal).
  EXPECT_LT (after.rmse_over_diagonal, 1.5e-3);

  // Same model for any thread count (the bunny case below has enough patches to code them in parallel).
  const SparseSurfaceModel threaded = encode (mesh, SparseSurfaceEncoderOptions (), 2);
  ASSERT_EQ (threaded.patches.size (), model.patches.size ());
  for (std::size_t p = 0; p < model.patches.size (); ++p)
  {
    EXPECT_EQ (threaded.patches[p].atoms, model.patches[p].atoms);
    EXPECT_EQ (threaded.patches[p].coefficients, model.patches[p].coefficients);
  }
}

// Tiled, each tile answers for its core vertices only: its margins are the neighbouring tiles', and counting
// them too let the merged model exceed the bound (bunny-npm-1k in 2 tiles: CR 1.58; found by a review).
// Measured here: CR 1.26 / 1.45 before, 0.76 / 0.52 now, at RMSE/diag 3.8e-4 -> 5.2e-4 and 2.7e-4 -> 9.2e-4:
// each tile must fit on its own, so a tile dense in patches gets fewer atoms than the whole would give it.
TEST (CompressionBound, TiledModelWithinTheBound)
{
  const auto mesh = std::make_shared<TriangleMesh> (makeIcosphere (3));
  for (int along : {2, 3})
  {
    TileGridOptions grid;
    grid.tiles_along_longest = along;
    TiledSurfaceEncoder encoder;
    encoder.setTileSource (std::make_shared<MemoryTileSource> (mesh, grid));
    encoder.setOptions ([] {
      SparseSurfaceEncoderOptions options;
      options.patches.rho = 0.0005;  // small patches: frames alone near the bound
      return options;
    } ());
    TiledModel tiled;
    encoder.compute (tiled);
    ASSERT_GT (tiled.tiles.size (), 1u);
    const ModelStatistics s = tiled.model.statistics (mesh->vertices);
    std::cout << along << " tiles along: M " << s.num_patches << ", CR " << s.compression_ratio << ", RMSE/diag "
              << s.rmse_over_diagonal << std::endl;
    EXPECT_LE (s.compression_ratio, 1.0) << along;
    EXPECT_EQ (s.uncovered, 0u) << along;
  }
}

TEST (CompressionBound, ModelWithinTheBoundIsUntouched)
{
  // A fine sphere is far below CR 1: the bound changes nothing, byte for byte; a tighter bound trims it.
  const auto mesh = std::make_shared<const TriangleMesh> (makeIcosphere (4));
  SparseSurfaceEncoderOptions unbounded;
  unbounded.max_compression_ratio = 0.0;
  const SparseSurfaceModel a = encode (mesh, unbounded), b = encode (mesh, SparseSurfaceEncoderOptions ());
  ASSERT_LT (a.compressionRatio (), 1.0);
  ASSERT_EQ (a.patches.size (), b.patches.size ());
  for (std::size_t p = 0; p < a.patches.size (); ++p)
  {
    EXPECT_EQ (a.patches[p].atoms, b.patches[p].atoms);
    EXPECT_EQ (a.patches[p].coefficients, b.patches[p].coefficients);
  }
  SparseSurfaceEncoderOptions tight;
  tight.max_compression_ratio = 0.5 * a.compressionRatio ();
  const SparseSurfaceModel c = encode (mesh, tight);
  EXPECT_LE (c.compressionRatio (), tight.max_compression_ratio);
  EXPECT_LT (totalAtoms (c), totalAtoms (a));
  EXPECT_EQ (c.statistics (mesh->vertices).uncovered, 0u);

  // The paper's preset has no bound.
  EXPECT_EQ (encoderPresetOptions (EncoderPreset::Paper).max_compression_ratio, 0.0);
  SparseSurfaceEncoderOptions bad;
  bad.max_compression_ratio = -1.0;
  EXPECT_THROW (bad.validate (), Error);
}

TEST (CompressionBound, BunnyNpm1kAtEveryRho)
{
  // Measured before the bound (default options): CR 1.87, 1.81, 1.22 at rho 0.0002, 0.001, 0.005, RMSE/diag
  // 1.6e-4, 2.6e-4, 5.0e-4. With it: CR <= 1 and RMSE/diag 5.1e-4, 5.1e-4, 5.2e-4; every vertex in a
  // patch and the resampled surface without holes wider than 3 spacings.
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/bunny-npm-1k.obj";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const auto mesh = std::make_shared<const TriangleMesh> (loadTriangleMesh (path));
  for (double rho : {0.0002, 0.001, 0.005})
  {
    SparseSurfaceEncoderOptions options;
    options.patches.rho = rho;
    std::vector<Patch> patches;
    auto model = std::make_shared<SparseSurfaceModel> (encode (mesh, options, 2, &patches));
    const ModelStatistics s = model->statistics (mesh->vertices);
    const pcl::PointCloud<pcl::PointNormal> cloud = pcl_sparse_test::resampleModel (model, 4 * mesh->vertices.size ());
    const CloudQuality q = evaluateCloudQuality (*mesh, cloud);
    std::cout << "bunny-npm-1k rho " << rho << ": M " << s.num_patches << ", CR " << s.compression_ratio
              << ", RMSE/diag " << s.rmse_over_diagonal << ", within 3 spacings " << q.completeness << ", flipped "
              << q.flipped << std::endl;
    EXPECT_LE (s.compression_ratio, 1.0) << "rho " << rho;
    EXPECT_EQ (s.uncovered, 0u) << "rho " << rho;
    EXPECT_LT (s.rmse_over_diagonal, 6e-4) << "rho " << rho;  // the authors': 5.84e-4 at CR 1.35
    EXPECT_GE (q.completeness, 0.99) << "rho " << rho;         // p99 hole within 3 spacings
    EXPECT_LE (q.flipped, cloud.size () / 1000) << "rho " << rho;
    if (rho == 0.001)
    {
      // The candidates are coded in parallel (over 64 patches): the same model on one thread.
      const SparseSurfaceModel single = encode (mesh, options, 1);
      ASSERT_EQ (single.patches.size (), model->patches.size ());
      for (std::size_t p = 0; p < single.patches.size (); ++p)
        ASSERT_EQ (single.patches[p].coefficients, model->patches[p].coefficients) << p;
    }
  }
}
