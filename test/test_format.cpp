/// Round trips and bad files for the .psm model file format (src/format).

#include "test_file_helpers.h"
#include "test_format_models.h"

#include <pcl_sparse/coding/dct_cosine_dictionary.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/memory_limit.h>
#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/crc32.h>
#include <pcl_sparse/format/frame_quantization.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/format/tiled_model_file.h>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

using namespace pcl_sparse;
using namespace pcl_sparse_test;

namespace
{
  template <typename T>
  bool
  sameBits (const T& a, const T& b)
  {
    return std::memcmp (&a, &b, sizeof (T)) == 0;
  }

  void
  expectBitIdentical (const SparseSurfaceModel& a, const SparseSurfaceModel& b, bool with_vertices)
  {
    ASSERT_EQ (a.patches.size (), b.patches.size ());
    EXPECT_EQ (a.num_input_vertices, b.num_input_vertices);
    EXPECT_TRUE (sameBits (a.bbox_diagonal, b.bbox_diagonal));
    EXPECT_EQ (a.basis->size (), b.basis->size ());
    for (std::size_t p = 0; p < a.patches.size (); ++p)
    {
      const PatchCode& x = a.patches[p];
      const PatchCode& y = b.patches[p];
      for (int i = 0; i < 3; ++i)
        EXPECT_TRUE (sameBits (x.origin[i], y.origin[i]));
      for (int i = 0; i < 9; ++i)
        EXPECT_TRUE (sameBits (x.frame (i), y.frame (i)));
      EXPECT_TRUE (sameBits (x.radius, y.radius));
      EXPECT_EQ (x.atoms, y.atoms);
      ASSERT_EQ (x.coefficients.size (), y.coefficients.size ());
      for (std::size_t k = 0; k < x.coefficients.size (); ++k)
        EXPECT_TRUE (sameBits (x.coefficients[k], y.coefficients[k]));
      ASSERT_EQ (x.footprint.extent.size (), y.footprint.extent.size ());
      for (std::size_t k = 0; k < x.footprint.extent.size (); ++k)
        EXPECT_TRUE (sameBits (x.footprint.extent[k], y.footprint.extent[k]));
      if (with_vertices)
      {
        EXPECT_EQ (x.vertices, y.vertices);
        ASSERT_EQ (x.vertex_xy.size (), y.vertex_xy.size ());
        for (std::size_t k = 0; k < x.vertex_xy.size (); ++k)
          EXPECT_TRUE (sameBits (x.vertex_xy[k], y.vertex_xy[k]));
      }
      else
      {
        EXPECT_TRUE (y.vertices.empty ());
        EXPECT_TRUE (y.vertex_xy.empty ());
      }
    }
  }

  /// Largest world displacement of surface points s + r R (x, y, h(x, y)) over a polar grid of each
  /// original patch's footprint.
  double
  largestSurfaceDisplacement (const SparseSurfaceModel& a, const SparseSurfaceModel& b)
  {
    double worst = 0.0;
    for (std::size_t p = 0; p < a.patches.size (); ++p)
      for (int k = 0; k < 32; ++k)
        for (int j = 0; j <= 8; ++j)
        {
          const double angle = 2.0 * M_PI * k / 32.0;
          const double r = a.patches[p].footprint.extentAt (angle) * j / 8.0;
          const double x = r * std::cos (angle), y = r * std::sin (angle);
          const Eigen::Vector3d pa = a.patches[p].toWorld (Eigen::Vector3d (x, y, a.evaluate (p, x, y).value));
          const Eigen::Vector3d pb = b.patches[p].toWorld (Eigen::Vector3d (x, y, b.evaluate (p, x, y).value));
          worst = std::max (worst, (pa - pb).norm ());
        }
    return worst;
  }

  std::vector<std::uint8_t>
  smallFile (bool quantised, bool attributes = false)
  {
    ModelWriteOptions options;
    options.tolerance = quantised ? 1e-3 : 0.0;
    options.include_vertices = false;
    auto model = test::makeSyntheticModel (2, 5, false, 4);
    if (attributes)
      test::addSyntheticAttributes (model, 5);
    return encodeModel (model, options);
  }

  void
  expectSameAttributes (const SparseSurfaceModel& a, const SparseSurfaceModel& b)
  {
    ASSERT_EQ (a.attribute_channels.size (), b.attribute_channels.size ());
    for (std::size_t c = 0; c < a.attribute_channels.size (); ++c)
    {
      EXPECT_EQ (a.attribute_channels[c].channel, b.attribute_channels[c].channel);
      EXPECT_TRUE (sameBits (a.attribute_channels[c].lower, b.attribute_channels[c].lower));
      EXPECT_TRUE (sameBits (a.attribute_channels[c].upper, b.attribute_channels[c].upper));
    }
    // The same cosine basis (kind and n) as the written model's.
    const auto* written = dynamic_cast<const CosineAtoms*> (a.attribute_basis.get ());
    const auto* read = dynamic_cast<const CosineAtoms*> (b.attribute_basis.get ());
    ASSERT_NE (written, nullptr);
    ASSERT_NE (read, nullptr);
    EXPECT_EQ (read->kind (), written->kind ());
    EXPECT_EQ (read->frequencies (), written->frequencies ());
    ASSERT_EQ (a.patches.size (), b.patches.size ());
    for (std::size_t p = 0; p < a.patches.size (); ++p)
    {
      ASSERT_EQ (a.patches[p].attributes.size (), b.patches[p].attributes.size ());
      for (std::size_t c = 0; c < a.patches[p].attributes.size (); ++c)
      {
        const SparseCode& x = a.patches[p].attributes[c];
        const SparseCode& y = b.patches[p].attributes[c];
        EXPECT_EQ (x.atoms, y.atoms);
        ASSERT_EQ (x.coefficients.size (), y.coefficients.size ());
        for (std::size_t k = 0; k < x.coefficients.size (); ++k)
          EXPECT_TRUE (sameBits (x.coefficients[k], y.coefficients[k]));
      }
    }
  }

  /// Largest change of an attribute value (clamped, as resampling evaluates it) over a polar grid of each
  /// patch's footprint, as a fraction of the channel's range.
  double
  largestAttributeChange (const SparseSurfaceModel& a, const SparseSurfaceModel& b)
  {
    double worst = 0.0;
    for (std::size_t p = 0; p < a.patches.size (); ++p)
      for (std::size_t c = 0; c < a.attribute_channels.size (); ++c)
        for (int k = 0; k < 16; ++k)
          for (int j = 0; j <= 4; ++j)
          {
            const double angle = 2.0 * M_PI * k / 16.0, r = j / 4.0;
            const double x = r * std::cos (angle), y = r * std::sin (angle);
            const double range = a.attribute_channels[c].upper - a.attribute_channels[c].lower;
            worst = std::max (worst, std::abs (a.evaluateAttribute (p, c, x, y) - b.evaluateAttribute (p, c, x, y)) / range);
          }
    return worst;
  }

  void
  expectErrorContaining (const std::vector<std::uint8_t>& bytes, const std::string& text)
  {
    try
    {
      decodeModel (bytes.data (), bytes.size (), "bad.psm");
      ADD_FAILURE () << "no error, expected one containing '" << text << "'";
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find (text), std::string::npos) << e.what ();
      EXPECT_EQ (std::string (e.what ()).rfind ("bad.psm", 0), 0u) << "message should name the file: " << e.what ();
    }
  }

  void
  putU32At (std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v)
  {
    for (int i = 0; i < 4; ++i)
      bytes[at + i] = static_cast<std::uint8_t> (v >> (8 * i));
  }

  void
  putU64At (std::vector<std::uint8_t>& bytes, std::size_t at, std::uint64_t v)
  {
    for (int i = 0; i < 8; ++i)
      bytes[at + i] = static_cast<std::uint8_t> (v >> (8 * i));
  }

  /// A synthetic model with vertices and colour / intensity, and options that write all of it at \a tolerance.
  std::pair<SparseSurfaceModel, ModelWriteOptions>
  modelWithEverything (std::size_t patches, unsigned seed, double tolerance)
  {
    auto model = test::makeSyntheticModel (patches, seed, true);
    test::addSyntheticAttributes (model, seed);
    ModelWriteOptions options;
    options.tolerance = tolerance;
    options.include_vertices = true;
    return {std::move (model), options};
  }

  /// Recomputes the header CRC, as a forger would, so that the field checks themselves are tested.
  void
  resealHeader (std::vector<std::uint8_t>& bytes)
  {
    putU32At (bytes, 48, crc32 (bytes.data (), 48));
  }

  void
  resealSectionHeader (std::vector<std::uint8_t>& bytes, std::size_t start)
  {
    putU32At (bytes, start + 28, crc32 (bytes.data () + start, 28));
  }
} // namespace

TEST (Crc32, KnownAnswer)
{
  const char* text = "123456789";
  EXPECT_EQ (crc32 (reinterpret_cast<const std::uint8_t*> (text), 9), 0xCBF43926u);
}

TEST (ByteStream, VarintsRoundTripAndRefuseOverlong)
{
  ByteWriter out;
  const std::int64_t values[] = {0, -1, 1, 63, -64, 64, 1 << 20, -(1ll << 40), std::numeric_limits<std::int64_t>::max (),
                                 std::numeric_limits<std::int64_t>::min ()};
  for (std::int64_t v : values)
    out.putSignedVarint (v);
  ByteReader in (out.bytes ().data (), out.size (), "test");
  for (std::int64_t v : values)
    EXPECT_EQ (in.getSignedVarint ("v"), v);
  EXPECT_TRUE (in.atEnd ());
  const std::vector<std::uint8_t> overlong (11, 0x80);
  ByteReader bad (overlong.data (), overlong.size (), "test");
  EXPECT_THROW (bad.getVarint ("v"), Error);
}

TEST (FrameQuantization, AngleErrorWithinBound)
{
  const auto model = test::makeSyntheticModel (300, 11);
  for (double step : {1e-2, 1e-3, 1e-5})
    for (const PatchCode& patch : model.patches)
    {
      Eigen::Matrix3d decoded;
      ASSERT_TRUE (dequantiseFrame (quantiseFrame (patch.frame, step), step, decoded));
      EXPECT_NEAR (decoded.determinant (), patch.frame.determinant (), 1e-9);
      const Eigen::Matrix3d relative = decoded.transpose () * patch.frame;
      const double angle = std::acos (std::clamp ((relative.trace () - 1.0) / 2.0, -1.0, 1.0));
      EXPECT_LE (angle, 1.1 * 2.0 * std::sqrt (3.0) * step);
    }
}

TEST (ModelFile, LosslessRoundTripIsBitIdentical)
{
  for (bool with_vertices : {false, true})
  {
    const auto model = test::makeSyntheticModel (200, 1, true);
    ModelWriteOptions options;
    options.include_vertices = with_vertices;
    const auto bytes = encodeModel (model, options);
    const auto decoded = decodeModel (bytes.data (), bytes.size ());
    expectBitIdentical (model, decoded, with_vertices);
    EXPECT_EQ (largestSurfaceDisplacement (model, decoded), 0.0);
    // and again: the decoded model encodes to the same bytes
    EXPECT_EQ (encodeModel (decoded, options), bytes);
  }
}

TEST (ModelFile, UncompressedSectionsRoundTrip)
{
  const auto model = test::makeSyntheticModel (30, 6, true);
  for (double tolerance : {0.0, 1e-4})
  {
    ModelWriteOptions options;
    options.tolerance = tolerance;
    options.include_vertices = true;
    const auto compressed = encodeModel (model, options);
    options.zstd_level = 0;
    const auto stored = encodeModel (model, options);
    EXPECT_GT (stored.size (), compressed.size ());
    const auto a = decodeModel (compressed.data (), compressed.size ());
    const auto b = decodeModel (stored.data (), stored.size ());
    expectBitIdentical (a, b, true);
  }
}

TEST (ModelFile, LargeSectionsTakeTheFasterLevel)
{
  ModelWriteOptions options;  // 19 up to 1 MiB, 9 above
  EXPECT_EQ (zstdLevelFor (0, options), 19);
  EXPECT_EQ (zstdLevelFor (std::size_t (1) << 20, options), 19);
  EXPECT_EQ (zstdLevelFor ((std::size_t (1) << 20) + 1, options), 9);
  options.zstd_level = 3;  // never a slower level than asked for
  EXPECT_EQ (zstdLevelFor (std::size_t (1) << 30, options), 3);
  options.zstd_level = 0;  // stored stays stored
  EXPECT_EQ (zstdLevelFor (std::size_t (1) << 30, options), 0);
  options = ModelWriteOptions ();
  options.zstd_large_level = 0;
  EXPECT_THROW (encodeModel (test::makeSyntheticModel (3, 4), options), Error);

  // A threshold below this model's sections changes the file, not the model it holds.
  const auto model = test::makeSyntheticModel (200, 5, true);
  for (double tolerance : {0.0, 1e-4})
  {
    ModelWriteOptions slow;
    slow.tolerance = tolerance;
    slow.include_vertices = true;
    ModelWriteOptions fast = slow;
    fast.zstd_large_section = 256;
    fast.zstd_large_level = 1;
    const auto a = encodeModel (model, slow);
    const auto b = encodeModel (model, fast);
    EXPECT_NE (a, b) << "tolerance " << tolerance;
    expectBitIdentical (decodeModel (a.data (), a.size ()), decodeModel (b.data (), b.size ()), true);
  }
}

TEST (ModelFile, EmptyModelRoundTrips)
{
  SparseSurfaceModel model;
  model.basis = std::make_shared<CosineDictionary> (12);
  model.bbox_diagonal = 2.0;
  for (double tolerance : {0.0, 1e-4})
  {
    ModelWriteOptions options;
    options.tolerance = tolerance;
    const auto bytes = encodeModel (model, options);
    const auto decoded = decodeModel (bytes.data (), bytes.size ());
    EXPECT_EQ (decoded.numPatches (), 0u);
    EXPECT_EQ (decoded.bbox_diagonal, 2.0);
  }
}

// Basis kind 2: the half-period cosines (pcl_sparse_encode -basis dct) survive a round trip as such.
// Basis kind 3: the half-period cosines and the monomials x, y, x^2, x y, y^2 as atoms 144 .. 148.
TEST (ModelFile, QuadricBasisRoundTrips)
{
  auto model = test::makeSyntheticModel (200, 5, true);
  model.basis = std::make_shared<QuadricDctDictionary> (12);
  for (std::size_t p = 0; p < model.patches.size (); ++p)
  {
    // One to three monomials a patch, some in front of the cosines (the order OMP picks them in).
    PatchCode& patch = model.patches[p];
    for (int k = 0; k <= static_cast<int> (p % 3); ++k)
    {
      const int monomial = 144 + static_cast<int> ((p + 2 * k) % 5);
      patch.atoms.insert (patch.atoms.begin () + (k % 2 == 0 ? 0 : static_cast<std::ptrdiff_t> (patch.atoms.size ())), monomial);
      patch.coefficients.insert (patch.coefficients.begin () + (k % 2 == 0 ? 0 : static_cast<std::ptrdiff_t> (patch.coefficients.size ())),
                                 0.02 * (static_cast<double> (p % 7) - 3.0) + 0.005);
    }
  }
  for (double tolerance : {0.0, 1e-4})
  {
    ModelWriteOptions options;
    options.tolerance = tolerance;
    const auto bytes = encodeModel (model, options);
    EXPECT_EQ (bytes[12], 3);
    const auto decoded = decodeModel (bytes.data (), bytes.size ());
    ASSERT_NE (dynamic_cast<const QuadricDctDictionary*> (decoded.basis.get ()), nullptr);
    EXPECT_EQ (decoded.basis->size (), 149);
    EXPECT_EQ (inspectModel (bytes.data (), bytes.size ()).basis, "quadric + dct cosine 12x12");
    if (tolerance == 0.0)
    {
      expectBitIdentical (model, decoded, false);
      EXPECT_EQ (encodeModel (decoded, options), bytes);
    }
    else
    {
      EXPECT_LE (largestSurfaceDisplacement (model, decoded), tolerance * model.bbox_diagonal);
      EXPECT_GT (largestSurfaceDisplacement (model, decoded), 0.0);
    }
    // Read over the cosines alone, the monomials lie outside the basis.
    auto relabelled = bytes;
    relabelled[12] = 2;
    resealHeader (relabelled);
    expectErrorContaining (relabelled, tolerance == 0.0 ? "outside the basis" : "runs past the basis' last atom");
  }
}

TEST (ModelFile, DctBasisRoundTrips)
{
  auto model = test::makeSyntheticModel (200, 5, true);
  model.basis = std::make_shared<DctCosineDictionary> (12);
  EXPECT_EQ (encodeModel (test::makeSyntheticModel (20, 5))[12], 1);  // the paper's dictionary: kind 1
  for (double tolerance : {0.0, 1e-4})
  {
    ModelWriteOptions options;
    options.tolerance = tolerance;
    const auto bytes = encodeModel (model, options);
    EXPECT_EQ (bytes[12], 2);
    const auto decoded = decodeModel (bytes.data (), bytes.size ());
    ASSERT_NE (dynamic_cast<const DctCosineDictionary*> (decoded.basis.get ()), nullptr);
    EXPECT_EQ (decoded.basis->size (), 144);
    EXPECT_EQ (inspectModel (bytes.data (), bytes.size ()).basis, "dct cosine 12x12");
    if (tolerance == 0.0)
    {
      expectBitIdentical (model, decoded, false);
      EXPECT_EQ (largestSurfaceDisplacement (model, decoded), 0.0);
      EXPECT_EQ (encodeModel (decoded, options), bytes);
    }
    else
      EXPECT_LE (largestSurfaceDisplacement (model, decoded), tolerance * model.bbox_diagonal);
    // The same codes read over the paper's atoms are a different surface: the kind matters.
    auto relabelled = bytes;
    relabelled[12] = 1;
    resealHeader (relabelled);
    const auto wrong = decodeModel (relabelled.data (), relabelled.size ());
    EXPECT_NE (dynamic_cast<const CosineDictionary*> (wrong.basis.get ()), nullptr);
    EXPECT_GT (largestSurfaceDisplacement (decoded, wrong), 1e-3 * model.bbox_diagonal);
  }
  auto bytes = encodeModel (model);
  bytes[12] = 4;
  resealHeader (bytes);
  expectErrorContaining (bytes, "unknown basis kind 4");
}

TEST (ModelFile, QuantisedRoundTripWithinTolerance)
{
  const auto model = test::makeSyntheticModel (300, 2, true);
  const std::size_t lossless = encodeModel (model).size ();
  std::size_t previous = 0;
  for (double tolerance : {1e-5, 1e-4, 1e-3})
  {
    ModelWriteOptions options;
    options.tolerance = tolerance;
    options.max_footprint_angles = 8;
    options.footprint_refine_steps = 0.0;  // every patch keeps 8 angles (refinement: the next test)
    const auto bytes = encodeModel (model, options);
    const auto decoded = decodeModel (bytes.data (), bytes.size ());
    ASSERT_EQ (decoded.numPatches (), model.numPatches ());
    const double bound = tolerance * model.bbox_diagonal;
    const double moved = largestSurfaceDisplacement (model, decoded);
    EXPECT_LE (moved, bound) << "tolerance " << tolerance;
    EXPECT_GE (moved, 0.02 * bound) << "the steps should use the budget, tolerance " << tolerance;
    for (std::size_t p = 0; p < model.numPatches (); ++p)
    {
      std::vector<int> sorted = model.patches[p].atoms, decoded_sorted = decoded.patches[p].atoms;
      std::sort (sorted.begin (), sorted.end ());
      std::sort (decoded_sorted.begin (), decoded_sorted.end ());
      EXPECT_EQ (decoded_sorted, sorted);
      for (std::size_t k = 1; k < decoded.patches[p].atoms.size (); ++k)  // shell order: max(i, j) never decreases
        EXPECT_LE (std::max (decoded.patches[p].atoms[k - 1] / 12, decoded.patches[p].atoms[k - 1] % 12),
                   std::max (decoded.patches[p].atoms[k] / 12, decoded.patches[p].atoms[k] % 12));
      const double error = (decoded.patches[p].frame.transpose () * decoded.patches[p].frame -
                            Eigen::Matrix3d::Identity ()).cwiseAbs ().maxCoeff ();
      EXPECT_LT (error, 1e-12);
      ASSERT_EQ (decoded.patches[p].footprint.extent.size (), 8u);  // 16 angles, every second kept
      for (std::size_t k = 0; k < 8; ++k)
        EXPECT_NEAR (decoded.patches[p].footprint.extent[k], model.patches[p].footprint.extent[2 * k], 0.5 / 15.0 + 1e-6);
    }
    EXPECT_LT (bytes.size (), lossless / 3) << "tolerance " << tolerance;
    if (previous)
      EXPECT_LT (bytes.size (), previous);
    previous = bytes.size ();
  }
}

// A quantised footprint keeps its coarse angles (8 here, 2 by default) where those draw it within
// footprint_refine_steps extent steps, and the angles between them where they would not (a border clipped at a
// crease): round footprints stay small, clipped ones keep their border (test_footprint_coding.cpp: the coding
// itself).
TEST (ModelFile, FootprintsKeepTheAnglesTheirBordersNeed)
{
  auto model = test::makeSyntheticModel (3, 2, false);
  const int angles = 64;
  for (std::size_t p = 0; p < 3; ++p)
  {
    std::vector<float>& extent = model.patches[p].footprint.extent;
    extent.assign (angles, 0.9f);
    for (int k = 0; k < angles; ++k)
      if (p == 1 && k >= 24 && k < 44)
        extent[k] = 0.15f;  // clipped across a third of the circle
      else if (p == 2)
        extent[k] = static_cast<float> (0.6 + 0.3 * std::cos (2.0 * M_PI * k / angles));  // smooth, not round
  }
  const double step = 0.9 / 15.0;  // the largest extent / (2^4 - 1)
  ModelWriteOptions options;
  options.tolerance = 1e-4;
  // The default: 2 coarse angles, the round footprint keeps them, the others are refined within the bound.
  const auto default_bytes = encodeModel (model, options);
  const auto by_default = decodeModel (default_bytes.data (), default_bytes.size ());
  EXPECT_EQ (by_default.patches[0].footprint.extent.size (), 2u);
  for (std::size_t p : {0u, 1u, 2u})
    EXPECT_LE (test::largestFootprintDeviation (model.patches[p].footprint, by_default.patches[p].footprint),
               (options.footprint_refine_steps + 0.5) * step + 1e-6) << "patch " << p;
  options.max_footprint_angles = 8;
  const auto refined_bytes = encodeModel (model, options);
  const auto refined = decodeModel (refined_bytes.data (), refined_bytes.size ());
  options.footprint_refine_steps = 0.0;
  const auto coarse_bytes = encodeModel (model, options);
  const auto coarse = decodeModel (coarse_bytes.data (), coarse_bytes.size ());
  // Round and smooth: 8 angles either way, within a step (rounding and the cosine's chords).
  for (std::size_t p : {0u, 2u})
  {
    EXPECT_EQ (refined.patches[p].footprint.extent.size (), 8u) << "patch " << p;
    EXPECT_LE (test::largestFootprintDeviation (model.patches[p].footprint, refined.patches[p].footprint), step)
      << "patch " << p;
  }
  // Clipped: 8 angles miss the clip by about its depth; refined, within the refinement's steps plus the
  // rounding (half a step).
  EXPECT_EQ (coarse.patches[1].footprint.extent.size (), 8u);
  EXPECT_GT (test::largestFootprintDeviation (model.patches[1].footprint, coarse.patches[1].footprint), 5.0 * step);
  EXPECT_GT (refined.patches[1].footprint.extent.size (), 8u);
  EXPECT_LE (test::largestFootprintDeviation (model.patches[1].footprint, refined.patches[1].footprint),
             (ModelWriteOptions ().footprint_refine_steps + 0.5) * step + 1e-6);
  // A refused value is an error.
  EXPECT_GT (ModelWriteOptions ().footprint_refine_steps, 0.0);
  options.footprint_refine_steps = -1.0;
  EXPECT_THROW (encodeModel (model, options), Error);
}

TEST (ModelFile, RangeCodedAndVarintLayoutsDecodeToTheSameModel)
{
  // The range coder changes how the quantised values are stored, not the values: both layouts decode to
  // bit-identical models, vertices and attributes included, and files of both layouts load.
  const auto [model, written] = modelWithEverything (120, 4, 1e-4);
  ModelWriteOptions options = written;
  const auto range_coded = encodeModel (model, options);
  options.range_coding = false;
  const auto varints = encodeModel (model, options);
  EXPECT_TRUE (inspectModel (range_coded.data (), range_coded.size (), "a").range_coded);
  EXPECT_FALSE (inspectModel (varints.data (), varints.size (), "b").range_coded);
  const auto a = decodeModel (range_coded.data (), range_coded.size ());
  const auto b = decodeModel (varints.data (), varints.size ());
  expectBitIdentical (a, b, true);
  expectSameAttributes (a, b);
  EXPECT_GT (largestSurfaceDisplacement (model, a), 0.0);
  // A lossless file has nothing to range-code: the option does not change it.
  EXPECT_EQ (encodeModel (model, ModelWriteOptions ()), encodeModel (model, [] {
               ModelWriteOptions o;
               o.range_coding = false;
               return o;
             }()));
}

/// A quantised, range-coded version-1 file promising \a m patches of the paper's basis, with byte-plane
/// seeds (3 m zero bytes) or, with \a coded_seeds, an empty range-coded SEED; m zero radius bytes; FRAM,
/// FOOT, ATOM and COEF empty.
std::vector<std::uint8_t>
fileWithPromisedPatches (std::uint32_t m, bool coded_seeds)
{
  ByteWriter out;
  const std::uint8_t magic[8] = {0x89, 'P', 'S', 'M', '\r', '\n', 0x1a, '\n'};
  out.putBytes (magic, 8);
  out.putU16 (1);
  out.putU16 (header_flag::quantised | header_flag::range_coded | (coded_seeds ? header_flag::coded_seeds : 0));
  out.putU8 (1);  // the paper's cosine basis
  out.putU8 (0);
  out.putU16 (12);
  out.putU32 (m);
  out.putU32 (7);
  out.putU64 (1000);
  out.putF64 (1.0);
  out.putF64 (1e-3);
  out.putU32 (crc32 (out.bytes ().data (), 48));
  ByteWriter quan;
  for (double v : {0.0, 0.0, 0.0, 0.01})
    quan.putF64 (v);
  quan.putU8 (1);  // seed bytes
  quan.putF64 (-3.0);
  quan.putF64 (0.01);
  quan.putU8 (1);  // radius bytes
  quan.putF64 (0.1);
  quan.putU8 (4);  // extent bits
  quan.putF64 (1e-3);
  quan.putF64 (1e-3);
  const std::vector<std::uint8_t> seeds (coded_seeds ? 0 : 3 * std::size_t (m), 0), radii (m, 0), none;
  for (const auto& [tag, payload] : std::vector<std::pair<std::string, const std::vector<std::uint8_t>*>> {
         {"QUAN", &quan.bytes ()}, {"SEED", &seeds}, {"FRAM", &none}, {"RADI", &radii}, {"FOOT", &none},
         {"ATOM", &none}, {"COEF", &none}})
  {
    const std::size_t start = out.size ();
    out.putBytes (reinterpret_cast<const std::uint8_t*> (tag.data ()), 4);
    out.putU32 (0);  // stored
    out.putU64 (payload->size ());
    out.putU64 (payload->size ());
    out.putU32 (crc32 (payload->data (), payload->size ()));
    out.putU32 (crc32 (out.bytes ().data () + start, 28));
    out.putBytes (payload->data (), payload->size ());
  }
  return out.bytes ();
}

TEST (ModelFile, PatchesPromisedByTheSeedsAreNotAllocatedBeforeTheyDecode)
{
  // SEED and RADI hold a few bytes a patch (zstd may shrink them 64 times), the range-coded sections less
  // than a byte: the reader made all M patches (285 bytes each) and unpacked M seed and radius integers
  // (32 bytes) before decoding the first, so a 280 KB file promising 4 million patches took 1.1 GB before
  // its empty FOOT section was found (this stored one: 4 MB, 310 MB).
  const std::vector<std::uint8_t> bytes = fileWithPromisedPatches (1u << 20, false);
  if (peakResidentKb (true) < 0)
    GTEST_SKIP () << "no /proc/self/clear_refs to measure the peak";
  const long before = peakResidentKb (false);
  expectErrorContaining (bytes, "section FOOT");
  const long grown = peakResidentKb (false) - before;
  EXPECT_LT (grown, 64 * 1024) << "kB, for a file of " << bytes.size () / 1024 << " kB";
}

TEST (ModelFile, PatchesThatCannotFitInMemoryAreRefusedBeforeDecoding)
{
  // A range-coded patch (coded seeds included) may take less than a byte, and only RADI grows with the
  // patches (one byte each, zstd may shrink it 64 times): a 155 KB file decoded to 1 GB of patches, so a
  // few MB could promise more than the machine's memory and end in an OOM kill. 1.2 x what fits (at 285
  // bytes a patch) is refused before a patch is decoded, naming the memory (its empty sections would fail).
  const double physical = physicalMemoryBytes ();
  const double m = 1.2 * physical / 285.0;
  if (!(m >= 1.0 && m < 5e8))
    GTEST_SKIP () << "this machine's " << physical / 1e9 << " GB need a file of more than 500 MB of radii";
  expectErrorContaining (fileWithPromisedPatches (static_cast<std::uint32_t> (m), true), "more than this machine's");
}

TEST (ModelFile, DamagedRangeCodedSectionsAreErrorsNotCrashes)
{
  // The checksums catch damage in a file; here every bit of the range-coded payloads is flipped behind
  // them (as a forger or the fuzzer would), and each one must decode to a model or throw pcl_sparse::Error
  // (under ASan + UBSan in test_format_sanitized). Tags: SEED FRAM RADI FOOT ATOM COEF VERT AATM ACOF.
  const auto [model, options] = modelWithEverything (6, 5, 1e-3);
  const ModelSections sections = encodeModelSections (model, options, {{0, model.patches.size ()}});
  const std::vector<std::string> tags = runSectionTags (sections.shared.flags);
  std::size_t errors = 0, decoded = 0;
  for (std::size_t s = 0; s < tags.size (); ++s)
  {
    if (tags[s] == "SEED" || tags[s] == "RADI" || tags[s] == "VERT")
      continue;  // not range-coded
    for (std::size_t bit = 0; bit < 8 * sections.runs[0][s].size (); ++bit)
    {
      std::vector<std::vector<std::uint8_t>> run = sections.runs[0];
      run[s][bit / 8] ^= static_cast<std::uint8_t> (1u << (bit % 8));
      std::vector<std::pair<const std::uint8_t*, std::size_t>> payloads;
      for (const auto& payload : run)
        payloads.emplace_back (payload.data (), payload.size ());
      try
      {
        const SparseSurfaceModel forged = decodeModelSections (sections.shared, model.patches.size (), payloads, "forged");
        ++decoded;
        // What decodes is a valid model: the writer refuses NaN, repeated or out-of-range atoms.
        EXPECT_NO_THROW (encodeModel (forged)) << tags[s] << " bit " << bit;
      }
      catch (const Error& e)
      {
        ++errors;
        // names a section: this one, or the one a damaged atom set or count misleads (COEF after ATOM)
        EXPECT_EQ (std::string (e.what ()).rfind ("forged: section ", 0), 0u) << e.what ();
      }
    }
  }
  EXPECT_GT (errors, 10 * decoded);  // measured 4147 refused, 285 decoded
  std::cout << "  flipped bits: " << errors << " refused, " << decoded << " decoded to another model" << std::endl;
}

TEST (ModelFile, QuantisedKeepsVertices)
{
  const auto model = test::makeSyntheticModel (20, 3, true);
  ModelWriteOptions options;
  options.tolerance = 1e-4;
  options.include_vertices = true;
  const auto bytes = encodeModel (model, options);
  const auto decoded = decodeModel (bytes.data (), bytes.size ());
  ASSERT_EQ (decoded.numPatches (), model.numPatches ());
  for (std::size_t p = 0; p < model.numPatches (); ++p)
  {
    EXPECT_EQ (decoded.patches[p].vertices, model.patches[p].vertices);
    ASSERT_EQ (decoded.patches[p].vertex_xy.size (), model.patches[p].vertex_xy.size ());
    for (std::size_t k = 0; k < model.patches[p].vertex_xy.size (); ++k)
      EXPECT_NEAR ((decoded.patches[p].vertex_xy[k] - model.patches[p].vertex_xy[k]).norm (), 0.0, 1e-7);
  }
}

TEST (ModelFile, EncoderRefusesWhatItCannotStore)
{
  auto model = test::makeSyntheticModel (3, 4);
  model.patches[1].coefficients[0] = std::nan ("");
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  model.patches[2].atoms[0] = 144;
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  model.patches[0].radius = 0.0;
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  model.patches[2].atoms[1] = model.patches[2].atoms[0];
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  model.patches[2].frame (0, 0) = 1.5;
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  model.bbox_diagonal = 0.0;
  ModelWriteOptions options;
  options.tolerance = 1e-4;
  EXPECT_THROW (encodeModel (model, options), Error);
  model.basis.reset ();
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4, true);
  model.patches[1].vertices.back () = static_cast<int> (model.num_input_vertices);
  ModelWriteOptions with_vertices;
  with_vertices.include_vertices = true;
  try
  {
    encodeModel (model, with_vertices);
    ADD_FAILURE () << "a vertex number past the input's vertices was written";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("a patch lists vertex 1000, outside the input's 1000 vertices"), std::string::npos)
      << e.what ();
  }
}

TEST (ModelFile, EveryTruncationIsAnError)
{
  for (bool quantised : {false, true})
    for (bool attributes : {false, true})
  {
    const auto bytes = smallFile (quantised, attributes);
    for (std::size_t length = 0; length < bytes.size (); ++length)
    {
      std::vector<std::uint8_t> cut (bytes.begin (), bytes.begin () + length);
      EXPECT_THROW (decodeModel (cut.data (), cut.size (), "cut.psm"), Error) << "length " << length;
    }
    std::vector<std::uint8_t> longer = bytes;
    longer.push_back (0);
    expectErrorContaining (longer, "trailing bytes");
  }
}

TEST (ModelFile, EverySingleBitFlipIsAnError)
{
  for (bool quantised : {false, true})
    for (bool attributes : {false, true})
  {
    const auto bytes = smallFile (quantised, attributes);
    ASSERT_LT (bytes.size (), 2000u);
    // Every bit of the file (a few hundred bytes).
    for (std::size_t bit = 0; bit < 8 * bytes.size (); ++bit)
    {
      std::vector<std::uint8_t> flipped = bytes;
      flipped[bit / 8] ^= static_cast<std::uint8_t> (1u << (bit % 8));
      EXPECT_THROW (decodeModel (flipped.data (), flipped.size (), "flip.psm"), Error) << "bit " << bit;
    }
  }
}

TEST (ModelFile, ForgedHeadersGiveClearErrors)
{
  const auto good = smallFile (false);
  auto bytes = good;
  bytes[1] = 'X';
  expectErrorContaining (bytes, "wrong magic");

  bytes = good;  // the version is checked first: a later version may lay out its header differently
  bytes[8] = 4;
  expectErrorContaining (bytes, "unsupported model file version 4");
  for (std::uint8_t tiled : {2, 3})  // versions 2 and 3 are tiled files (tiled_model_file.h), whose header this is not
  {
    bytes[8] = tiled;
    expectErrorContaining (bytes, "tiled model file");
  }

  bytes = good;
  bytes[17] ^= 1;
  expectErrorContaining (bytes, "header checksum");

  bytes = good;  // lying patch count, checksum forged
  putU32At (bytes, 16, 1000000);
  resealHeader (bytes);
  expectErrorContaining (bytes, "patches need");

  bytes = good;
  putU32At (bytes, 16, 0xFFFFFFFFu);
  resealHeader (bytes);
  expectErrorContaining (bytes, "number of patches");

  bytes = good;
  bytes[14] = 200;  // basis with 200 frequencies
  resealHeader (bytes);
  expectErrorContaining (bytes, "frequencies is out of range");

  bytes = good;
  putU32At (bytes, 20, 99);
  resealHeader (bytes);
  expectErrorContaining (bytes, "sections, expected");

  // A huge declared decompressed size in the first zstd section, checksum forged. Sections zstd does not
  // shrink are stored, as all of this small file's are: a larger model has zstd sections.
  bytes = encodeModel (test::makeSyntheticModel (200, 5, false, 4), ModelWriteOptions ());
  std::size_t zstd_section = 52;
  while (zstd_section + 32 <= bytes.size () && bytes[zstd_section + 4] != 1)
    zstd_section += 32 + bytes[zstd_section + 8] + 256 * bytes[zstd_section + 9] + 65536 * bytes[zstd_section + 10];
  ASSERT_LT (zstd_section + 32, bytes.size ()) << "no zstd section";
  putU64At (bytes, zstd_section + 16, std::uint64_t (1) << 40);
  resealSectionHeader (bytes, zstd_section);
  expectErrorContaining (bytes, "can justify");
  bytes = good;  // the same on SEED, stored: its random doubles do not shrink
  ASSERT_EQ (bytes[52 + 4], 0);
  putU64At (bytes, 52 + 16, std::uint64_t (1) << 40);
  resealSectionHeader (bytes, 52);
  expectErrorContaining (bytes, "different raw and stored sizes");

  bytes = good;  // a huge stored size
  putU64At (bytes, 52 + 8, std::uint64_t (1) << 62);
  resealSectionHeader (bytes, 52);
  expectErrorContaining (bytes, "truncated file");

  bytes = good;
  bytes[52] = 'X';
  resealSectionHeader (bytes, 52);
  expectErrorContaining (bytes, "expected 'SEED'");

  bytes = good;
  bytes[10] |= 8;  // the range-coded flag on a lossless file
  resealHeader (bytes);
  expectErrorContaining (bytes, "range-coded flag needs the quantised flag");

  bytes = good;
  bytes[10] |= 16;  // the adaptive-footprint flag on a lossless file
  resealHeader (bytes);
  expectErrorContaining (bytes, "adaptive-footprint flag needs the quantised flag");

  bytes = good;
  bytes[10] |= 32;  // the coded-seed flag on a lossless file (so without the range-coded flag)
  resealHeader (bytes);
  expectErrorContaining (bytes, "coded-seed flag needs the range-coded flag");

  bytes = good;
  bytes[10] |= 64;  // a flag of a later format
  resealHeader (bytes);
  expectErrorContaining (bytes, "unknown header flags");

  bytes = good;
  bytes[40 + 7] = 0x7F;  // tolerance becomes a huge number on a lossless file
  resealHeader (bytes);
  expectErrorContaining (bytes, "tolerance");
}

TEST (ModelFile, SaveAndLoadFiles)
{
  const std::string directory = std::string (PCL_SPARSE_BINARY_DIR) + "/test_format_files";
  std::filesystem::create_directories (directory);
  const std::string path = directory + "/model.psm";
  const auto model = test::makeSyntheticModel (50, 9);
  saveModel (path, model);
  expectBitIdentical (model, loadModel (path), false);
  const ModelFileInfo info = inspectModelFile (path);
  EXPECT_EQ (info.num_patches, 50u);
  EXPECT_EQ (info.sections.size (), 6u);
  EXPECT_EQ (info.file_bytes, std::filesystem::file_size (path));
  EXPECT_EQ (info.basis, "cosine 12x12");

  EXPECT_THROW (loadModel (directory + "/missing.psm"), Error);
  EXPECT_THROW (loadModel (directory), Error);
  // Failed saves leave nothing behind, not even a temporary file: a folder that does not exist, and a model
  // the encoder refuses (before any file is opened; AtomicWrite.FailureLeavesNoFile fails a write midway).
  EXPECT_THROW (saveModel (directory + "/no/such/dir/model.psm", model), Error);
  auto bad = model;
  bad.patches[0].radius = -1.0;
  EXPECT_THROW (saveModel (directory + "/bad.psm", bad), Error);
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator (directory))
    left.push_back (entry.path ().filename ().string ());
  EXPECT_EQ (left, std::vector<std::string>{"model.psm"});
  std::filesystem::remove_all (directory);
}

// Colour and intensity (issue 12 point 7): sections ACHN AATM ACOF after the others, flag bit 2.
TEST (ModelFile, AttributesLosslessRoundTripIsBitIdentical)
{
  for (bool with_vertices : {false, true})
  {
    auto model = test::makeSyntheticModel (120, 11, true);
    const auto plain = encodeModel (model);
    test::addSyntheticAttributes (model, 12);
    ModelWriteOptions options;
    options.include_vertices = with_vertices;
    const auto bytes = encodeModel (model, options);
    EXPECT_EQ (bytes[10], with_vertices ? 6 : 4);  // flags: attributes (4), vertices (2)
    const auto decoded = decodeModel (bytes.data (), bytes.size ());
    expectBitIdentical (model, decoded, with_vertices);
    expectSameAttributes (model, decoded);
    EXPECT_EQ (largestAttributeChange (model, decoded), 0.0);
    EXPECT_EQ (encodeModel (decoded, options), bytes);
    const ModelFileInfo info = inspectModel (bytes.data (), bytes.size ());
    EXPECT_EQ (info.attributes, (std::vector<std::string>{"r", "g", "b", "intensity"}));
    EXPECT_EQ (info.sections.size (), with_vertices ? 10u : 9u);
    EXPECT_EQ (info.sections.back ().tag, "ACOF");
    // The geometry's sections are the file without attributes, byte for byte (after the header).
    if (!with_vertices)
      EXPECT_TRUE (std::equal (plain.begin () + 52, plain.end (), bytes.begin () + 52));
  }
}

// An attribute basis with the quadric's monomials (a model built in the library; the encoder codes colour over
// the cosines): ACHN stores kind 3 and the monomials' shell ranks, as the header's basis does. Before, ACHN knew
// kinds 1 and 2 only and wrote such a basis as kind 1, which the reader refused ("outside the basis").
TEST (ModelFile, QuadricAttributeBasisRoundTrips)
{
  auto model = test::makeSyntheticModel (150, 17);
  test::addSyntheticAttributes (model, 18, CosineBasisKind::DctQuadric);
  std::size_t monomials = 0;
  for (const PatchCode& patch : model.patches)
    for (const SparseCode& code : patch.attributes)
      monomials += std::count_if (code.atoms.begin (), code.atoms.end (), [] (int a) { return a >= 144; });
  ASSERT_GT (monomials, 20u) << "the codes must use the monomials";
  const auto lossless = encodeModel (model);
  const SparseSurfaceModel decoded = decodeModel (lossless.data (), lossless.size ());
  ASSERT_NE (dynamic_cast<const QuadricDctDictionary*> (decoded.attribute_basis.get ()), nullptr);
  expectSameAttributes (model, decoded);
  EXPECT_EQ (largestAttributeChange (model, decoded), 0.0);
  for (bool range_coding : {true, false})
  {
    ModelWriteOptions options;
    options.tolerance = 1e-4;
    options.attribute_tolerance = 0.5 / 255.0;
    options.range_coding = range_coding;
    const auto bytes = encodeModel (model, options);
    const SparseSurfaceModel quantised = decodeModel (bytes.data (), bytes.size ());
    ASSERT_NE (dynamic_cast<const QuadricDctDictionary*> (quantised.attribute_basis.get ()), nullptr);
    const double changed = largestAttributeChange (model, quantised);
    EXPECT_LE (changed, options.attribute_tolerance * (1.0 + 1e-9)) << range_coding;
    EXPECT_GT (changed, 0.0) << range_coding;
  }
}

TEST (ModelFile, AttributesQuantisedWithinTolerance)
{
  auto model = test::makeSyntheticModel (200, 13);
  test::addSyntheticAttributes (model, 14);
  std::size_t previous = 0;
  for (double attribute_tolerance : {0.1 / 255.0, 0.5 / 255.0, 2.0 / 255.0})
  {
    ModelWriteOptions options;
    options.tolerance = 1e-4;
    options.attribute_tolerance = attribute_tolerance;
    const auto bytes = encodeModel (model, options);
    const auto decoded = decodeModel (bytes.data (), bytes.size ());
    const double changed = largestAttributeChange (model, decoded);
    EXPECT_LE (changed, attribute_tolerance * (1.0 + 1e-9));
    EXPECT_GE (changed, 0.05 * attribute_tolerance) << "the steps should use the budget";
    EXPECT_LE (largestSurfaceDisplacement (model, decoded), options.tolerance * model.bbox_diagonal);
    if (previous)
      EXPECT_LT (bytes.size (), previous);
    previous = bytes.size ();
  }
  ModelWriteOptions bad;
  bad.tolerance = 1e-4;
  bad.attribute_tolerance = 0.0;
  EXPECT_THROW (encodeModel (model, bad), Error);
}

TEST (ModelFile, AttributeSectionsRefuseLiesAndBadModels)
{
  const auto good = smallFile (false, true);
  // ACHN is the 7th section: 52-byte header + 6 sections before it.
  std::size_t start = 52;
  for (int s = 0; s < 6; ++s)
  {
    std::uint64_t stored = 0;
    for (int i = 0; i < 8; ++i)
      stored |= static_cast<std::uint64_t> (good[start + 8 + i]) << (8 * i);
    start += 32 + stored;
  }
  ASSERT_EQ (std::string (good.begin () + start, good.begin () + start + 4), "ACHN");
  auto forge = [&] (std::size_t at, std::uint8_t value) {
    auto bytes = good;
    bytes[start + 32 + at] = value;  // in the payload (stored: its CRC is recomputed)
    putU32At (bytes, start + 24, crc32 (bytes.data () + start + 32, bytes[start + 8]));
    resealSectionHeader (bytes, start);
    return bytes;
  };
  expectErrorContaining (forge (3, 200), "channels");         // channel count 200
  expectErrorContaining (forge (4, 9), "attribute channel 9");  // unknown channel id
  expectErrorContaining (forge (0, 7), "unknown attribute basis kind 7");
  expectErrorContaining (forge (1, 0), "frequencies is out of range");

  auto bytes = good;  // the attribute flag without the sections
  bytes[10] = 0;
  resealHeader (bytes);
  expectErrorContaining (bytes, "9 sections, expected 6");

  auto model = test::makeSyntheticModel (3, 4);
  test::addSyntheticAttributes (model, 4);
  model.patches[1].attributes.pop_back ();
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  test::addSyntheticAttributes (model, 4);
  model.patches[2].attributes[0].atoms = {3, 3};
  model.patches[2].attributes[0].coefficients = {1.0, 2.0};
  EXPECT_THROW (encodeModel (model), Error);
  model.patches[2].attributes[0].atoms = {144};
  model.patches[2].attributes[0].coefficients = {1.0};
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  test::addSyntheticAttributes (model, 4);
  model.attribute_basis.reset ();
  EXPECT_THROW (encodeModel (model), Error);
  model = test::makeSyntheticModel (3, 4);
  test::addSyntheticAttributes (model, 4);
  model.attribute_channels.clear ();  // codes without channels would be dropped silently
  EXPECT_THROW (encodeModel (model), Error);
}

namespace
{
  /// \a model cut into three tiles of a 3 x 1 x 1 grid (none if it has fewer than 3 patches; the format does
  /// not check where patches lie).
  TiledModel
  threeTiles (const SparseSurfaceModel& model)
  {
    TiledModel tiled;
    tiled.model = model;
    tiled.grid.origin = Eigen::Vector3d (-1.0, -1.0, -1.0);
    tiled.grid.edge = 1.0;
    tiled.grid.counts = Eigen::Vector3i (3, 1, 1);
    tiled.grid.margin = 0.1;
    const std::size_t m = model.patches.size ();
    if (m >= 3)
      tiled.tiles = {{0, 0, m / 3}, {1, m / 3, m / 3}, {2, 2 * (m / 3), m - 2 * (m / 3)}};
    tiled.total_patches = m;
    return tiled;
  }
} // namespace

TEST (TiledModelFile, AttributesRoundTripAndEveryDamageIsAnError)
{
  // Version 3 (lean tiles, shared QUAN and ACHN): lossless bit for bit, quantised as the version-1 file of the
  // same model; every truncation and every bit flip refused (this file also runs under ASan and UBSan).
  auto model = test::makeSyntheticModel (9, 7, true, 4);
  test::addSyntheticAttributes (model, 7);
  for (bool quantised : {false, true})
  {
    ModelWriteOptions options;
    options.tolerance = quantised ? 1e-3 : 0.0;
    options.include_vertices = true;
    const TiledModel tiled = threeTiles (model);
    const std::vector<std::uint8_t> bytes = encodeTiledModel (tiled, options, 1);
    const SparseSurfaceModel loaded = decodeModel (bytes.data (), bytes.size (), "tiled.psm");
    const std::vector<std::uint8_t> untiled = encodeModel (model, options);
    const SparseSurfaceModel expected = quantised ? decodeModel (untiled.data (), untiled.size ()) : model;
    expectBitIdentical (expected, loaded, true);
    expectSameAttributes (expected, loaded);
    const ModelFileInfo info = inspectModel (bytes.data (), bytes.size ());
    EXPECT_EQ (info.version, 3);
    EXPECT_EQ (info.num_tiles, 3u);
    EXPECT_EQ (info.attributes.size (), model.attribute_channels.size ());
    for (std::size_t length = 0; length < bytes.size (); ++length)
      EXPECT_THROW (decodeModel (bytes.data (), length, "cut.psm"), Error) << "length " << length;
    // Every bit of the header, shared sections and index; every 5th bit of the tiles (each has its CRC-32).
    const std::size_t index_end = 116 + 4 + (bytes[104] | bytes[105] << 8) + (bytes[108] | bytes[109] << 8);
    for (std::size_t bit = 0; bit < 8 * bytes.size (); bit += bit < 8 * index_end ? 1 : 5)
    {
      std::vector<std::uint8_t> flipped = bytes;
      flipped[bit / 8] ^= static_cast<std::uint8_t> (1u << (bit % 8));
      EXPECT_THROW (decodeModel (flipped.data (), flipped.size (), "flip.psm"), Error) << "bit " << bit;
    }
  }
}

TEST (TiledModelFile, EmptyModelKeepsItsBasisAndChannels)
{
  // No tiles: the merged model still has the basis and channels of the shared fields (it re-encodes).
  auto model = test::makeSyntheticModel (0, 3, false, 4);
  test::addSyntheticAttributes (model, 3);
  ModelWriteOptions options;
  options.tolerance = 1e-3;
  const std::vector<std::uint8_t> bytes = encodeTiledModel (threeTiles (model), options, 1);
  const SparseSurfaceModel loaded = decodeModel (bytes.data (), bytes.size ());
  EXPECT_TRUE (loaded.patches.empty ());
  ASSERT_TRUE (loaded.basis);
  EXPECT_EQ (loaded.basis->size (), model.basis->size ());
  EXPECT_EQ (loaded.attribute_channels.size (), model.attribute_channels.size ());
  expectSameAttributes (model, loaded);  // channel ids, ranges and the attribute basis
  EXPECT_EQ (loaded.bbox_diagonal, model.bbox_diagonal);
  EXPECT_EQ (loaded.num_input_vertices, model.num_input_vertices);
  EXPECT_NO_THROW (encodeModel (loaded, options));
}

TEST (ModelFile, RadiiBeyondTheQuantisedScaleAreRefusedWithTheCause)
{
  // One patch of radius 1e20 among radii of 0.1-1 (a mesh with one vertex at 1e20): the log scale of the
  // radii, as fine as the tolerance needs, has more than 2^32 steps. Said so, with what to do instead.
  SparseSurfaceModel model = test::makeSyntheticModel (20, 7);
  model.patches[5].radius = 1e20;
  ModelWriteOptions options;
  options.tolerance = 1e-3;
  try
  {
    encodeModel (model, options);
    FAIL () << "a radius of 1e20 was quantised";
  }
  catch (const Error& e)
  {
    const std::string message = e.what ();
    EXPECT_NE (message.find ("1e+20"), std::string::npos) << message;
    EXPECT_NE (message.find ("a vertex far from the rest"), std::string::npos) << message;
    EXPECT_NE (message.find ("-tolerance 0"), std::string::npos) << message;
  }
  // The lossless file holds it.
  EXPECT_NO_THROW (encodeModel (model, ModelWriteOptions ()));
}
