// What the tools share (apps/tool_support.h): option values read exactly, and JSON that stays valid UTF-8.

#include <gtest/gtest.h>

#include "error_message.h"
#include "tool_input.h"
#include "tool_support.h"
#include "tool_tiling.h"

#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

using namespace pcl_sparse;
using pcl_sparse::tools::CommandLine;
using pcl_sparse::tools::Range;

namespace
{
  /// A command line "tool OPTION VALUE" with options -seed, -n and -x.
  CommandLine
  commandLine (const std::string& option, const std::string& value)
  {
    std::vector<std::string> words = {"tool", option, value};
    std::vector<char*> argv;
    for (std::string& word : words)
      argv.push_back (&word[0]);
    return CommandLine (static_cast<int> (argv.size ()), argv.data (), {"-seed", "-n", "-x"}, {});
  }

  std::uint64_t
  seed (const std::string& text)
  {
    std::uint64_t value = 7;
    commandLine ("-seed", text).integer ("-seed", value, Range::atLeast (0));
    return value;
  }

  int
  count (const std::string& text)
  {
    int value = 7;
    commandLine ("-n", text).integer ("-n", value, Range::closed (1, 1 << 26));
    return value;
  }

  double
  number (const std::string& text)
  {
    double value = 7.0;
    commandLine ("-x", text).number ("-x", value);
    return value;
  }

  /// The message of the pcl_sparse::Error that \a read throws, "" when it throws none.
  template <typename Read>
  std::string
  refusal (Read read)
  {
    return pcl_sparse_test::errorMessage (read);
  }

  /// Expects \a read to throw a pcl_sparse::Error that names \a option ("option -n: ..."): a refusal the
  /// user can act on, not some other error.
  template <typename Read>
  void
  expectRefusedNaming (Read read, const std::string& option, const std::string& text)
  {
    const std::string message = refusal (read);
    EXPECT_EQ (message.rfind ("option " + option, 0), 0u) << "'" << text << "': " << message;
  }
} // namespace

TEST (ToolOptions, SixtyFourBitSeedsKeepEveryDigit)
{
  // Read through a double, 2^53 + 1 was 2^53 and the largest seed was refused as too big.
  EXPECT_EQ (seed ("9007199254740993"), 9007199254740993ULL);
  EXPECT_EQ (seed ("18446744073709551615"), 18446744073709551615ULL);
  EXPECT_EQ (seed ("0"), 0u);
  EXPECT_EQ (seed ("9007199254740992"), 9007199254740992ULL);  // 2^53, the neighbour of 2^53 + 1
  for (const char* bad : {"18446744073709551616", "-1", "1.5"})  // one past the largest, negative, a fraction
    expectRefusedNaming ([&] { seed (bad); }, "-seed", bad);
}

TEST (ToolOptions, OtherSpellingsOnlyWhileExact)
{
  EXPECT_EQ (count ("1e6"), 1000000);
  EXPECT_EQ (count ("2.0e3"), 2000);
  EXPECT_EQ (seed ("4.5e15"), 4500000000000000ULL);
  // 1e17 as a double stands for many integers: the digits must be written out.
  expectRefusedNaming ([] { seed ("1e17"); }, "-seed", "1e17");
  EXPECT_NE (refusal ([] { seed ("1e17"); }).find ("plain digits"), std::string::npos);
  EXPECT_EQ (seed ("100000000000000000"), 100000000000000000ULL);
  // The range's ends are in it, one step beyond is not.
  EXPECT_EQ (count ("1"), 1);
  EXPECT_EQ (count ("67108864"), 1 << 26);
  // The bounds as they are (%g printed this one "[1, 6.71089e+07]").
  EXPECT_EQ (refusal ([] { count ("0"); }), "option -n: 0 is not in [1, 67108864]");
  EXPECT_EQ (refusal ([] { count ("67108865"); }), "option -n: 67108865 is not in [1, 67108864]");
  for (const char* bad : {"0", "67108865", "3000000000", "12abc", ""})  // out of range, of an int's range, not a number, empty
    expectRefusedNaming ([&] { count (bad); }, "-n", bad);
}

TEST (ToolOptions, NoSpacesNoHexadecimal)
{
  // strtod skips leading spaces and reads hexadecimal; neither is a number a user means on a command line.
  for (const char* bad : {" 5", "0x10"})
    expectRefusedNaming ([&] { count (bad); }, "-n", bad);
  expectRefusedNaming ([] { seed ("0X10"); }, "-seed", "0X10");
  for (const char* bad : {" 1.5", "0x1p3", "inf", "nan", "1.5 ", "1e400", "1e-400"})
    expectRefusedNaming ([&] { number (bad); }, "-x", bad);
  // Beyond a double: said so, not "not a number" (strtod reads 1e400 as infinity, with ERANGE).
  for (const char* far : {"1e400", "-1e400", "1e-400"})
    EXPECT_EQ (refusal ([&] { number (far); }), std::string ("option -x: ") + far + " is beyond what a double holds");
  EXPECT_EQ (refusal ([] { number ("-inf"); }), "option -x: '-inf' is not a number");
  // Read exactly as strtod reads them (the nearest double), not approximately.
  EXPECT_EQ (number ("1.5"), 1.5);
  EXPECT_EQ (number (".5"), 0.5);
  EXPECT_EQ (number ("-2e-3"), -2e-3);
  EXPECT_EQ (number ("+3"), 3.0);
  EXPECT_EQ (number ("0.1"), 0.1);
}

TEST (ToolOptions, AbsentOrRefusedLeavesTheValue)
{
  // Absent: false, the default untouched (a reader that wrote 0 into it turned every default off).
  std::vector<std::string> words = {"tool", "-x", "2.5"};
  std::vector<char*> argv;
  for (std::string& word : words)
    argv.push_back (&word[0]);
  const CommandLine args (static_cast<int> (argv.size ()), argv.data (), {"-seed", "-n", "-x"}, {});
  int n = 7;
  std::uint64_t s = 11;
  double x = 7.0;
  EXPECT_FALSE (args.integer ("-n", n, Range::closed (1, 10)));
  EXPECT_FALSE (args.integer ("-seed", s));
  EXPECT_EQ (n, 7);
  EXPECT_EQ (s, 11u);
  EXPECT_TRUE (args.number ("-x", x));
  EXPECT_EQ (x, 2.5);
  // Refused: the value as it was, whichever path (plain digits, another spelling, a non-number) refused it.
  for (const char* bad : {"11", "2e1", "1.5", "x"})
  {
    int value = 7;
    EXPECT_THROW (commandLine ("-n", bad).integer ("-n", value, Range::closed (1, 10)), Error) << bad;
    EXPECT_EQ (value, 7) << bad;
  }
  double value = 7.0;
  EXPECT_THROW (commandLine ("-x", "3").number ("-x", value, Range::closed (0.0, 1.0)), Error);
  EXPECT_EQ (value, 7.0);
  // The message names the option, the value and the range.
  EXPECT_EQ (refusal ([] {
               int value = 7;
               commandLine ("-n", "11").integer ("-n", value, Range::closed (1, 10));
             }),
             "option -n: 11 is not in [1, 10]");
  EXPECT_EQ (refusal ([] {
               double value = 7.0;
               commandLine ("-x", "0").number ("-x", value, Range::aboveUpTo (0.0, 90.0));
             }),
             "option -x: 0 is not in (0, 90]");
  // An infinite bound is open: no number given is infinite (pcl_sparse_resample "-density 0" said "(0, inf]").
  EXPECT_EQ (refusal ([] {
               double value = 7.0;
               commandLine ("-x", "0").number ("-x", value, Range::above (0.0));
             }),
             "option -x: 0 is not in (0, inf)");
  EXPECT_EQ (Range::atLeast (1.0).str (), "[1, inf)");
  EXPECT_EQ (Range ().str (), "(-inf, inf)");
}

namespace
{
  /// "tool -viewpoint TEXT" read by tools::parseViewpoint.
  Eigen::Vector3d
  viewpoint (const std::string& text)
  {
    std::vector<std::string> words = {"tool", "-viewpoint", text};
    std::vector<char*> argv;
    for (std::string& word : words)
      argv.push_back (&word[0]);
    const CommandLine args (static_cast<int> (argv.size ()), argv.data (), {"-viewpoint"}, {});
    Eigen::Vector3d v = Eigen::Vector3d::Constant (7.0);
    EXPECT_TRUE (pcl_sparse::tools::parseViewpoint (args, v));
    return v;
  }
} // namespace

TEST (ToolOptions, NumberListsAsStrictAsOneNumber)
{
  // Exact values: isApprox (relative to the norm, 300 here) let 1 read as 1.0000000001 pass.
  EXPECT_EQ (viewpoint ("1,2.5,-3e2"), Eigen::Vector3d (1.0, 2.5, -300.0));
  EXPECT_EQ (viewpoint ("+0,.5,-0"), Eigen::Vector3d (0.0, 0.5, 0.0));
  EXPECT_EQ (viewpoint ("0.1,-7,1e-30"), Eigen::Vector3d (0.1, -7.0, 1e-30));
  // Each item as -n or -rho: no spaces, no hexadecimal, finite; exactly three, nothing empty.
  for (const char* bad : {"1,2", "1,2,3,4", "1,2,3,", ",1,2,3", "1,,3", " 1,2,3", "1, 2,3", "0x1,2,3", "1,2,inf",
                          "1,nan,3", "1;2;3", "", "1,2,1e-400"})
    expectRefusedNaming ([&] { viewpoint (bad); }, "-viewpoint", bad);
  // The stages take floats (as pcl::Feature::setViewPoint): 1e300 became infinite inside them.
  EXPECT_NE (refusal ([] { viewpoint ("1e300,0,0"); }).find ("beyond what a float holds"), std::string::npos);
  EXPECT_NE (refusal ([] { viewpoint ("0,-3.5e38,0"); }).find ("beyond what a float holds"), std::string::npos);
  EXPECT_EQ (viewpoint ("3e38,0,0"), Eigen::Vector3d (3e38, 0.0, 0.0));
  // Without the option: false, and the viewpoint left as it was.
  std::vector<std::string> words = {"tool"};
  std::vector<char*> argv = {&words[0][0]};
  const CommandLine none (1, argv.data (), {"-viewpoint"}, {});
  Eigen::Vector3d unchanged (7.0, 8.0, 9.0);
  EXPECT_FALSE (pcl_sparse::tools::parseViewpoint (none, unchanged));
  EXPECT_EQ (unchanged, Eigen::Vector3d (7.0, 8.0, 9.0));
}

// -memory's sizes: K, M, G, T in powers of 1024, also written KB / KiB ("2GB" was not a size).
TEST (ToolOptions, ByteSizesWithOrWithoutB)
{
  using pcl_sparse::tools::parseByteSize;
  const std::uint64_t two_g = 2ull << 30;
  for (const char* text : {"2G", "2g", "2GB", "2GiB", "2gb", "2Gb"})
    EXPECT_EQ (parseByteSize ("-memory", text), two_g) << text;
  EXPECT_EQ (parseByteSize ("-memory", "1.5M"), 3ull << 19);
  EXPECT_EQ (parseByteSize ("-memory", "1TiB"), 1ull << 40);
  for (const char* text : {"2GBB", "2iB", "2B", "2 G", "G", "2X", "2GiBs"})
    EXPECT_NE (pcl_sparse_test::errorMessage ([&] { parseByteSize ("-memory", text); }).find ("is not a size"),
               std::string::npos)
      << text;
  EXPECT_NE (pcl_sparse_test::errorMessage ([&] { parseByteSize ("-memory", "512K"); }).find ("at least 1M"),
             std::string::npos);
}

TEST (ToolJson, InvalidUtf8BecomesReplacementCharacters)
{
  using pcl_sparse::tools::jsonString;
  // Valid UTF-8 passes through: 2-, 3- and 4-byte sequences.
  EXPECT_EQ (jsonString ("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x99\x82"), "\"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x99\x82\"");
  // A Latin-1 file name: the lone 0xe9 is not UTF-8.
  EXPECT_EQ (jsonString ("caf\xe9.ply"), "\"caf\\ufffd.ply\"");
  EXPECT_EQ (jsonString ("\xc0\xaf"), "\"\\ufffd\\ufffd\"");                // overlong '/'
  EXPECT_EQ (jsonString ("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");      // a UTF-16 surrogate
  EXPECT_EQ (jsonString ("\xf4\x90\x80\x80"), "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");  // past U+10FFFF
  EXPECT_EQ (jsonString ("a\xe2\x82"), "\"a\\ufffd\\ufffd\"");               // cut off at the end
  EXPECT_EQ (jsonString ("\xe2\x82x"), "\"\\ufffd\\ufffdx\"");               // cut off by an ASCII byte
  EXPECT_EQ (jsonString ("\xff"), "\"\\ufffd\"");
  // Quotes, backslashes and control characters as before.
  EXPECT_EQ (jsonString ("a\"b\\c\n"), "\"a\\\"b\\\\c\\u000a\"");
}

TEST (ToolJson, ObjectsOfEveryKind)
{
  using pcl_sparse::tools::JsonObject;
  JsonObject inner;
  inner.add ("k", 3);
  JsonObject object;
  object.add ("s", std::string ("a\"b"))
    .add ("c", "caf\xe9")
    .add ("t", true)
    .add ("f", false)
    .add ("n", std::int64_t (-9007199254740993))
    .add ("u", std::uint64_t (18446744073709551615ULL))
    .add ("d", 0.1)
    .add ("e", -2.5e-300)
    .add ("nan", std::numeric_limits<double>::quiet_NaN ())
    .add ("inf", -std::numeric_limits<double>::infinity ())
    .add ("list", std::vector<double>{1.0, std::numeric_limits<double>::infinity (), 1.0 / 3.0})
    .add ("empty", std::vector<double>{})
    .addSeconds ("sec", 1.23456789)
    .addSeconds ("never", std::numeric_limits<double>::quiet_NaN ())
    .add ("o", inner);
  // Doubles with 17 digits (they read back exactly), non-finite ones as null (JSON has no word for them),
  // integers with every digit, durations to the microsecond.
  EXPECT_EQ (object.str (),
             "{\"s\": \"a\\\"b\", \"c\": \"caf\\ufffd\", \"t\": true, \"f\": false, \"n\": -9007199254740993, "
             "\"u\": 18446744073709551615, \"d\": 0.10000000000000001, \"e\": -2.5e-300, \"nan\": null, "
             "\"inf\": null, \"list\": [1, null, 0.33333333333333331], \"empty\": [], \"sec\": 1.234568, "
             "\"never\": null, \"o\": {\"k\": 3}}");
  EXPECT_EQ (std::strtod ("0.33333333333333331", nullptr), 1.0 / 3.0);
  EXPECT_EQ (JsonObject ().str (), "{}");
}
