// Hidden triangles (patches/hidden_triangles.h, issue 13: no flipped normal): a patch's triangles beyond a
// bay its seed sees no surface across leave it, so its star-shaped footprint does not span the bay.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/patches/hidden_triangles.h>
#include <pcl_sparse/patches/patch_growth.h>
#include <pcl_sparse/resampling/cloud_quality.h>

#include "model_helpers.h"
#include "shared_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// Which faces of the comb a case keeps and how.
  enum class Between
  {
    Nothing,     ///< the faces outside the patch are left out of the mesh: a bay with no surface
    FacingUp,    ///< they stay, on the patch's side: the seed sees the far triangles over them
    FacingDown,  ///< they stay, wound the other way (but at the seed): surface facing away, as across a thin part
  };

  /// A comb as blade's: [-1, 1]^2 in 20 x 2 cells, so every triangle is a tooth 0.1 wide reaching from the
  /// row y = 0 to y = -1 or 1, the faces outside the patch as \a between says; and the patch, seeded at the
  /// centre, holding the row's vertices and the teeth of the quadrant x > 0, y < 0 (at the seed) and of the
  /// block x < -0.6, y > 0 (no edge shared with the quadrant's); with \a bridge also the teeth 0 > x > -0.6,
  /// y > 0, which join the two by edges.
  std::pair<TriangleMesh, Patch>
  bayCase (Between between, bool bridge)
  {
    const TriangleMesh grid = makeHeightFieldGrid (20, 2, 1.0, 1.0, [] (double, double) { return 0.0; });
    TriangleMesh mesh;
    mesh.vertices = grid.vertices;
    Patch patch;
    for (std::size_t v = 0; v < grid.vertices.size (); ++v)
      if (grid.vertices[v].head<2> ().norm () < 1e-9)
        patch.seed = static_cast<int> (v);
    patch.origin = grid.vertices[patch.seed];
    for (const Eigen::Vector3i& t : grid.triangles)
    {
      const Eigen::Vector3d c = (grid.vertices[t[0]] + grid.vertices[t[1]] + grid.vertices[t[2]]) / 3.0;
      const bool in_patch = (c.x () > 0.0 && c.y () < 0.0) || (c.x () < -0.6 && c.y () > 0.0) ||
                            (bridge && c.x () < 0.0 && c.y () > 0.0);
      if (in_patch)
        patch.triangles.push_back (static_cast<int> (mesh.triangles.size ()));
      if (in_patch || between == Between::FacingUp)
        mesh.triangles.push_back (t);
      else if (between == Between::FacingDown)  // but at the seed, whose normal is the patch's
        mesh.triangles.push_back (t[0] == patch.seed || t[1] == patch.seed || t[2] == patch.seed
                                    ? t
                                    : Eigen::Vector3i (t[0], t[2], t[1]));
    }
    patch.vertices.push_back (patch.seed);
    auto add = [&] (int v) {
      if (std::find (patch.vertices.begin (), patch.vertices.end (), v) == patch.vertices.end ())
        patch.vertices.push_back (v);
    };
    for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
      if (std::abs (mesh.vertices[v].y ()) < 1e-9)
        add (static_cast<int> (v));
    for (int f : patch.triangles)
      for (int k = 0; k < 3; ++k)
        add (mesh.triangles[f][k]);
    return {mesh, patch};
  }

  std::vector<int>
  hiddenIn (const std::pair<TriangleMesh, Patch>& c, double min_gap)
  {
    const MeshTopology topology = buildMeshTopology (c.first);
    const PatchGrowthGeometry geometry = computePatchGrowthGeometry (c.first, topology);
    return hiddenPatchTriangles (c.first, topology, geometry, c.second, min_gap);
  }

  /// The patch's triangles in the block x < -0.6, y > 0.
  std::vector<int>
  farBlock (const std::pair<TriangleMesh, Patch>& c)
  {
    std::vector<int> faces;
    for (int f : c.second.triangles)
    {
      const Eigen::Vector3i& t = c.first.triangles[f];
      const Eigen::Vector3d centroid = (c.first.vertices[t[0]] + c.first.vertices[t[1]] + c.first.vertices[t[2]]) / 3.0;
      if (centroid.x () < -0.6 && centroid.y () > 0.0)
        faces.push_back (f);
    }
    return faces;
  }
} // namespace

TEST (HiddenTriangles, TrianglesBeyondABayWithoutSurfaceAreHidden)
{
  // The block's centroids lie 0.72-1.2 from the seed (R = 1.41); the segments to them run 0.68-0.9
  // outside every face of the patch's side before they reach the block: more than 0.3 R = 0.42, less than R.
  const auto bay = bayCase (Between::Nothing, false);
  const std::vector<int> block = farBlock (bay);
  ASSERT_EQ (block.size (), 8u);
  EXPECT_EQ (hiddenIn (bay, 0.3), block);
  const auto away = bayCase (Between::FacingDown, false);
  EXPECT_EQ (hiddenIn (away, 0.3), farBlock (away)) << "surface facing away is no surface of the patch's side";
  EXPECT_TRUE (hiddenIn (bay, 1.0).empty ());
}

TEST (HiddenTriangles, SurfaceBetweenOrAnEdgePathKeepsThemSeen)
{
  // The seed sees the block over the faces of its own side that are not the patch's.
  EXPECT_TRUE (hiddenIn (bayCase (Between::FacingUp, false), 0.3).empty ());
  // Joined to the seed's triangles by edges, the block is part of the patch as grown: never tested.
  EXPECT_TRUE (hiddenIn (bayCase (Between::Nothing, true), 0.3).empty ());
  EXPECT_TRUE (hiddenIn (bayCase (Between::FacingDown, true), 0.3).empty ());
}

TEST (HiddenTriangles, RemovingTrianglesDropsTheCornersOnlyTheyHeld)
{
  auto [mesh, patch] = bayCase (Between::Nothing, false);
  patch.completed_triangles = 4;  // the last four came from face completion
  const std::vector<int> block = farBlock ({mesh, patch});
  const std::size_t triangles = patch.triangles.size (), vertices = patch.vertices.size ();
  removePatchTriangles (mesh, block, patch);
  EXPECT_EQ (patch.triangles.size (), triangles - block.size ());
  EXPECT_EQ (patch.completed_triangles, 0u) << "the last four were the block's";
  // The block's corners: x = -1, -0.9, ..., -0.6 at y = 0 and y = 1; the others keep the row at y = 0.
  EXPECT_EQ (patch.vertices.size (), vertices - 10u);
  EXPECT_EQ (patch.vertices.front (), patch.seed);
  for (int f : patch.triangles)
    for (int k = 0; k < 3; ++k)
      EXPECT_NE (std::find (patch.vertices.begin (), patch.vertices.end (), mesh.triangles[f][k]), patch.vertices.end ());
  for (int v : patch.vertices)
    EXPECT_FALSE (mesh.vertices[v].x () < -0.55) << "corner " << v << " of the block stayed";
}

TEST (HiddenTriangles, BladeBayLeavesItsPatch)
{
  // blade.off's patch 298 (seeded at vertex 631) is a comb of long thin triangles whose far arm lies
  // across a bay with no surface of its side; its footprint spanned the bay, where the code ran 1.7 spacings
  // off the mesh with 5 flipped normals at 4 V points (bench/results/flips.md). Released, those triangles
  // grow patches of their own: no flipped point, and a smaller mean distance (2.44e-5 -> 2.38e-5 of the
  // diagonal in bench_flips; 13 hidden faces in 2 patches -> 1, given back to its patch). Both encodings keep
  // the footprints as coded: drawn in at flipped places (trim_flipped_places), the kept bay flips no point
  // either (and lies 2.28e-5 off), which would hide what the release does.
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/blade.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const TriangleMesh::ConstPtr mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
  const MeshTopology topology = buildMeshTopology (*mesh);
  const PatchGrowthGeometry geometry = computePatchGrowthGeometry (*mesh, topology);
  std::size_t flipped[2] = {0, 0}, hidden[2] = {0, 0};
  double mean_distance[2] = {0.0, 0.0};
  for (int released = 0; released < 2; ++released)
  {
    SparseSurfaceEncoderOptions options;
    options.trim_flipped_places = false;
    if (!released)
      options.patches.hidden_triangle_gap = 0.0;
    const PatchSamplingResult sampling = sampleFeatureAwarePatches (*mesh, topology, options.patches, {}, {}, 2, nullptr);
    for (const Patch& p : sampling.patches)
      hidden[released] += hiddenPatchTriangles (*mesh, topology, geometry, p, 0.3).size ();
    if (released)  // the release looks at the patches in parallel: the same partition with one thread
    {
      const PatchSamplingResult one = sampleFeatureAwarePatches (*mesh, topology, options.patches, {}, {}, 1, nullptr);
      ASSERT_EQ (one.patches.size (), sampling.patches.size ());
      for (std::size_t p = 0; p < one.patches.size (); ++p)
      {
        EXPECT_EQ (one.patches[p].triangles, sampling.patches[p].triangles) << "patch " << p;
        EXPECT_EQ (one.patches[p].vertices, sampling.patches[p].vertices) << "patch " << p;
      }
    }
    const pcl::PointCloud<pcl::PointNormal> cloud =
      pcl_sparse_test::resampleModel (pcl_sparse_test::encodeMesh (mesh, options), 4 * mesh->numVertices ());
    const CloudQuality q = evaluateCloudQuality (*mesh, cloud, CloudQualityOptions ());
    flipped[released] = q.flipped;
    mean_distance[released] = q.mean_distance / q.bbox_diagonal;
    std::cout << "blade.off, hidden triangles " << (released ? "released" : "kept") << ": " << hidden[released]
              << " hidden, " << q.flipped << " flipped of " << cloud.size () << ", mean distance / diag "
              << mean_distance[released] << std::endl;
  }
  EXPECT_GE (hidden[0], 7u) << "the bay is gone from the mesh's patches: the test no longer tests the release";
  EXPECT_LT (hidden[1], hidden[0]) << "a face no new patch takes goes back to its patch";
  EXPECT_GE (flipped[0], 3u);
  EXPECT_EQ (flipped[1], 0u);
  EXPECT_LT (mean_distance[1], 0.99 * mean_distance[0]);
}

TEST (HiddenTriangles, OptionPresetsAndRange)
{
  EXPECT_EQ (PatchOptions ().hidden_triangle_gap, -1.0);
  EXPECT_EQ (patchOptionsFor (PatchOptions (), false).hidden_triangle_gap, 0.3) << "on a mesh";
  EXPECT_EQ (patchOptionsFor (PatchOptions (), true).hidden_triangle_gap, 0.0) << "on a scan";
  PatchOptions given;
  given.hidden_triangle_gap = 0.5;
  EXPECT_EQ (patchOptionsFor (given, true).hidden_triangle_gap, 0.5) << "a value given holds on scans too";
  EXPECT_EQ (encoderPresetOptions (EncoderPreset::Paper).patches.hidden_triangle_gap, 0.0);
  EXPECT_EQ (authorsCodePatchOptions ().hidden_triangle_gap, 0.0);
  for (double bad : {-0.1, -2.0, std::nan (""), std::numeric_limits<double>::infinity ()})
  {
    PatchOptions wrong;
    wrong.hidden_triangle_gap = bad;
    try
    {
      wrong.validate ();
      ADD_FAILURE () << bad << " was taken";
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find ("hidden_triangle_gap"), std::string::npos) << e.what ();
    }
  }
}
