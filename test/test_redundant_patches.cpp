// Redundant patches (patches/redundant_patches.h, issue 13): a patch whose every vertex and triangle other
// patches hold is dropped, and nothing any patch held is left uncovered.

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/element_holders.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/patches/redundant_patches.h>

#include "analytic_surfaces.h"
#include "model_helpers.h"
#include "patch_helpers.h"
#include "shared_data.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;
using pcl_sparse_test::paraboloid;
using pcl_sparse_test::makePatch;

namespace
{
  /// Two triangles apart: (0, 1, 2) and (3, 4, 5).
  TriangleMesh
  twoTriangles ()
  {
    TriangleMesh mesh;
    for (int i = 0; i < 6; ++i)
      mesh.vertices.emplace_back (i, i % 2, 0.0);
    mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    return mesh;
  }

  PatchSamplingResult
  samplePatches (const TriangleMesh& mesh, bool drop_redundant)
  {
    PatchOptions options;
    options.drop_redundant_patches = drop_redundant;
    options.merge_own_elements = 0;  // dropping alone (merging: test_patch_merging.cpp)
    return sampleFeatureAwarePatches (mesh, buildMeshTopology (mesh), options, {}, {}, 1, nullptr);
  }
} // namespace

TEST (RedundantPatches, LaterPatchDroppedFirstUnlessBesideAnUncoveredFace)
{
  const TriangleMesh mesh = twoTriangles ();
  // The second patch holds only what the first holds: dropped (the pass goes from the last patch).
  std::vector<Patch> patches = {makePatch ({0, 1, 2, 3, 4, 5}, {0, 1}), makePatch ({0, 1, 2}, {0})};
  EXPECT_EQ (redundantPatches (mesh, patches), (std::vector<bool>{false, true}));
  // Both the same: the later one goes, the earlier one keeps them.
  patches = {makePatch ({0, 1, 2}, {0}), makePatch ({0, 1, 2}, {0})};
  EXPECT_EQ (redundantPatches (mesh, patches), (std::vector<bool>{false, true}));
  // A patch beside a face no patch holds is kept (its unclipped footprint covers that face): the other goes.
  patches[1].beside_uncovered_face = true;
  EXPECT_EQ (redundantPatches (mesh, patches), (std::vector<bool>{true, false}));
  // A vertex or a triangle of its own keeps a patch.
  patches = {makePatch ({0, 1, 2, 3, 4, 5}, {0}), makePatch ({3, 4, 5}, {1})};
  EXPECT_EQ (redundantPatches (mesh, patches), (std::vector<bool>{false, false}));
  EXPECT_EQ (redundantPatches (mesh, {}), std::vector<bool> ());
}

TEST (RedundantPatches, HoldersCountedAndReleased)
{
  const TriangleMesh mesh = twoTriangles ();
  const std::vector<Patch> patches = {makePatch ({0, 1, 2}, {0}), makePatch ({0, 1, 2, 3, 4, 5}, {0, 1})};
  ElementHolders holders = countElementHolders (mesh, patches);
  EXPECT_EQ (holders.vertices, (std::vector<int>{2, 2, 2, 1, 1, 1}));
  EXPECT_EQ (holders.faces, (std::vector<int>{2, 1}));
  holders.release (patches[1]);
  EXPECT_EQ (holders.vertices, (std::vector<int>{1, 1, 1, 0, 0, 0}));
  EXPECT_EQ (holders.faces, (std::vector<int>{1, 0}));
  // In a tile whose core is the first triangle, the second's vertices and face count as held elsewhere.
  const ElementHolders core = countElementHolders (mesh, patches, {1, 1, 1, 0, 0, 0});
  EXPECT_EQ (core.vertices[0], 2);
  EXPECT_GT (core.vertices[3], 1000000);
  EXPECT_EQ (core.faces[0], 2);
  EXPECT_GT (core.faces[1], 1000000);
}

TEST (RedundantPatches, TileMarginIsTheNeighboursToCover)
{
  const TriangleMesh mesh = twoTriangles ();
  // The last patch holds, alone, the second triangle: kept, and the first patch is redundant.
  const std::vector<Patch> patches = {makePatch ({0, 1, 2}, {0}), makePatch ({0, 1, 2, 3, 4, 5}, {0, 1})};
  EXPECT_EQ (redundantPatches (mesh, patches), (std::vector<bool>{true, false}));
  // In a tile whose core is the first triangle, the second lies in the margin, another tile's to cover:
  // the last patch holds nothing of the core alone and goes; the first is then the core's only holder.
  const std::vector<std::uint8_t> core = {1, 1, 1, 0, 0, 0};
  EXPECT_EQ (redundantPatches (mesh, patches, core), (std::vector<bool>{false, true}));
  // A triangle with one corner in the core is the tile's too.
  const std::vector<std::uint8_t> one_corner = {1, 1, 1, 1, 0, 0};
  EXPECT_EQ (redundantPatches (mesh, patches, one_corner), (std::vector<bool>{true, false}));
}

TEST (RedundantPatches, ParaboloidKeepsEveryVertexAndFaceCovered)
{
  const TriangleMesh bowl = makeHeightFieldGrid (60, 60, 1.0, 1.0, paraboloid);
  const PatchSamplingResult all = samplePatches (bowl, false), kept = samplePatches (bowl, true);
  std::cout << "paraboloid: " << all.patches.size () << " patches, " << kept.patches.size () << " kept" << std::endl;
  EXPECT_EQ (all.num_redundant, 0u);
  EXPECT_EQ (kept.num_redundant, all.patches.size () - kept.patches.size ());
  // Measured: 80 -> 37.
  EXPECT_LT (kept.patches.size (), 0.6 * all.patches.size ());
  const ElementHolders all_holders = countElementHolders (bowl, all.patches);
  const ElementHolders kept_holders = countElementHolders (bowl, kept.patches);
  const std::vector<int>& vertices_all = all_holders.vertices;
  const std::vector<int>& faces_all = all_holders.faces;
  const std::vector<int>& vertices_kept = kept_holders.vertices;
  const std::vector<int>& faces_kept = kept_holders.faces;
  for (std::size_t v = 0; v < bowl.vertices.size (); ++v)
    ASSERT_EQ (vertices_kept[v] > 0, vertices_all[v] > 0) << "vertex " << v;
  for (std::size_t f = 0; f < bowl.triangles.size (); ++f)
    ASSERT_EQ (faces_kept[f] > 0, faces_all[f] > 0) << "face " << f;
  // Every patch kept holds a vertex or a triangle no other kept patch holds, and the kept ones are the
  // sampling's, in its order.
  for (const Patch& patch : kept.patches)
  {
    bool own = false;
    for (int v : patch.vertices)
      own = own || vertices_kept[v] == 1;
    for (int f : patch.triangles)
      own = own || faces_kept[f] == 1;
    EXPECT_TRUE (own) << "patch seeded at " << patch.seed;
  }
  std::size_t next = 0;
  for (const Patch& patch : kept.patches)
  {
    while (next < all.patches.size () && all.patches[next].seed != patch.seed)
      ++next;
    ASSERT_LT (next, all.patches.size ()) << "patch seeded at " << patch.seed << " out of order";
    EXPECT_EQ (all.patches[next].vertices, patch.vertices);
    ++next;
  }
  EXPECT_EQ (kept.frame_kinds.size (), kept.patches.size ());
}

TEST (RedundantPatches, ParaboloidCodedWithHalfTheAtoms)
{
  // The default basis on the paraboloid, no patch merged: fewer than half the patches and atoms, the error 17 % higher
  // (4.49e-5 -> 5.27e-5 of the diagonal).
  const auto bowl = std::make_shared<TriangleMesh> (makeHeightFieldGrid (60, 60, 1.0, 1.0, paraboloid));
  SparseSurfaceEncoderOptions every_patch, dropped;
  every_patch.patches.drop_redundant_patches = false;
  every_patch.patches.merge_own_elements = dropped.patches.merge_own_elements = 0;  // dropping alone
  const ModelStatistics all = pcl_sparse_test::encodeMesh (bowl, every_patch)->statistics (bowl->vertices);
  const ModelStatistics kept = pcl_sparse_test::encodeMesh (bowl, dropped)->statistics (bowl->vertices);
  std::cout << "paraboloid: " << all.num_patches << " patches, " << all.num_nonzeros << " atoms, RMSE / diag "
            << all.rmse_over_diagonal << "; redundant ones dropped: " << kept.num_patches << ", " << kept.num_nonzeros
            << ", " << kept.rmse_over_diagonal << std::endl;
  EXPECT_EQ (kept.uncovered, 0u);
  EXPECT_LT (kept.num_nonzeros, 0.5 * all.num_nonzeros);
  EXPECT_LT (kept.rmse_over_diagonal, 1.25 * all.rmse_over_diagonal);
  EXPECT_LT (kept.rmse_over_diagonal, 1e-4);
}

TEST (RedundantPatches, SpotFileAFifthSmaller)
{
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/spot.obj";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
  SparseSurfaceEncoderOptions every_patch, dropped;
  every_patch.patches.drop_redundant_patches = false;
  every_patch.patches.merge_own_elements = dropped.patches.merge_own_elements = 0;  // dropping alone
  const SparseSurfaceModel::Ptr all = pcl_sparse_test::encodeMesh (mesh, every_patch);
  const SparseSurfaceModel::Ptr kept = pcl_sparse_test::encodeMesh (mesh, dropped);
  // Each at its own default file options, as pcl_sparse_encode -o writes it.
  ModelStatistics all_stats, kept_stats;
  const std::size_t all_bytes = pcl_sparse_test::defaultFileBytes (*all, mesh->vertices, &all_stats).size ();
  const std::size_t kept_bytes = pcl_sparse_test::defaultFileBytes (*kept, mesh->vertices, &kept_stats).size ();
  std::cout << "spot: " << all_stats.num_patches << " patches, RMSE / diag " << all_stats.rmse_over_diagonal << ", "
            << all_bytes << " bytes; redundant ones dropped: " << kept_stats.num_patches << ", "
            << kept_stats.rmse_over_diagonal << ", " << kept_bytes << " bytes" << std::endl;
  // Measured: 1426 -> 1042 patches (the compression bound trimmed atoms from all 1426: CR 1.00 -> 0.75),
  // 42354 -> 33257 bytes, RMSE / diag 6.30e-5 -> 6.76e-5.
  EXPECT_EQ (kept_stats.uncovered, 0u);
  EXPECT_LT (kept_stats.num_patches, 0.8 * all_stats.num_patches);
  EXPECT_LT (kept_stats.compression_ratio, 0.8);
  EXPECT_LT (static_cast<double> (kept_bytes), 0.82 * all_bytes);
  EXPECT_LT (kept_stats.rmse_over_diagonal, 1.12 * all_stats.rmse_over_diagonal);
}
