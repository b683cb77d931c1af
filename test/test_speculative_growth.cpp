/// SpeculativeGrowth (src/patches/speculative_growth.h): the sampling loop's helper threads grow patches
/// ahead of it; every patch the loop gets must be the one its own grower would grow, whichever thread grew it.
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/patch_growth.h>
#include <pcl_sparse/patches/patch_options.h>

#include "../src/patches/speculative_growth.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// Runs a sampling-like loop over every vertex of \a mesh in a shuffled order with \a helpers: the loop
  /// invalidates the vertices of every third patch it takes (as the sampling loop does with kept patches),
  /// and compares each patch with a sequential growth. Returns the number of patches the helpers grew;
  /// \a seeds receives the seeds of the patches the loop took, in order, \a degenerate the number of them
  /// that were empty or had no positive radius.
  std::size_t
  runLoop (const TriangleMesh& mesh, int helpers, int& mismatches, std::size_t& grown, std::vector<int>& seeds,
           std::size_t& degenerate)
  {
    // One OpenMP thread: this test also runs under ThreadSanitizer, which cannot see libgomp's barriers.
    const MeshTopology topology = buildMeshTopology (mesh, 1);
    const PatchGrowthGeometry geometry = computePatchGrowthGeometry (mesh, topology, {}, 1);
    const PatchOptions options;
    std::vector<int> order (mesh.vertices.size ());
    std::iota (order.begin (), order.end (), 0);
    std::shuffle (order.begin (), order.end (), std::mt19937 (7));
    std::vector<std::uint8_t> never_grown (order.size (), 0);
    never_grown[order[3]] = 1;
    std::unique_ptr<std::atomic<std::uint8_t>[]> invalid (new std::atomic<std::uint8_t>[order.size ()] ());

    PatchGrower loop_grower (mesh, topology, geometry, options), reference (mesh, topology, geometry, options);
    SpeculativeGrowth speculative (mesh, topology, geometry, options, order, never_grown, invalid.get (), helpers);
    Patch patch, expected;
    for (std::size_t i = 0; i < order.size (); ++i)
    {
      const int v = order[i];
      if (never_grown[v] || invalid[v].load ())
        continue;
      const double radius = speculative.grow (i, loop_grower, patch);
      const double expected_radius = reference.grow (v, expected);
      if (radius != expected_radius || patch.seed != v || patch.vertices != expected.vertices ||
          patch.triangles != expected.triangles)
        ++mismatches;
      // An empty patch or a zero (or NaN) radius would make the comparison above pass on nothing.
      if (expected.vertices.empty () || expected.triangles.empty () || !(expected_radius > 0.0))
        ++degenerate;
      seeds.push_back (v);
      if (++grown % 3 == 0)
        for (int u : patch.vertices)
          invalid[u].store (1);
    }
    return speculative.numTaken ();
  }
} // namespace

TEST (SpeculativeGrowth, EveryPatchIsTheSequentialOne)
{
  const TriangleMesh mesh = makeTorus (160, 64);
  std::vector<int> sequential_seeds;  // the loop's patches without helpers
  for (int helpers : {0, 1, 3})
  {
    // Helpers take patches only when they are scheduled before the loop gets there: a few tries make
    // "they took some" certain on a loaded machine too; every try checks every patch.
    std::size_t taken = 0;
    for (int attempt = 0; attempt < 10 && (attempt == 0 || (helpers > 0 && taken == 0)); ++attempt)
    {
      int mismatches = 0;
      std::size_t grown = 0, degenerate = 0;
      std::vector<int> seeds;
      taken = runLoop (mesh, helpers, mismatches, grown, seeds, degenerate);
      EXPECT_EQ (mismatches, 0) << helpers << " helpers";
      EXPECT_EQ (degenerate, 0u) << helpers << " helpers";
      // Measured: 1874 of the 10240 vertices grown, the others invalidated by every third patch.
      EXPECT_GT (grown, 1250u);
      EXPECT_LT (grown, 2800u);
      EXPECT_LE (taken, grown);
      // The loop takes the same patches, in the same order, whoever grew them.
      if (helpers == 0 && attempt == 0)
        sequential_seeds = seeds;
      else
        EXPECT_TRUE (seeds == sequential_seeds) << helpers << " helpers: " << seeds.size () << " patches, "
                                                << sequential_seeds.size () << " without helpers";
    }
    if (helpers == 0)
      EXPECT_EQ (taken, 0u);
    else
      EXPECT_GT (taken, 0u) << helpers << " helpers took no patch in 10 runs";
  }
}
