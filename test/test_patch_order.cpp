/// The Morton order (geometry/morton_order.h), the seeds coded as steps along it (format/seed_coding.h) and
/// the encoder's patches in the order that codes smaller (format/coding_order.h).

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/coding_order.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/seed_coding.h>
#include <pcl_sparse/geometry/morton_order.h>
#include <pcl_sparse/io/mesh_io.h>

#include "model_helpers.h"
#include "shared_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <random>

using namespace pcl_sparse;

TEST (MortonOrder, CubeCornersFollowTheZCurve)
{
  // Corner k of the unit cube has x = bit 0, y = bit 1, z = bit 2 of k: its Morton code is k.
  std::vector<Eigen::Vector3d> points;
  const int shuffled[] = {5, 2, 7, 0, 3, 6, 1, 4};
  for (int k : shuffled)
    points.emplace_back (k & 1, (k >> 1) & 1, (k >> 2) & 1);
  const std::vector<int> order = mortonOrder (points);
  ASSERT_EQ (order.size (), 8u);
  for (int k = 0; k < 8; ++k)
    EXPECT_EQ (shuffled[order[k]], k);
}

TEST (MortonOrder, NonFinitePointsComeFirstAndRepeatedIndicesOnce)
{
  const double nan = std::numeric_limits<double>::quiet_NaN ();
  const std::vector<Eigen::Vector3d> points{{1, 1, 1}, {nan, 0, 0}, {0, 0, 0}, {1, 0, 0}};
  // NaN takes code 0, as the smallest corner does: ties by index.
  EXPECT_EQ (mortonOrder (points), (std::vector<int>{1, 2, 3, 0}));
  EXPECT_EQ (mortonOrder (points, {3, 0, 3, 2}), (std::vector<int>{2, 3, 0}));
  // One point, or all at one place: no extent, the order is by index.
  EXPECT_EQ (mortonOrder ({{2, 2, 2}, {2, 2, 2}}), (std::vector<int>{0, 1}));
}

namespace
{
  std::vector<std::uint8_t>
  codeSeeds (const std::vector<std::array<std::uint64_t, 3>>& steps)
  {
    RangeEncoder out;
    SeedStepCoder coder;
    for (const auto& s : steps)
      coder.put (out, s);
    return out.finish ();
  }
} // namespace

TEST (SeedStepCoder, RoundTripsStepsOfAnySize)
{
  const std::uint64_t limit = std::uint64_t{1} << 32;
  std::vector<std::array<std::uint64_t, 3>> steps{{0, 0, 0}, {limit - 1, 0, 17}, {0, limit - 1, 17}, {5, 5, limit - 1}};
  std::mt19937_64 random (3);
  for (int i = 0; i < 500; ++i)
    steps.push_back ({random () % limit, random () % 1000, random () % 7});
  const std::vector<std::uint8_t> bytes = codeSeeds (steps);
  RangeDecoder in (bytes.data (), bytes.size (), "SEED");
  SeedStepCoder coder;
  for (const auto& s : steps)
    EXPECT_EQ (coder.get (in, limit), s);
  in.expectEnd ();
}

TEST (SeedStepCoder, RefusesStepsOutsideTheLimit)
{
  const std::vector<std::uint8_t> bytes = codeSeeds ({{10, 300, 20}, {10, 200, 20}});
  RangeDecoder in (bytes.data (), bytes.size (), "model x.psm: section SEED");
  SeedStepCoder coder;
  try
  {
    coder.get (in, 256);  // y = 300 needs two seed bytes
    ADD_FAILURE () << "a step of 300 passed a limit of 256";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ (e.what (), "model x.psm: section SEED: a seed step outside 0..255");
  }
}

TEST (SeedStepCoder, SeedsAlongTheMortonCurveCodeInAFifthFewerBytes)
{
  // 1600 seeds on a gently curved sheet, as a model's seeds lie on its surface, in steps of a 16-bit grid.
  std::vector<Eigen::Vector3d> seeds;
  std::mt19937_64 random (7);
  std::uniform_real_distribution<double> jitter (-0.3, 0.3);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
    {
      const double x = (i + jitter (random)) / 40.0, y = (j + jitter (random)) / 40.0;
      seeds.emplace_back (x, y, 0.2 * x * x + 0.1 * y);
    }
  std::shuffle (seeds.begin (), seeds.end (), random);
  auto stepsInOrder = [&] (const std::vector<int>& order) {
    std::vector<std::array<std::uint64_t, 3>> steps;
    for (int p : order)
      steps.push_back ({static_cast<std::uint64_t> (std::lround (seeds[p].x () * 65535)),
                        static_cast<std::uint64_t> (std::lround (seeds[p].y () * 65535)),
                        static_cast<std::uint64_t> (std::lround (seeds[p].z () * 65535))});
    return steps;
  };
  std::vector<int> as_given (seeds.size ());
  std::iota (as_given.begin (), as_given.end (), 0);
  const double shuffled_bits = 8.0 * codeSeeds (stepsInOrder (as_given)).size () / seeds.size ();
  const double morton_bits = 8.0 * codeSeeds (stepsInOrder (mortonOrder (seeds))).size () / seeds.size ();
  std::printf ("bits a seed: shuffled %.1f, Morton order %.1f\n", shuffled_bits, morton_bits);
  // Shuffled: about 3 x 16 bits; along the curve, about 3 x log2 (65535 / 40) plus sign and exponent bits.
  EXPECT_GT (shuffled_bits, 40.0);
  EXPECT_LT (morton_bits, 0.8 * shuffled_bits);
}

TEST (SparseSurfaceEncoder, PatchesFollowTheMortonOrderOfTheirSeedsThoseWithAtomsFirst)
{
  // stanford-bunny with its 1113 unreferenced vertices covered, even next to its faces: their one-vertex
  // patches, 45 % of its patches, have no atom.
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/stanford-bunny.obj";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  SparseSurfaceEncoderOptions options;
  options.patches.cover_unreferenced_vertices = 1;
  options.patches.unreferenced_patch_spacings = 0.0;
  const auto model = pcl_sparse_test::encodeMesh (std::make_shared<TriangleMesh> (loadTriangleMesh (path)), options);
  const std::size_t m = model->patches.size ();
  ASSERT_GT (m, 1000u);
  const auto first_empty = std::find_if (model->patches.begin (), model->patches.end (),
                                         [] (const PatchCode& patch) { return patch.atoms.empty (); });
  const std::size_t with_atoms = static_cast<std::size_t> (first_empty - model->patches.begin ());
  EXPECT_GT (with_atoms, 0u);
  EXPECT_LT (with_atoms, m * 3 / 4) << "the one-vertex patches should have no atom";
  EXPECT_TRUE (std::all_of (first_empty, model->patches.end (), [] (const PatchCode& patch) { return patch.atoms.empty (); }));
  // Each group in the order the Morton curve over all seeds gives it.
  std::vector<Eigen::Vector3d> seeds;
  for (const PatchCode& patch : model->patches)
    seeds.push_back (patch.origin);
  std::vector<int> expected = mortonOrder (seeds);
  std::stable_partition (expected.begin (), expected.end (), [&] (int p) { return static_cast<std::size_t> (p) < with_atoms; });
  std::vector<int> identity (m);
  std::iota (identity.begin (), identity.end (), 0);
  EXPECT_EQ (expected, identity);

  // And the file is smaller than the same patches' in a shuffled order.
  ModelWriteOptions write;
  write.tolerance = 1e-4;
  SparseSurfaceModel shuffled = *model;
  std::mt19937 random (1);
  std::shuffle (shuffled.patches.begin (), shuffled.patches.end (), random);
  const std::size_t ordered_bytes = encodeModel (*model, write).size ();
  const std::size_t shuffled_bytes = encodeModel (shuffled, write).size ();
  std::printf ("%zu patches (%zu with atoms): %zu bytes, shuffled %zu\n", m, with_atoms, ordered_bytes, shuffled_bytes);
  EXPECT_LT (ordered_bytes, shuffled_bytes);
}

TEST (SparseSurfaceEncoder, KeepsTheSamplingOrderWhereItCodesSmaller)
{
  // blade: patches of like curvature follow one another in the sampling order (decreasing Harris response),
  // which its file codes 8 % smaller than the Morton order.
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/blade.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  const auto model = pcl_sparse_test::encodeMesh (std::make_shared<TriangleMesh> (loadTriangleMesh (path)));
  const std::vector<int> morton = seedMortonOrder (*model);
  std::vector<int> identity (model->patches.size ());
  std::iota (identity.begin (), identity.end (), 0);
  EXPECT_NE (morton, identity);
  EXPECT_EQ (smallerCodingOrder (*model), identity);
  ModelWriteOptions write;
  write.tolerance = 1e-4;
  SparseSurfaceModel reordered = *model;
  for (std::size_t k = 0; k < morton.size (); ++k)
    reordered.patches[k] = model->patches[morton[k]];
  const std::size_t own_bytes = encodeModel (*model, write).size ();
  const std::size_t morton_bytes = encodeModel (reordered, write).size ();
  std::printf ("blade: %zu bytes in the sampling order, %zu in the Morton order\n", own_bytes, morton_bytes);
  EXPECT_LT (1.05 * own_bytes, morton_bytes);
  // And a model in no useful order (shuffled) gets the Morton one.
  SparseSurfaceModel shuffled = *model;
  std::mt19937 random (2);
  std::shuffle (shuffled.patches.begin (), shuffled.patches.end (), random);
  EXPECT_EQ (smallerCodingOrder (shuffled), seedMortonOrder (shuffled));
  // Models over max_trial_patches take the Morton order untried (the trial writes cost time that grows
  // with the model; the sampling order won only on small CAD meshes).
  EXPECT_EQ (smallerCodingOrder (*model, 0, model->patches.size () - 1), morton);
}
