/// The adaptive binary range coder of the model file (format/range_coder.h): exact round trips, code
/// lengths near the entropy, the stored bytes pinned, and damaged streams refused.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/range_coder.h>
#include <pcl_sparse/format/sparse_code_stream.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace pcl_sparse;

namespace
{
  /// Bits that are 1 with probability 1 / \a one_in (std::mt19937_64 is the same on every platform).
  std::vector<bool>
  rareBits (std::size_t count, unsigned one_in, std::uint64_t seed)
  {
    std::mt19937_64 random (seed);
    std::vector<bool> bits (count);
    for (std::size_t i = 0; i < count; ++i)
      bits[i] = random () % one_in == 0;
    return bits;
  }

  /// A mixed stream: adaptive bits, a bit tree, signed integers, equal-probable bits.
  std::vector<std::uint8_t>
  encodeMixed (const std::vector<std::int64_t>& integers)
  {
    RangeEncoder out;
    AdaptiveBit bit;
    BitTreeModel tree (4);
    SignedIntegerModel integer;
    for (int i = 0; i < 16; ++i)
      out.put (bit, (0xB38Fu >> i) & 1u);
    for (std::uint32_t v = 0; v < 16; ++v)
      tree.put (out, v);
    for (std::int64_t v : integers)
      integer.put (out, v);
    for (int i = 0; i < 8; ++i)
      out.putEqualProbable (i % 3 == 0);
    return out.finish ();
  }

  /// Decodes encodeMixed's stream of \a count integers and checks every value (expectEnd included).
  void
  decodeMixed (const std::vector<std::uint8_t>& bytes, const std::vector<std::int64_t>& integers)
  {
    RangeDecoder in (bytes.data (), bytes.size (), "stream");
    AdaptiveBit bit;
    BitTreeModel tree (4);
    SignedIntegerModel integer;
    for (int i = 0; i < 16; ++i)
      EXPECT_EQ (in.get (bit), bool ((0xB38Fu >> i) & 1u));
    for (std::uint32_t v = 0; v < 16; ++v)
      EXPECT_EQ (tree.get (in), v);
    for (std::int64_t v : integers)
      EXPECT_EQ (integer.get (in), v);
    for (int i = 0; i < 8; ++i)
      EXPECT_EQ (in.getEqualProbable (), i % 3 == 0);
    in.expectEnd ();
  }

  const std::vector<std::int64_t> kIntegers = {0, 1, -1, 2, 3, -7, 300, -4096, std::int64_t (1) << 40,
                                               std::numeric_limits<std::int64_t>::max (),
                                               -std::numeric_limits<std::int64_t>::max (), 0, 0, 5};
} // namespace

TEST (RangeCoder, AdaptiveBitsRoundTripCloseToTheirEntropy)
{
  // Measured over the entropy of the ones actually drawn: 1.026, 1.083, 1.128.
  const std::pair<unsigned, double> cases[] = {{2u, 1.05}, {16u, 1.12}, {200u, 1.18}};
  for (const auto& [one_in, bound] : cases)
  {
    const std::vector<bool> bits = rareBits (20000, one_in, one_in);
    RangeEncoder out;
    AdaptiveBit model;
    for (bool b : bits)
      out.put (model, b);
    const std::vector<std::uint8_t> bytes = out.finish ();

    RangeDecoder in (bytes.data (), bytes.size (), "bits");
    AdaptiveBit same;
    for (std::size_t i = 0; i < bits.size (); ++i)
      ASSERT_EQ (in.get (same), bits[i]) << "bit " << i;
    in.expectEnd ();

    const double p = static_cast<double> (std::count (bits.begin (), bits.end (), true)) / bits.size ();
    const double entropy_bytes = bits.size () * -(p * std::log2 (p) + (1 - p) * std::log2 (1 - p)) / 8.0;
    // Adapting by 1/16 of the way costs a few to 18 % over the entropy (more for rarer bits), far below the
    // one bit per value of any byte-aligned coding of single bits.
    EXPECT_LE (bytes.size (), bound * entropy_bytes + 4) << "1 in " << one_in;
    EXPECT_GE (bytes.size (), entropy_bytes * 0.95) << "1 in " << one_in;
  }
}

TEST (RangeCoder, EqualProbableBitsTakeOneBitEach)
{
  const std::vector<bool> bits = rareBits (8000, 2, 7);
  RangeEncoder out;
  for (bool b : bits)
    out.putEqualProbable (b);
  const std::vector<std::uint8_t> bytes = out.finish ();
  EXPECT_EQ (bytes.size (), 1000u + 4u);
  RangeDecoder in (bytes.data (), bytes.size (), "bits");
  for (bool b : bits)
    ASSERT_EQ (in.getEqualProbable (), b);
  in.expectEnd ();
}

TEST (RangeCoder, MixedStreamRoundTripsAndItsBytesArePinned)
{
  const std::vector<std::uint8_t> bytes = encodeMixed (kIntegers);
  decodeMixed (bytes, kIntegers);
  // The file format's bytes: a change here makes existing files unreadable.
  // The run of 0xFF bytes is the carry path: the equal-probable bits of the two largest magnitudes.
  const std::vector<std::uint8_t> pinned = {0xEB, 0x0F, 0xF3, 0xB4, 0x87, 0xA4, 0xBB, 0x81, 0x3F, 0x2C, 0x81, 0x7C,
                                               0x64, 0xFE, 0x42, 0x5A, 0xDA, 0x4A, 0x54, 0x94, 0xB3, 0xE4, 0xFF, 0xFE,
                                               0x6F, 0x20, 0x00, 0x00, 0x00, 0x8A, 0xBA, 0xAC, 0x6F, 0xFF, 0xFF, 0xFF,
                                               0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
                                               0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xF9, 0x40,
                                               0x0D, 0x0F, 0xA5, 0x80};
  EXPECT_EQ (bytes, pinned);
}

TEST (RangeCoder, EmptyStreamIsNoBytes)
{
  RangeEncoder out;
  EXPECT_TRUE (out.finish ().empty ());
  const std::uint8_t none = 0;
  RangeDecoder in (&none, 0, "empty");
  EXPECT_NO_THROW (in.expectEnd ());
  AdaptiveBit model;
  EXPECT_THROW (in.get (model), Error);
}

TEST (RangeCoder, TruncatedOrExtendedStreamsAreRefused)
{
  const std::vector<std::uint8_t> bytes = encodeMixed (kIntegers);
  for (std::size_t length = 0; length < bytes.size (); ++length)
  {
    const std::vector<std::uint8_t> cut (bytes.begin (), bytes.begin () + length);
    EXPECT_ANY_THROW (decodeMixed (cut, kIntegers)) << "length " << length;
  }
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back (0);
  try
  {
    decodeMixed (longer, kIntegers);
    ADD_FAILURE () << "a trailing byte was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("stream: 1 unexpected trailing bytes"), std::string::npos) << e.what ();
  }
}

TEST (RangeCoder, BitTreeLearnsASkewedDistribution)
{
  // Counts of 8 most of the time, as footprint angles are: far below the tree's 13 bits each.
  RangeEncoder out;
  BitTreeModel tree (13);
  std::mt19937_64 random (3);
  std::vector<std::uint32_t> values;
  for (int i = 0; i < 5000; ++i)
    values.push_back (random () % 10 == 0 ? static_cast<std::uint32_t> (random () % 4097) : 8u);
  for (std::uint32_t v : values)
    tree.put (out, v);
  const std::vector<std::uint8_t> bytes = out.finish ();
  EXPECT_LT (bytes.size (), 5000u * 2u / 8u + 100u);  // under 2 bits a value
  RangeDecoder in (bytes.data (), bytes.size (), "tree");
  BitTreeModel same (13);
  for (std::uint32_t v : values)
    ASSERT_EQ (same.get (in), v);
  in.expectEnd ();
  EXPECT_THROW (BitTreeModel (4).put (out, 16), std::invalid_argument);
  EXPECT_THROW (BitTreeModel (17), std::invalid_argument);
}

TEST (SparseCodeContexts, CodesRoundTripInShellRankOrder)
{
  const int n = 12;
  const std::vector<std::vector<int>> codes = {{0, 1, 12, 13}, {}, {143}, {5, 77, 2, 140, 12}, {0}};
  RangeEncoder atoms, coefficients;
  SparseCodeContexts writer (n);
  std::vector<std::vector<double>> written;
  for (const std::vector<int>& code : codes)
  {
    std::vector<double> values;
    for (std::size_t k = 0; k < code.size (); ++k)
      values.push_back (0.25 * static_cast<double> (code[k]) - 3.0);
    const std::vector<std::size_t> order = writer.putAtoms (atoms, code);
    for (std::size_t k = 1; k < order.size (); ++k)
      EXPECT_LT (shellRank (code[order[k - 1]], n), shellRank (code[order[k]], n));
    written.push_back (writer.putCoefficients (coefficients, code, values, order, 0.125));
  }
  const std::vector<std::uint8_t> atom_bytes = atoms.finish (), coefficient_bytes = coefficients.finish ();

  RangeDecoder atom_in (atom_bytes.data (), atom_bytes.size (), "atoms");
  RangeDecoder coefficient_in (coefficient_bytes.data (), coefficient_bytes.size (), "coefficients");
  SparseCodeContexts reader (n);
  for (std::size_t c = 0; c < codes.size (); ++c)
  {
    std::vector<int> decoded;
    std::vector<double> values;
    reader.getAtoms (atom_in, "code", decoded);
    ASSERT_EQ (decoded.size (), codes[c].size ());
    reader.getCoefficients (coefficient_in, decoded, 0.125, values);
    for (std::size_t k = 0; k < decoded.size (); ++k)
    {
      // In rank order, each coefficient with its atom (values are multiples of the step: exact).
      EXPECT_EQ (values[k], 0.25 * static_cast<double> (decoded[k]) - 3.0);
      EXPECT_EQ (values[k], written[c][k]);
    }
  }
  atom_in.expectEnd ();
  coefficient_in.expectEnd ();
}

TEST (SparseCodeContexts, RefusesACountAboveTheBasis)
{
  // A 2 x 2 basis has 4 atoms; its count tree holds up to 7.
  RangeEncoder out;
  BitTreeModel count (3);
  count.put (out, 5);
  const std::vector<std::uint8_t> bytes = out.finish ();
  RangeDecoder in (bytes.data (), bytes.size (), "atoms");
  SparseCodeContexts contexts (2);
  std::vector<int> atoms;
  try
  {
    contexts.getAtoms (in, "patch 0", atoms);
    ADD_FAILURE () << "5 atoms of 4 accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("patch 0 has 5 atoms"), std::string::npos) << e.what ();
  }
}

// QuadricDctDictionary's monomials (atoms n^2 .. n^2 + 4) rank right after the constant, the cosines after
// them in their shell order: a bijection of the 149 atoms onto ranks 0 .. 148.
TEST (ShellRank, MonomialsRankAfterTheConstant)
{
  const int n = 12, monomials = 5;
  std::vector<int> atom_of_rank (n * n + monomials, -1);
  for (int atom = 0; atom < n * n + monomials; ++atom)
  {
    const int rank = shellRank (atom, n, monomials);
    ASSERT_GE (rank, 0);
    ASSERT_LT (rank, n * n + monomials);
    EXPECT_EQ (atom_of_rank[rank], -1) << "rank " << rank << " taken twice";
    atom_of_rank[rank] = atom;
    EXPECT_EQ (atomOfShellRank (rank, n, monomials), atom);
  }
  EXPECT_EQ (atom_of_rank[0], 0);
  for (int k = 0; k < monomials; ++k)
    EXPECT_EQ (atom_of_rank[1 + k], n * n + k);
  for (int atom = 1; atom < n * n; ++atom)
    EXPECT_EQ (shellRank (atom, n, monomials), shellRank (atom, n) + monomials);

  // The range coder's contexts take every atom of the basis, monomials included.
  const std::vector<std::vector<int>> codes = {{0, 144, 146, 148, 13}, {147}, {143, 145}};
  RangeEncoder out;
  SparseCodeContexts writer (n, monomials);
  for (const std::vector<int>& code : codes)
    writer.putAtoms (out, code);
  const std::vector<std::uint8_t> bytes = out.finish ();
  RangeDecoder in (bytes.data (), bytes.size (), "atoms");
  SparseCodeContexts reader (n, monomials);
  for (const std::vector<int>& code : codes)
  {
    std::vector<int> atoms;
    reader.getAtoms (in, "code", atoms);
    std::vector<int> sorted (code);
    std::sort (sorted.begin (), sorted.end (), [&] (int a, int b) { return shellRank (a, n, monomials) < shellRank (b, n, monomials); });
    EXPECT_EQ (atoms, sorted);
  }
}
