#include "tool_support.h"

#include <pcl_sparse/common/decimal_text.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>

#include <unistd.h>

namespace pcl_sparse
{
  namespace tools
  {
    bool
    hasExtension (const std::string& path, const std::string& extension)
    {
      if (path.size () <= extension.size ())
        return false;
      std::string tail = path.substr (path.size () - extension.size ());
      std::transform (tail.begin (), tail.end (), tail.begin (), [] (unsigned char c) { return std::tolower (c); });
      return tail == extension;
    }

    namespace
    {
      /// The length of the well-formed UTF-8 sequence (RFC 3629: no overlong forms, no surrogates, nothing
      /// past U+10FFFF) starting at \a text[i], a byte >= 0x80; 0 if none starts there.
      std::size_t
      utf8SequenceLength (const std::string& text, std::size_t i)
      {
        const auto byte = [&text] (std::size_t k) { return static_cast<unsigned char> (text[k]); };
        const unsigned char lead = byte (i);
        std::size_t length = 0;
        unsigned char low = 0x80, high = 0xbf;  // the allowed range of the second byte
        if (lead >= 0xc2 && lead <= 0xdf)
          length = 2;
        else if (lead >= 0xe0 && lead <= 0xef)
        {
          length = 3;
          low = lead == 0xe0 ? 0xa0 : 0x80;
          high = lead == 0xed ? 0x9f : 0xbf;
        }
        else if (lead >= 0xf0 && lead <= 0xf4)
        {
          length = 4;
          low = lead == 0xf0 ? 0x90 : 0x80;
          high = lead == 0xf4 ? 0x8f : 0xbf;
        }
        if (length == 0 || i + length > text.size () || byte (i + 1) < low || byte (i + 1) > high)
          return 0;
        for (std::size_t k = 2; k < length; ++k)
          if (byte (i + k) < 0x80 || byte (i + k) > 0xbf)
            return 0;
        return length;
      }
    } // namespace

    std::string
    jsonString (const std::string& text)
    {
      std::string out = "\"";
      for (std::size_t i = 0; i < text.size ();)
      {
        const unsigned char c = static_cast<unsigned char> (text[i]);
        if (c == '"' || c == '\\')
          out += std::string ("\\") + static_cast<char> (c);
        else if (c < 0x20)
        {
          char buffer[8];
          std::snprintf (buffer, sizeof (buffer), "\\u%04x", c);
          out += buffer;
        }
        else if (c >= 0x80)
        {
          const std::size_t length = utf8SequenceLength (text, i);
          out += length > 0 ? text.substr (i, length) : std::string ("\\ufffd");
          i += length > 0 ? length : 1;
          continue;
        }
        else
          out += static_cast<char> (c);
        ++i;
      }
      return out + "\"";
    }

    // ---- JsonObject --------------------------------------------------------------------------------

    namespace
    {
      /// A double as JSON: 17 significant digits (reads back exactly); null for NaN and infinity, which JSON
      /// has no words for.
      std::string
      jsonNumber (double value)
      {
        return std::isfinite (value) ? format ("%.17g", value) : "null";
      }
    } // namespace

    JsonObject&
    JsonObject::addRaw (const std::string& key, const std::string& json_value)
    {
      if (!members_.empty ())
        members_ += ", ";
      members_ += jsonString (key) + ": " + json_value;
      return *this;
    }

    JsonObject&
    JsonObject::add (const std::string& key, const std::string& value)
    {
      return addRaw (key, jsonString (value));
    }

    JsonObject&
    JsonObject::add (const std::string& key, const char* value)
    {
      return addRaw (key, jsonString (value ? value : ""));
    }

    JsonObject&
    JsonObject::add (const std::string& key, bool value)
    {
      return addRaw (key, value ? "true" : "false");
    }

    JsonObject&
    JsonObject::add (const std::string& key, double value)
    {
      return addRaw (key, jsonNumber (value));
    }

    JsonObject&
    JsonObject::addSeconds (const std::string& key, double seconds)
    {
      return addRaw (key, std::isfinite (seconds) ? format ("%.6f", seconds) : "null");
    }

    JsonObject&
    JsonObject::add (const std::string& key, const JsonObject& value)
    {
      return addRaw (key, value.str ());
    }

    JsonObject&
    JsonObject::add (const std::string& key, const std::vector<double>& values)
    {
      std::string array;
      for (double value : values)
        array += (array.empty () ? "" : ", ") + jsonNumber (value);
      return addRaw (key, "[" + array + "]");
    }

    std::string
    JsonObject::str () const
    {
      return "{" + members_ + "}";
    }

    void
    JsonObject::print () const
    {
      std::printf ("%s\n", str ().c_str ());
      std::fflush (stdout);
    }

    // ---- Range ---------------------------------------------------------------------------------------

    bool
    Range::contains (double x) const
    {
      const bool above_min = min_open ? x > min : x >= min;
      const bool below_max = max_open ? x < max : x <= max;
      return above_min && below_max;
    }

    std::string
    Range::str () const
    {
      // An infinite bound is shown open: the number parser takes no "inf" ("-density 0" said "(0, inf]", and
      // "-density inf" was "not a number").
      return std::string (min_open || std::isinf (min) ? "(" : "[") + shortestDecimal (min) + ", " +
             shortestDecimal (max) + (max_open || std::isinf (max) ? ")" : "]");
    }

    // ---- CommandLine ---------------------------------------------------------------------------------

    CommandLine::CommandLine (int argc, char** argv, const std::vector<OptionSpec>& options,
                              const std::vector<std::string>& switches)
    {
      for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        const auto option = std::find_if (options.begin (), options.end (),
                                          [&] (const OptionSpec& o) { return o.name == arg; });
        if (option != options.end ())
        {
          if (i + option->values >= argc)
            throw Error ("option " + arg + (option->values == 1 ? std::string (" needs a value")
                                                                : " needs " + std::to_string (option->values) +
                                                                    " values"));
          if (has (arg))  // the first value won, silently: "-o a.psm -o b.psm" never wrote b.psm
            throw Error ("option " + arg + " given twice");
          for (int k = 1; k <= option->values; ++k)
            if (argv[i + k][0] == '\0')  // "-o ''" wrote nothing, silently
              throw Error ("option " + arg + " has an empty value");
          given_.emplace_back (arg, std::vector<std::string> (argv + i + 1, argv + i + 1 + option->values));
          i += option->values;
          continue;
        }
        if (arg == "-h" || arg == "--help" || std::find (switches.begin (), switches.end (), arg) != switches.end ())
        {
          given_.emplace_back (arg, std::vector<std::string> ());
          continue;
        }
        if (arg.size () > 1 && arg[0] == '-')
          throw Error ("unknown option '" + arg + "' (see --help)");
        positional_.push_back (arg);
      }
    }

    void
    CommandLine::expectPositional (std::size_t count, const std::string& names) const
    {
      if (positional_.size () != count)
        throw Error ("expected " + names + ", got " + std::to_string (positional_.size ()) +
                     " file arguments (see --help)");
    }

    bool
    CommandLine::has (const std::string& name) const
    {
      return std::any_of (given_.begin (), given_.end (), [&] (const auto& g) { return g.first == name; });
    }

    std::vector<std::string>
    CommandLine::values (const std::string& name) const
    {
      for (const auto& g : given_)
        if (g.first == name)
          return g.second;
      return {};
    }

    std::string
    CommandLine::value (const std::string& name, const std::string& fallback) const
    {
      const std::vector<std::string> v = values (name);
      return v.empty () ? fallback : v.front ();
    }

    namespace
    {
      enum class Decimal { Number, Malformed, OutOfRange };

      /// \a text as a finite decimal number: strtod also skips leading spaces and reads hexadecimal ("0x10"),
      /// neither of which is a number of ours; 1e-320 and 1e400 are beyond a double (ERANGE).
      Decimal
      readDecimal (const std::string& text, double& x)
      {
        char* end = nullptr;
        errno = 0;
        x = std::strtod (text.c_str (), &end);
        const bool decimal = !text.empty () && (std::isdigit (static_cast<unsigned char> (text[0])) ||
                                                text[0] == '-' || text[0] == '+' || text[0] == '.') &&
                             text.find_first_of ("xX") == std::string::npos;
        if (!decimal || end != text.c_str () + text.size ())
          return Decimal::Malformed;
        if (errno == ERANGE)  // before the finiteness check: 1e400 reads as infinity and was "not a number"
          return Decimal::OutOfRange;
        return std::isfinite (x) ? Decimal::Number : Decimal::Malformed;
      }
    } // namespace

    bool
    CommandLine::number (const std::string& name, double& value, const Range& range) const
    {
      if (!has (name))
        return false;
      const std::string text = this->value (name);
      double x = 0.0;
      const Decimal read = readDecimal (text, x);
      if (read == Decimal::Malformed)
        throw Error ("option " + name + ": '" + text + "' is not a number");
      if (read == Decimal::OutOfRange)  // 1e-320 was "not a number"
        throw Error ("option " + name + ": " + text + " is beyond what a double holds");
      checkRange (name, x, range);
      value = x;
      return true;
    }

    bool
    CommandLine::numbers (const std::string& name, std::size_t count, const std::string& expected,
                          std::vector<double>& values) const
    {
      if (!has (name))
        return false;
      const std::string text = this->value (name);
      std::vector<double> read;
      std::size_t at = 0;
      while (read.size () <= count)
      {
        const std::size_t comma = std::min (text.find (',', at), text.size ());
        double x = 0.0;
        if (readDecimal (text.substr (at, comma - at), x) != Decimal::Number)
          break;
        read.push_back (x);
        if (comma == text.size ())
        {
          if (read.size () != count)
            break;
          values = std::move (read);
          return true;
        }
        at = comma + 1;
      }
      throw Error ("option " + name + ": expected " + expected + ", got '" + text + "'");
    }

    void
    CommandLine::checkRange (const std::string& name, double x, const Range& range) const
    {
      if (!range.contains (x))
        throw Error ("option " + name + ": " + value (name) + " is not in " + range.str ());
    }

    bool
    CommandLine::angle (const std::string& name, double& radians, const Range& degrees) const
    {
      double x = 0.0;
      if (!number (name, x, degrees))
        return false;
      radians = x * M_PI / 180.0;
      return true;
    }

    void
    CommandLine::checkInteger (const std::string& name, double x, double lowest, double limit) const
    {
      if (x != std::floor (x) || x < lowest || x >= limit)
        throw Error ("option " + name + ": '" + value (name) + "' is not an integer" +
                     (x == std::floor (x) ? " of this size" : ""));
      if (std::fabs (x) > std::ldexp (1.0, 53))  // 1.8446744073709551e19 names many integers: ask for digits
        throw Error ("option " + name + ": '" + value (name) + "' is beyond what a double holds exactly; " +
                     "write the integer in plain digits");
    }

    // ---- help, main ----------------------------------------------------------------------------------

    void
    printHelp (const char* argv0, const ToolDescription& tool)
    {
      pcl::console::print_error ("Syntax is: %s %s\n", argv0, tool.syntax.c_str ());
      std::size_t width = 0;
      for (const HelpLine& line : tool.help)
        width = std::max (width, line.name.size ());
      for (const HelpLine& line : tool.help)
        pcl::console::print_info ("  %-*s  %s\n", static_cast<int> (width), line.name.c_str (),
                                  line.description.c_str ());
    }

    void
    printNote (const std::string& text)
    {
      if (pcl::console::isVerbosityLevelEnabled (pcl::console::L_INFO))
        std::fprintf (stderr, "%s\n", text.c_str ());
    }

    std::string
    format (const char* pattern, ...)
    {
      va_list args;
      va_start (args, pattern);
      va_list copy;
      va_copy (copy, args);
      const int size = std::vsnprintf (nullptr, 0, pattern, copy);
      va_end (copy);
      std::string text (size > 0 ? static_cast<std::size_t> (size) : 0, '\0');
      if (size > 0)
        std::vsnprintf (&text[0], text.size () + 1, pattern, args);
      va_end (args);
      return text;
    }

    namespace
    {
      /// Whether two paths name one file: the same file when both exist, else the same normalised path.
      bool
      sameFile (const std::string& a, const std::string& b)
      {
        namespace fs = std::filesystem;
        std::error_code ec;
        if (fs::exists (a, ec) && fs::exists (b, ec))
          return fs::equivalent (a, b, ec);
        const fs::path pa = fs::weakly_canonical (a, ec), pb = fs::weakly_canonical (b, ec);
        return ec ? fs::path (a).lexically_normal () == fs::path (b).lexically_normal () : pa == pb;
      }

      /// Throws unless a file can be created in \a folder, the folder of output \a out. A real file is created
      /// and removed: access (W_OK) says yes to root in a read-only or immutable (chattr +i) folder.
      void
      checkFolderTakesFiles (const std::string& out, const std::filesystem::path& folder)
      {
        std::string probe = (folder / ".pcl_sparse_write_check_XXXXXX").string ();
        const int fd = ::mkstemp (&probe[0]);
        if (fd < 0)
        {
          const std::string reason = std::strerror (errno);
          throw Error ("output '" + out + "': cannot write in the folder '" + folder.string () + "' (" + reason + ")");
        }
        ::close (fd);
        std::remove (probe.c_str ());
      }

      /// The outputs this run has written (removeIfRunFails), removed by runTool when the run fails.
      std::vector<std::string>&
      writtenOutputs ()
      {
        static std::vector<std::string> paths;
        return paths;
      }

      /// Removes the outputs this run has written: after a failure, none of them is the whole answer.
      void
      removeWrittenOutputs ()
      {
        for (const std::string& path : writtenOutputs ())
          std::remove (path.c_str ());
        writtenOutputs ().clear ();
      }
    } // namespace

    void
    removeIfRunFails (const std::string& path)
    {
      writtenOutputs ().push_back (path);
    }

    void
    checkOutputPaths (const std::vector<std::string>& inputs, const std::vector<std::string>& outputs)
    {
      namespace fs = std::filesystem;
      for (std::size_t k = 0; k < outputs.size (); ++k)
      {
        const std::string& out = outputs[k];
        if (out.empty ())
          continue;
        std::error_code ec;
        if (fs::is_directory (out, ec))
          throw Error ("output '" + out + "' is a folder");
        const fs::path folder = fs::path (out).parent_path ();
        if (!folder.empty () && !fs::is_directory (folder, ec))
          throw Error ("output '" + out + "': the folder '" + folder.string () + "' does not exist");
        checkFolderTakesFiles (out, folder.empty () ? fs::path (".") : folder);
        for (const std::string& in : inputs)
          if (!in.empty () && sameFile (in, out))
            throw Error ("output '" + out + "' is the input '" + in + "': refusing to overwrite it");
        for (std::size_t j = 0; j < k; ++j)
          if (!outputs[j].empty () && sameFile (outputs[j], out))
            throw Error ("two outputs are the same file '" + out + "'");
      }
    }

    int
    runTool (int argc, char** argv, const ToolDescription& tool, const std::function<int (const CommandLine&)>& body)
    {
      for (int i = 1; i < argc; ++i)
        if (std::string (argv[i]) == "-h" || std::string (argv[i]) == "--help")
        {
          printHelp (argv[0], tool);
          return 0;
        }
      if (argc - 1 < tool.min_arguments)
      {
        printHelp (argv[0], tool);
        return 1;
      }
      try
      {
        const int status = body (CommandLine (argc, argv, tool.options, tool.switches));
        // A report or JSON object lost to a full disk or a closed pipe is a failure (it exited 0).
        if (std::fflush (stdout) != 0 || std::ferror (stdout))
          throw Error ("cannot write to standard output");
        if (status != 0)
          removeWrittenOutputs ();
        return status;
      }
      catch (const Error& e)
      {
        pcl::console::print_error ("%s: %s\n", tool.program, e.what ());
      }
      catch (const std::exception& e)
      {
        pcl::console::print_error ("%s: unexpected failure: %s\n", tool.program, e.what ());
      }
      removeWrittenOutputs ();
      return 1;
    }
  } // namespace tools
} // namespace pcl_sparse
