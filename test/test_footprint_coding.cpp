/// Quantised footprints (format/footprint_coding.h): coarse angles where they draw the footprint, the others
/// only where a clipped border needs them, both layouts alike, damaged symbols refused; and files written
/// before the adaptive footprints (every stride-th angle of a patch) still read as they did.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/footprint_coding.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/format/range_coder.h>
#include <pcl_sparse/resampling/footprint_slack.h>

#include "test_format_models.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

using namespace pcl_sparse;

namespace
{
  constexpr int kAngles = 64;
  const FootprintLevels kLevels{1.0 / 15.0, 4};  // 4-bit levels of extents up to 1

  PatchFootprint
  roundFootprint (float extent)
  {
    PatchFootprint footprint;
    footprint.extent.assign (kAngles, extent);
    return footprint;
  }

  /// A round footprint of radius 0.9 cut by the line at distance \a d from the centre, facing angle 0
  /// (polar: r = d / cos(theta) where that is shorter): a patch at a crease or an open border.
  PatchFootprint
  clippedFootprint (double d)
  {
    PatchFootprint footprint;
    for (int k = 0; k < kAngles; ++k)
    {
      const double c = std::cos (2.0 * M_PI * k / kAngles);
      footprint.extent.push_back (static_cast<float> (c > d / 0.9 ? d / c : 0.9));
    }
    return footprint;
  }

  PatchFootprint
  throughBytes (const PatchFootprint& footprint, const FootprintRefinement& refinement, std::size_t* bytes = nullptr,
                const FootprintSlack* slack = nullptr)
  {
    ByteWriter out;
    putFootprint (out, footprint, kLevels, refinement, slack);
    if (bytes)
      *bytes = out.size ();
    ByteReader in (out.bytes ().data (), out.size (), "FOOT");
    PatchFootprint decoded;
    getFootprint (in, kLevels, 0, decoded);
    EXPECT_TRUE (in.atEnd ());
    return decoded;
  }

  PatchFootprint
  throughRangeCoder (const PatchFootprint& footprint, const FootprintRefinement& refinement,
                     const FootprintSlack* slack = nullptr)
  {
    RangeEncoder out;
    FootprintContexts write_contexts (kLevels.bits);
    putFootprint (out, write_contexts, footprint, kLevels, refinement, slack);
    const std::vector<std::uint8_t> bytes = out.finish ();
    RangeDecoder in (bytes.data (), bytes.size (), "FOOT");
    FootprintContexts read_contexts (kLevels.bits);
    PatchFootprint decoded;
    getFootprint (in, read_contexts, kLevels, 0, decoded);
    in.expectEnd ();
    return decoded;
  }

  using test::largestFootprintDeviation;
} // namespace

TEST (FootprintCoding, RoundFootprintKeepsItsCoarseAngles)
{
  const PatchFootprint round = roundFootprint (0.83f);
  std::size_t bytes = 0;
  const PatchFootprint decoded = throughBytes (round, FootprintRefinement{}, &bytes);
  ASSERT_EQ (decoded.extent.size (), 2u);  // the default: 2 opposite angles
  for (float e : decoded.extent)
    EXPECT_FLOAT_EQ (e, static_cast<float> (12 * kLevels.step));  // 0.83 * 15 = 12.45: level 12
  EXPECT_EQ (bytes, 1u + 1u + 2u + 2u);  // angles, stride, 2 levels, 2 "not split"
  const PatchFootprint eight = throughBytes (round, FootprintRefinement{8, 2.0}, &bytes);
  ASSERT_EQ (eight.extent.size (), 8u);
  EXPECT_EQ (bytes, 1u + 1u + 8u + 8u);
}

TEST (FootprintCoding, ClippedBorderKeepsItsAnglesThereOnly)
{
  const PatchFootprint clipped = clippedFootprint (0.35);
  for (double steps : {2.0, 1.0, 0.5})
  {
    const FootprintRefinement refinement{8, steps};
    std::size_t bytes = 0;
    const PatchFootprint decoded = throughBytes (clipped, refinement, &bytes);
    ASSERT_EQ (decoded.extent.size (), static_cast<std::size_t> (kAngles));
    // Within the bound plus the rounding of the interval's ends.
    EXPECT_LE (largestFootprintDeviation (clipped, decoded), (steps + 0.5) * kLevels.step + 1e-6) << steps;
    // The uncut part (about 60 % of the angles) is drawn from its coarse angles: at most two thirds of the
    // bytes of a level for every angle (66; 30-42 here; splitting every interval would take 130).
    EXPECT_LE (bytes, 44u) << steps;
    const PatchFootprint ranged = throughRangeCoder (clipped, refinement);
    EXPECT_EQ (ranged.extent, decoded.extent) << "the two layouts code the same footprint";
  }
  // Coarse angles alone stray far from the cut (what the refinement is for).
  const PatchFootprint coarse = throughBytes (clipped, FootprintRefinement{8, 0.0});
  ASSERT_EQ (coarse.extent.size (), 8u);
  EXPECT_GT (largestFootprintDeviation (clipped, coarse), 3.0 * kLevels.step);
}

// A clipped footprint's cut as a knife edge (FootprintSlack::knife_edge): there no angle is drawn more than
// a level inside its extent (resampling clears the other side's places a level past the border drawn,
// SparseSurfaceModel::footprint_step), in both layouts, where the refinement alone draws some further in;
// the round part is drawn as without the flags.
TEST (FootprintCoding, KnifeEdgeAnglesAreDrawnWithinALevel)
{
  // A cut with a tooth three levels high at angle 2: the line between coded angles passes under the tooth.
  PatchFootprint clipped = clippedFootprint (0.35);
  clipped.extent[2] += static_cast<float> (3.0 * kLevels.step);
  FootprintSlack knife{clipped.extent, clipped.extent, std::vector<char> (kAngles, 0)};
  std::size_t knife_angles = 0;
  for (int k = 0; k < kAngles; ++k)
    if (clipped.extent[static_cast<std::size_t> (k)] < 0.9f)
    {
      knife.knife_edge[static_cast<std::size_t> (k)] = 1;
      ++knife_angles;
    }
  ASSERT_GT (knife_angles, 20u);
  auto decode = [&] (const FootprintRefinement& refinement, const FootprintSlack* slack, std::size_t& bytes) {
    const PatchFootprint decoded = throughBytes (clipped, refinement, &bytes, slack);
    EXPECT_EQ (throughRangeCoder (clipped, refinement, slack).extent, decoded.extent) << "the two layouts code the same footprint";
    return decoded;
  };
  // The furthest inside its extent a knife angle is drawn, in levels.
  auto deepestInside = [&] (const PatchFootprint& decoded) {
    EXPECT_EQ (decoded.extent.size (), static_cast<std::size_t> (kAngles));
    double deepest = 0.0;
    for (std::size_t k = 0; k < decoded.extent.size (); ++k)
      if (knife.knife_edge[k])
        deepest = std::max (deepest, (static_cast<double> (clipped.extent[k]) - decoded.extent[k]) / kLevels.step);
    return deepest;
  };
  for (double steps : {2.0, 4.0})
  {
    const FootprintRefinement refinement{2, steps};
    std::size_t bytes_plain = 0, bytes_knife = 0;
    const PatchFootprint plain = decode (refinement, nullptr, bytes_plain);
    const PatchFootprint bounded = decode (refinement, &knife, bytes_knife);
    std::cout << "  refinement " << steps << " steps: knife angles drawn up to " << deepestInside (plain)
              << " levels inside without the flags (" << bytes_plain << " bytes), " << deepestInside (bounded)
              << " with them (" << bytes_knife << " bytes)" << std::endl;
    EXPECT_LE (deepestInside (bounded), 1.0 + 1e-6) << steps;
    EXPECT_LE (bytes_knife, bytes_plain + 12) << steps;
    for (std::size_t k = 20; k < 44; ++k)  // the round part, away from the cut
      EXPECT_FLOAT_EQ (bounded.extent[k], plain.extent[k]) << k;
    if (steps == 4.0)
      EXPECT_GT (deepestInside (plain), 1.0) << "the refinement alone no longer draws a knife angle over a level in";
  }
}

// Trim cuts (PatchFootprint::trimmed): a round footprint drawn in at a few angles, each cut a fraction of a
// level or a few levels deep. Without the flags the file draws some cuts outside (rounded to the nearest level,
// or a shallow dent left to the line between coarse angles); with them no trimmed angle is drawn outside its
// extent, none more than a level inside, in both layouts, and the other angles as before.
TEST (FootprintCoding, TrimCutsAreNeverDrawnOutside)
{
  PatchFootprint cut = roundFootprint (static_cast<float> (12 * kLevels.step));
  cut.trimmed.assign (kAngles, 0);
  // angle: depth in levels (0.4: rounds back up to the uncut level; 0.7: a dent the line passes over; 1: a
  // cut on a level, but for the floats' rounding)
  const std::vector<std::pair<std::size_t, double>> cuts{{5, 0.4}, {20, 0.7}, {21, 0.7}, {40, 3.6}, {50, 1.0}};
  for (const auto& [angle, depth] : cuts)
  {
    cut.extent[angle] -= static_cast<float> (depth * kLevels.step);
    cut.trimmed[angle] = 1;
  }
  // The level-1 cut a float step under 11 levels, as extents computed in floats land.
  cut.extent[50] = std::nextafter (static_cast<float> (11 * kLevels.step), 0.0f);
  ASSERT_LT (cut.extent[50] / kLevels.step, 11.0);
  PatchFootprint unflagged = cut;
  unflagged.trimmed.clear ();
  auto drawnAt = [] (const PatchFootprint& decoded, std::size_t angle) {
    return decoded.extentAt (2.0 * M_PI * static_cast<double> (angle) / kAngles);
  };
  // The furthest outside its extent a trimmed angle is drawn, in levels (negative: inside).
  auto furthestOutside = [&] (const PatchFootprint& decoded) {
    double furthest = -1e9;
    for (const auto& [angle, depth] : cuts)
      furthest = std::max (furthest, (drawnAt (decoded, angle) - cut.extent[angle]) / kLevels.step);
    return furthest;
  };
  for (double steps : {2.0, 4.0})
  {
    const FootprintRefinement refinement{2, steps};
    std::size_t bytes_plain = 0, bytes_cut = 0;
    const PatchFootprint plain = throughBytes (unflagged, refinement, &bytes_plain);
    const PatchFootprint bounded = throughBytes (cut, refinement, &bytes_cut);
    EXPECT_EQ (throughRangeCoder (cut, refinement).extent, bounded.extent) << "the two layouts code the same footprint";
    std::cout << "  refinement " << steps << " steps: trimmed angles drawn up to " << furthestOutside (plain)
              << " levels outside without the flags (" << bytes_plain << " bytes), " << furthestOutside (bounded)
              << " with them (" << bytes_cut << " bytes)" << std::endl;
    EXPECT_GT (furthestOutside (plain), 0.3) << steps << ": the nearest level alone draws a cut outside";
    EXPECT_LE (furthestOutside (bounded), 1e-6) << steps;
    for (const auto& [angle, depth] : cuts)
      EXPECT_GE (drawnAt (bounded, angle), cut.extent[angle] - kLevels.step - 1e-6) << angle;
    EXPECT_NEAR (drawnAt (bounded, 50), cut.extent[50], 1e-6) << "a cut on a level keeps that level";
    // Each cut's angle is coded: a chain of splits down from the coarse stride (32 here), per depth a split
    // flag, a residual and the sibling's flag in the varint layout (the range coder's are smaller).
    EXPECT_LE (bytes_cut, bytes_plain + 10 * cuts.size ()) << steps;
    for (std::size_t k = 26; k < 36; ++k)  // away from every cut
      EXPECT_NEAR (drawnAt (bounded, k), drawnAt (plain, k), 1e-6) << k;
  }
}

TEST (FootprintCoding, EveryAngleKeptWithoutACoarseBound)
{
  const PatchFootprint clipped = clippedFootprint (0.5);
  const PatchFootprint decoded = throughRangeCoder (clipped, FootprintRefinement{0, 2.0});
  ASSERT_EQ (decoded.extent.size (), static_cast<std::size_t> (kAngles));
  EXPECT_LE (largestFootprintDeviation (clipped, decoded), 0.5 * kLevels.step + 1e-6);
}

TEST (FootprintCoding, DamagedSymbolsAreRefused)
{
  ByteWriter out;
  putFootprint (out, clippedFootprint (0.35), kLevels, FootprintRefinement{8, 2.0});
  const std::vector<std::uint8_t> good = out.bytes ();
  auto expectError = [] (std::vector<std::uint8_t> bytes, const std::string& text) {
    ByteReader in (bytes.data (), bytes.size (), "FOOT");
    PatchFootprint decoded;
    try
    {
      getFootprint (in, kLevels, 3, decoded);
      ADD_FAILURE () << "no error, expected one containing '" << text << "'";
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find (text), std::string::npos) << e.what ();
    }
  };
  auto bytes = good;
  bytes[1] = 7;  // stride 128 does not divide 64 angles
  expectError (bytes, "does not divide");
  bytes = good;
  bytes[2] = 16;  // a level of 5 bits
  expectError (bytes, "extent level out of range");
  bytes = good;
  bytes[10] = 2;  // the first interval's split is a bit
  expectError (bytes, "footprint split out of range");
  bytes = good;
  bytes.resize (bytes.size () - 1);
  expectError (bytes, "FOOT");
  bytes = {0x81, 0x40, 0};  // 8193 angles
  expectError (bytes, "footprint angles");
}

// Files written before the adaptive footprints (commit 24e4214, test/data/uniform_footprints_*.psm): the model
// below at tolerance 1e-3, range-coded and in the varint layout; every patch kept every stride-th of its 64
// angles (8 for the round ones, all 64 for the random ones). makeSyntheticModel's uniform reals are those of
// libstdc++, with which the files were written.
TEST (FootprintCoding, FilesOfUniformFootprintsReadAsBefore)
{
  SparseSurfaceModel model = test::makeSyntheticModel (24, 7, false, kAngles);
  for (std::size_t p = 0; p < model.patches.size (); p += 2)
    model.patches[p].footprint = roundFootprint (0.8f);
  float extent_max = 0.0f;
  for (const PatchCode& patch : model.patches)
    extent_max = std::max (extent_max, *std::max_element (patch.footprint.extent.begin (), patch.footprint.extent.end ()));
  const double step = extent_max / 15.0;
  ModelWriteOptions options;
  options.tolerance = 1e-3;
  const std::vector<std::uint8_t> bytes = encodeModel (model, options);
  const SparseSurfaceModel now = decodeModel (bytes.data (), bytes.size (), "now");
  for (const char* layout : {"range", "varint"})
  {
    const std::string path = std::string (PCL_SPARSE_SOURCE_DIR) + "/test/data/uniform_footprints_" + layout + ".psm";
    const SparseSurfaceModel old = loadModel (path);
    ASSERT_EQ (old.patches.size (), model.patches.size ()) << layout;
    for (std::size_t p = 0; p < model.patches.size (); ++p)
    {
      const PatchCode &a = old.patches[p], &b = now.patches[p];
      EXPECT_EQ (a.origin, b.origin) << layout << " patch " << p;  // only the footprints are coded otherwise
      EXPECT_EQ (a.frame, b.frame);
      EXPECT_EQ (a.radius, b.radius);
      EXPECT_EQ (a.atoms, b.atoms);
      EXPECT_EQ (a.coefficients, b.coefficients);
      const std::vector<float>& original = model.patches[p].footprint.extent;
      const std::size_t k = a.footprint.extent.size ();
      ASSERT_EQ (k, p % 2 == 0 ? 8u : 64u) << layout << " patch " << p;
      for (std::size_t i = 0; i < k; ++i)
        EXPECT_NEAR (a.footprint.extent[i], std::round (original[i * (kAngles / k)] / step) * step, 1e-6);
    }
  }
}

// A few bits of FOOT can stand for thousands of interpolated angles; a reader holds a run's footprints to 1 KiB
// of extents a byte of FOOT (over a 64k-angle allowance), and the writer refuses a model it would not read back.
TEST (FootprintCoding, FootprintsOfThousandsOfAnglesFromAFewAreRefused)
{
  SparseSurfaceModel model = test::makeSyntheticModel (40, 3, false, 8);
  for (PatchCode& patch : model.patches)
  {
    patch.footprint.extent.assign (4096, 0.8f);
    patch.footprint.extent[1] = 0.1f;  // one notch: the first interval splits down to it, the rest stay coarse
  }
  ModelWriteOptions options;
  options.tolerance = 1e-3;
  try
  {
    encodeModel (model, options);
    ADD_FAILURE () << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("more than a reader accepts"), std::string::npos) << e.what ();
  }
  // Fewer patches of it fit the allowance and read back: every one with its 4096 angles, the notch kept.
  model.patches.resize (8);
  const std::vector<std::uint8_t> bytes = encodeModel (model, options);
  const SparseSurfaceModel decoded = decodeModel (bytes.data (), bytes.size (), "notched");
  ASSERT_EQ (decoded.numPatches (), 8u);
  for (const PatchCode& patch : decoded.patches)
  {
    ASSERT_EQ (patch.footprint.extent.size (), 4096u);
    EXPECT_LT (patch.footprint.extent[1], 0.2f);
    EXPECT_GT (patch.footprint.extent[2048], 0.7f);
  }
}

// The reader holds a run to the same angle allowance on its own, for files no writer of ours would make: runs of
// equal patches whose FOOT section is replaced by one coding a notched 4096-angle footprint per patch (a few
// bytes each: the range coder's splits and levels of a footprint it has seen before cost next to nothing).
TEST (FootprintCoding, ReaderRefusesARunOfMoreAnglesThanItsBytesJustify)
{
  PatchFootprint notched;
  notched.extent.assign (4096, 0.8f);
  notched.extent[1] = 0.1f;
  auto decodeRun = [&] (std::size_t num_patches, std::size_t* foot_bytes) {
    SparseSurfaceModel model = test::makeSyntheticModel (1, 3, false, 8);
    model.patches[0].footprint.extent.assign (8, 0.8f);  // the same extent scale as the notched footprints
    model.patches.resize (num_patches, model.patches[0]);
    ModelWriteOptions options;
    options.tolerance = 1e-3;
    ModelSections sections = encodeModelSections (model, options, {{0, num_patches}});
    const std::vector<std::string> tags = runSectionTags (sections.shared.flags);
    const std::size_t foot = std::find (tags.begin (), tags.end (), "FOOT") - tags.begin ();
    RangeEncoder coder;
    FootprintContexts contexts (options.extent_bits);
    const FootprintLevels levels{0.8 / ((1 << options.extent_bits) - 1), options.extent_bits};
    for (std::size_t p = 0; p < num_patches; ++p)
      putFootprint (coder, contexts, notched, levels, FootprintRefinement{});
    sections.runs[0][foot] = coder.finish ();
    *foot_bytes = sections.runs[0][foot].size ();
    std::vector<std::pair<const std::uint8_t*, std::size_t>> views;
    for (const std::vector<std::uint8_t>& bytes : sections.runs[0])
      views.emplace_back (bytes.data (), bytes.size ());
    return decodeModelSections (sections.shared, num_patches, views, "notched");
  };
  // 16 patches, 65536 angles: within the allowance, and each reads back with its notch.
  std::size_t foot_bytes = 0;
  const SparseSurfaceModel sixteen = decodeRun (16, &foot_bytes);
  ASSERT_EQ (sixteen.patches.size (), 16u);
  for (const PatchCode& patch : sixteen.patches)
  {
    ASSERT_EQ (patch.footprint.extent.size (), 4096u);
    EXPECT_LT (patch.footprint.extent[1], 0.2f);
    EXPECT_GT (patch.footprint.extent[2048], 0.7f);
  }
  // 40 patches, 163840 angles from far fewer FOOT bytes than that justifies: refused, naming the limit.
  try
  {
    decodeRun (40, &foot_bytes);
    ADD_FAILURE () << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("more angles than its bytes justify"), std::string::npos) << e.what ();
  }
  EXPECT_LT (65536 + 256 * foot_bytes, 40u * 4096u) << foot_bytes << " FOOT bytes";
}
