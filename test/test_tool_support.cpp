// What the tools share (apps/tool_support.h): option values read exactly, and JSON that stays valid UTF-8.

#include <gtest/gtest.h>

#include "tool_input.h"
#include "tool_support.h"

#include <cstdint>
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
} // namespace

TEST (ToolOptions, SixtyFourBitSeedsKeepEveryDigit)
{
  // Read through a double, 2^53 + 1 was 2^53 and the largest seed was refused as too big.
  EXPECT_EQ (seed ("9007199254740993"), 9007199254740993ULL);
  EXPECT_EQ (seed ("18446744073709551615"), 18446744073709551615ULL);
  EXPECT_EQ (seed ("0"), 0u);
  EXPECT_THROW (seed ("18446744073709551616"), Error);  // one past the largest
  EXPECT_THROW (seed ("-1"), Error);
  EXPECT_THROW (seed ("1.5"), Error);
}

TEST (ToolOptions, OtherSpellingsOnlyWhileExact)
{
  EXPECT_EQ (count ("1e6"), 1000000);
  EXPECT_EQ (count ("2.0e3"), 2000);
  EXPECT_EQ (seed ("4.5e15"), 4500000000000000ULL);
  // 1e17 as a double stands for many integers: the digits must be written out.
  EXPECT_THROW (seed ("1e17"), Error);
  EXPECT_EQ (seed ("100000000000000000"), 100000000000000000ULL);
  EXPECT_THROW (count ("0"), Error);          // out of range
  EXPECT_THROW (count ("67108865"), Error);   // out of range
  EXPECT_THROW (count ("3000000000"), Error); // out of an int's range
  EXPECT_THROW (count ("12abc"), Error);
  EXPECT_THROW (count (""), Error);
}

TEST (ToolOptions, NoSpacesNoHexadecimal)
{
  // strtod skips leading spaces and reads hexadecimal; neither is a number a user means on a command line.
  EXPECT_THROW (count (" 5"), Error);
  EXPECT_THROW (count ("0x10"), Error);
  EXPECT_THROW (seed ("0X10"), Error);
  EXPECT_THROW (number (" 1.5"), Error);
  EXPECT_THROW (number ("0x1p3"), Error);
  EXPECT_THROW (number ("inf"), Error);
  EXPECT_THROW (number ("nan"), Error);
  EXPECT_THROW (number ("1.5 "), Error);
  EXPECT_DOUBLE_EQ (number ("1.5"), 1.5);
  EXPECT_DOUBLE_EQ (number (".5"), 0.5);
  EXPECT_DOUBLE_EQ (number ("-2e-3"), -2e-3);
  EXPECT_DOUBLE_EQ (number ("+3"), 3.0);
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
  EXPECT_TRUE (viewpoint ("1,2.5,-3e2").isApprox (Eigen::Vector3d (1.0, 2.5, -300.0)));
  EXPECT_TRUE (viewpoint ("+0,.5,-0").isApprox (Eigen::Vector3d (0.0, 0.5, 0.0)));
  // Each item as -n or -rho: no spaces, no hexadecimal, finite; exactly three, nothing empty.
  for (const char* bad : {"1,2", "1,2,3,4", "1,2,3,", ",1,2,3", "1,,3", " 1,2,3", "1, 2,3", "0x1,2,3", "1,2,inf",
                          "1,nan,3", "1;2;3", "", "1,2,1e-400"})
    EXPECT_THROW (viewpoint (bad), Error) << "'" << bad << "'";
  // The stages take floats (as pcl::Feature::setViewPoint): 1e300 became infinite inside them.
  EXPECT_THROW (viewpoint ("1e300,0,0"), Error);
  EXPECT_NO_THROW (viewpoint ("3e38,0,0"));
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
