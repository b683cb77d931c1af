#pragma once
/// \file mesh_readers.h
/// Internal to src/io: the per-format readers behind loadTriangleMesh and the small text-scanning helpers
/// they share. Every reader works on the whole file in memory and throws pcl_sparse::Error with messages
/// that start with the file path.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace io_detail
  {
    /// Refuses a missing file, a directory, something that is not a regular file, an empty file.
    void
    checkReadableFile (const std::string& path);

    /// Reads the whole file; refuses a missing file, a directory, an unreadable or empty file.
    std::string
    readWholeFile (const std::string& path);

    /// Lower-case extension with the dot (".ply"), or "" when there is none.
    std::string
    lowerCaseExtension (const std::string& path);

    /// Refuses data containing NUL bytes (binary data in a text format).
    void
    requireText (const std::string& data, const std::string& path, const char* format);

    /// Dispatches on the extension and reads the file with the format's reader: every check of the format,
    /// but none of loadTriangleMesh's checks on the result (empty, no faces, non-finite).
    TriangleMesh
    readMeshFile (const std::string& path);

    /// Format readers: fill \a mesh with every vertex of the file and the fan-triangulated faces, and
    /// check face indices. Non-finite coordinates and empty results are checked by the caller.
    void
    readObj (const std::string& data, const std::string& path, TriangleMesh& mesh);
    void
    readOff (const std::string& data, const std::string& path, TriangleMesh& mesh);
    void
    readPly (const std::string& data, const std::string& path, TriangleMesh& mesh);
    void
    readStl (const std::string& data, const std::string& path, TriangleMesh& mesh);

    /// A cursor over text with line counting, for error messages "file:line: problem".
    struct TextCursor
    {
      const char* p;
      const char* end;
      std::size_t line = 1;

      TextCursor (const std::string& data) : p (data.data ()), end (data.data () + data.size ()) {}

      static bool
      isBlank (char c)
      {
        return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
      }

      /// Skips spaces and tabs (and the CR of CRLF) but not the end of the line.
      void
      skipBlanks ()
      {
        while (p < end && isBlank (*p))
          ++p;
      }

      /// Moves past the next newline (or to the end).
      void
      skipLine ()
      {
        const void* nl = std::memchr (p, '\n', static_cast<std::size_t> (end - p));
        if (nl)
        {
          p = static_cast<const char*> (nl) + 1;
          ++line;
        }
        else
          p = end;
      }

      /// True at the end of the current line (newline, end of data, or a '#' comment).
      bool
      atLineEnd ()
      {
        skipBlanks ();
        return p == end || *p == '\n' || *p == '#';
      }

      /// Skips whitespace, newlines and '#' comments up to the next token; false at the end of data.
      bool
      skipToToken ()
      {
        while (p < end)
        {
          if (isBlank (*p))
            ++p;
          else if (*p == '\n')
          {
            ++p;
            ++line;
          }
          else if (*p == '#')
            skipLine ();
          else
            return true;
        }
        return false;
      }

      /// True if the next character ends a number token.
      bool
      atDelimiter () const
      {
        return p == end || isBlank (*p) || *p == '\n' || *p == '#';
      }

      /// Parses a double at p (a leading '+' is allowed, unlike std::from_chars); false if there is none.
      bool
      parseDouble (double& value)
      {
        const char* q = p;
        if (q < end && *q == '+')
          ++q;
        const auto result = std::from_chars (q, end, value);
        if (result.ec == std::errc::result_out_of_range)
        {
          // Over- or underflow: take strtod's answer (+-HUGE_VAL or a denormal/zero) on a copy of the whole
          // token (a copy cut short drops the exponent: 1.000...0e999 of 76 characters read as 1).
          const std::string token (q, result.ptr);
          value = std::strtod (token.c_str (), nullptr);
        }
        else if (result.ec != std::errc ())
          return false;
        p = result.ptr;
        return true;
      }

      /// Parses a signed integer at p (a leading '+' is allowed); false if there is none or it overflows.
      bool
      parseInteger (long long& value)
      {
        const char* q = p;
        if (q < end && *q == '+')
          ++q;
        const auto result = std::from_chars (q, end, value);
        if (result.ec != std::errc ())
          return false;
        p = result.ptr;
        return true;
      }

      /// The text of the token at p (up to 20 characters), for error messages.
      std::string
      tokenForMessage () const
      {
        const char* q = p;
        while (q < end && q - p < 20 && !isBlank (*q) && *q != '\n')
          ++q;
        std::string token (p, q);
        for (char& c : token)
          if (static_cast<unsigned char> (c) < 32 || static_cast<unsigned char> (c) >= 127)
            c = '?';
        return token.empty () ? std::string ("end of line") : "'" + token + "'";
      }
    };

    /// Builds "path:line: message".
    inline std::string
    atLine (const std::string& path, std::size_t line, const std::string& message)
    {
      return path + ":" + std::to_string (line) + ": " + message;
    }
  } // namespace io_detail
} // namespace pcl_sparse
