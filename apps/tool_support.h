#pragma once
/// \file tool_support.h
/// What the command-line tools share: the command line (positional arguments, switches, options with
/// checked numeric values), the help text, a JSON object writer, extension checks and the main wrapper
/// that turns an exception into one error line and exit code 1. Not part of the library API.

#include <pcl_sparse/common/error.h>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  namespace tools
  {
    /// True if \a path ends in \a extension (given with its dot, lower case), in any case, after at
    /// least one other character.
    bool
    hasExtension (const std::string& path, const std::string& extension);

    /// \a text as a JSON string literal, quotes included; quotes, backslashes and control characters escaped,
    /// and each byte that is not part of valid UTF-8 (a file name in Latin-1, say) written as U+FFFD, since
    /// JSON text must be UTF-8.
    std::string
    jsonString (const std::string& text);

    /// One JSON object on one line, keys in insertion order: `{"key": value, ...}`. Doubles are written
    /// with 17 significant digits (they read back exactly), durations with addSeconds to the microsecond,
    /// non-finite numbers as null.
    class JsonObject
    {
    public:
      JsonObject& add (const std::string& key, const std::string& value);
      JsonObject& add (const std::string& key, const char* value);
      JsonObject& add (const std::string& key, bool value);
      JsonObject& add (const std::string& key, double value);
      JsonObject& add (const std::string& key, const JsonObject& value);
      /// A JSON array of numbers (as add (key, double) writes each).
      JsonObject& add (const std::string& key, const std::vector<double>& values);

      /// Any integer type except bool.
      template <typename Integer>
      std::enable_if_t<std::is_integral<Integer>::value && !std::is_same<Integer, bool>::value, JsonObject&>
      add (const std::string& key, Integer value)
      {
        return addRaw (key, std::to_string (value));
      }

      /// A duration in seconds, six decimals.
      JsonObject& addSeconds (const std::string& key, double seconds);

      /// The object as text, without a newline.
      std::string str () const;

      /// Prints the object and a newline on stdout.
      void print () const;

    private:
      JsonObject& addRaw (const std::string& key, const std::string& json_value);
      std::string members_;
    };

    /// An interval of accepted option values; bounds may be open and infinite.
    struct Range
    {
      double min = -std::numeric_limits<double>::infinity ();
      double max = std::numeric_limits<double>::infinity ();
      bool min_open = false;
      bool max_open = false;

      static Range closed (double a, double b) { return {a, b, false, false}; }
      static Range atLeast (double a) { return {a, std::numeric_limits<double>::infinity (), false, false}; }
      static Range above (double a) { return {a, std::numeric_limits<double>::infinity (), true, false}; }
      /// (a, b]
      static Range aboveUpTo (double a, double b) { return {a, b, true, false}; }
      /// (a, b)
      static Range open (double a, double b) { return {a, b, true, true}; }

      bool contains (double x) const;
      /// "[0, 1]", "(0, inf)", ...
      std::string str () const;
    };

    /// An option taking values: its name and how many arguments follow it.
    struct OptionSpec
    {
      OptionSpec (const char* option_name, int value_count = 1) : name (option_name), values (value_count) {}
      std::string name;
      int values;
    };

    /// The arguments of a tool, checked on construction: every argument starting with '-' must be a
    /// known switch (-h and --help always are) or a known option followed by its values; anything else
    /// is positional. Errors (unknown option, missing value) are thrown as Error naming the option.
    class CommandLine
    {
    public:
      CommandLine (int argc, char** argv, const std::vector<OptionSpec>& options,
                   const std::vector<std::string>& switches);

      const std::vector<std::string>& positional () const { return positional_; }

      /// Throws unless there are exactly \a count positional arguments; \a names says which ("MESH and OUT").
      void expectPositional (std::size_t count, const std::string& names) const;

      /// True if switch or option \a name is on the command line.
      bool has (const std::string& name) const;

      /// The (first) value of option \a name, \a fallback when absent.
      std::string value (const std::string& name, const std::string& fallback = std::string ()) const;

      /// All values of option \a name (empty when absent).
      std::vector<std::string> values (const std::string& name) const;

      /// Reads option \a name as a finite decimal number in \a range into \a value (no spaces, no hexadecimal);
      /// false (value untouched) when absent. Throws Error naming the option when the value is malformed or out of range.
      bool number (const std::string& name, double& value, const Range& range = Range ()) const;

      /// Reads option \a name as exactly \a count numbers separated by commas ("1,2.5,-3"), each as number reads
      /// one (decimal, finite, no spaces); false (\a values untouched) when absent. Throws Error naming the
      /// option and quoting its value, with \a expected ("X,Y,Z (three numbers)") saying what was wanted.
      bool numbers (const std::string& name, std::size_t count, const std::string& expected, std::vector<double>& values) const;

      /// Reads option \a name, an angle in degrees within \a degrees, into \a radians (radians untouched
      /// when absent). Throws as number.
      bool angle (const std::string& name, double& radians, const Range& degrees = Range::aboveUpTo (0.0, 180.0)) const;

      /// As number, and the value must be a whole number that \a Integer holds. Plain decimal digits (with a
      /// '-' for signed types) are read exactly, so a 64-bit seed keeps every digit; other spellings of a
      /// number (1e6) are accepted while a double holds them exactly (up to 2^53).
      template <typename Integer>
      bool
      integer (const std::string& name, Integer& value, const Range& range = Range ()) const
      {
        if (!has (name))
          return false;
        const std::string text = this->value (name);
        Integer parsed = 0;
        const std::from_chars_result digits = std::from_chars (text.data (), text.data () + text.size (), parsed);
        if (digits.ec == std::errc () && digits.ptr == text.data () + text.size ())
        {
          checkRange (name, static_cast<double> (parsed), range);
          value = parsed;
          return true;
        }
        double x = 0.0;
        number (name, x, range);
        // 2^digits is exact as a double, unlike the largest value of a 64-bit type.
        checkInteger (name, x, static_cast<double> (std::numeric_limits<Integer>::lowest ()),
                      std::ldexp (1.0, std::numeric_limits<Integer>::digits));
        value = static_cast<Integer> (x);
        return true;
      }

    private:
      /// Throws unless \a x is a whole number in [lowest, limit) that a double holds exactly (|x| <= 2^53).
      void checkInteger (const std::string& name, double x, double lowest, double limit) const;
      /// Throws unless \a range contains \a x.
      void checkRange (const std::string& name, double x, const Range& range) const;

      std::vector<std::string> positional_;
      std::vector<std::pair<std::string, std::vector<std::string>>> given_;  ///< options and switches in order
    };

    /// One line of a tool's help: an argument or option and what it does (an empty name continues the
    /// description of the line above).
    struct HelpLine
    {
      std::string name;
      std::string description;
    };

    /// What a tool is called, its help and its command line.
    struct ToolDescription
    {
      const char* program;                 ///< name at the start of error lines
      std::string syntax;                  ///< the arguments in "Syntax is: PROGRAM SYNTAX"
      std::vector<HelpLine> help;          ///< arguments and options, one line each
      int min_arguments;                   ///< with fewer arguments the tool prints its help and exits with 1
      std::vector<OptionSpec> options;     ///< options taking values
      std::vector<std::string> switches;   ///< options without values (-h and --help are implicit)
    };

    /// Refuses, before any work, outputs that would overwrite an input or another output (the same file,
    /// also through another spelling or a link: "-o c.obj" over the input c.obj replaced the mesh), that are
    /// a folder, or whose folder does not exist or takes no new file (read-only, immutable, not ours: all
    /// found only after an encode of hours). Empty paths are skipped (options not given).
    void
    checkOutputPaths (const std::vector<std::string>& inputs, const std::vector<std::string>& outputs);

    /// Records that this run has written the output \a path (complete, renamed into place), so that runTool
    /// removes it if the run fails afterwards: a tool that fails leaves no output, not the ones written before
    /// a later one failed. Called by the helpers that finish writing an output.
    void
    removeIfRunFails (const std::string& path);

    /// Prints "Syntax is: PROGRAM SYNTAX" on stderr (one error line when the tool is called wrongly) and
    /// the aligned help lines on stdout, as PCL's tools do.
    void
    printHelp (const char* argv0, const ToolDescription& tool);

    /// Prints one note about the input (what the tool did to it) on stderr, so that --json's stdout stays
    /// one JSON object; nothing when PCL's notes are off (the tools turn them off with -q and --json).
    void
    printNote (const std::string& text);

    /// printf-style formatting into a string (for help lines showing defaults).
    std::string
    format (const char* pattern, ...) __attribute__ ((format (printf, 1, 2)));

    /// The whole main of a tool: prints the help and returns 0 for -h / --help, returns 1 after the help
    /// when there are too few arguments; otherwise parses the command line and runs \a body with it. An
    /// Error or any other exception (from parsing or the body) becomes one line "PROGRAM: message" on
    /// stderr and exit code 1; otherwise the body's exit code is returned. On any failure (also a non-zero
    /// exit code, or stdout that cannot be written) the outputs given to removeIfRunFails are removed.
    int
    runTool (int argc, char** argv, const ToolDescription& tool, const std::function<int (const CommandLine&)>& body);
  } // namespace tools
} // namespace pcl_sparse
