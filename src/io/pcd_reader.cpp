/// PCD input: our strict header check, then PCL's reader into a raw PCLPointCloud2 (any field types).

#include "cloud_readers.h"
#include "mesh_readers.h"

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <locale>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace pcl_sparse
{
  namespace io_detail
  {
    namespace
    {
      /// VIEWPOINT as PCL's reader takes it: origin x y z, then the quaternion w x y z, seven floats (PCL
      /// refuses the file otherwise, so we do too, with a clearer message).
      void
      readViewpoint (const std::vector<std::string>& values, const std::string& path, PcdHeader& header)
      {
        float v[7];
        for (std::size_t k = 0; k < 7; ++k)
        {
          std::istringstream token (k < values.size () ? values[k] : std::string ());
          token.imbue (std::locale::classic ());
          if (values.size () != 7 || !(token >> v[k]) || !(token >> std::ws).eof ())
            throw Error (path + ": bad PCD VIEWPOINT line (seven numbers expected)");
        }
        header.sensor_origin = Eigen::Vector4f (v[0], v[1], v[2], 0.0f);
        header.sensor_orientation = Eigen::Quaternionf (v[3], v[4], v[5], v[6]);
      }
    } // namespace

    PcdHeader
    readPcdHeader (const std::string& path)
    {
      std::FILE* file = std::fopen (path.c_str (), "rb");
      if (!file)
        throw Error (path + ": cannot open the file");
      std::string head (65536, '\0');
      head.resize (std::fread (&head[0], 1, head.size (), file));
      std::fseek (file, 0, SEEK_END);
      const long file_size = std::ftell (file);
      std::fclose (file);

      std::map<std::string, std::vector<std::string>> header;
      std::size_t position = 0;
      std::string data_kind;
      while (data_kind.empty ())
      {
        const std::size_t nl = head.find ('\n', position);
        if (nl == std::string::npos)
          throw Error (path + ": not a PCD file (no complete header with a DATA line)");
        // PCL's reader skips only empty lines: a line of blanks (" ", the "\r" of CRLF) ends its header there,
        // without fields, and it then crashed on the data (found by bench/fuzz.sh inputs).
        if (nl > position && head.find_first_not_of (" \t\r\v\f", position) >= nl)
          throw Error (path + ": not a readable PCD file (a blank line in its header, where PCL's reader ends it)");
        std::istringstream line (head.substr (position, nl - position));
        position = nl + 1;
        std::string keyword;
        if (!(line >> keyword) || keyword[0] == '#')
          continue;
        std::vector<std::string> values;
        for (std::string value; line >> value;)
          values.push_back (value);
        static const std::set<std::string> known = {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT",
                                                    "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
        if (!known.count (keyword))
          throw Error (path + ": not a PCD file (unknown header line)");
        if (keyword == "DATA")
          data_kind = values.empty () ? "?" : values[0];
        header[keyword == "COLUMNS" ? "FIELDS" : keyword] = values;
      }
      const std::vector<std::string>& fields = header["FIELDS"];
      const std::vector<std::string>& sizes = header["SIZE"];
      const std::vector<std::string>& types = header["TYPE"];
      std::vector<std::string> counts = header["COUNT"];
      if (counts.empty ())
        counts.assign (fields.size (), "1");
      if (fields.empty () || sizes.size () != fields.size () || types.size () != fields.size () ||
          counts.size () != fields.size ())
        throw Error (path + ": bad PCD header (FIELDS, SIZE, TYPE, COUNT disagree)");
      const auto number = [&] (const std::string& text, long long max) {
        long long value = -1;
        const auto result = std::from_chars (text.data (), text.data () + text.size (), value);
        if (result.ec != std::errc () || result.ptr != text.data () + text.size () || value < 0 || value > max)
          throw Error (path + ": bad PCD header value '" + text.substr (0, 20) + "'");
        return value;
      };
      PcdHeader result;
      long long point_size = 0;
      for (std::size_t i = 0; i < fields.size (); ++i)
      {
        const long long size = number (sizes[i], 8);
        if ((size != 1 && size != 2 && size != 4 && size != 8) ||
            (types[i] != "I" && types[i] != "U" && types[i] != "F"))
          throw Error (path + ": bad PCD field type for '" + fields[i] + "'");
        const long long count = number (counts[i], 1 << 20);
        // The layout PCL's reader gives: fields packed in header order, those of COUNT 0 removed.
        pcl::PCLPointField field;
        field.name = fields[i];
        field.offset = static_cast<std::uint32_t> (point_size);
        field.datatype = pcl::getFieldType (static_cast<int> (size), types[i][0]);
        field.count = static_cast<std::uint32_t> (count);
        if (count > 0)
          result.layout.fields.push_back (field);
        point_size += size * count;
      }
      for (const char* name : {"x", "y", "z"})
        if (std::find (fields.begin (), fields.end (), name) == fields.end ())
          throw Error (path + ": the PCD file has no x, y, z fields");
      if (header["WIDTH"].size () != 1 || header["HEIGHT"].size () != 1)
        throw Error (path + ": bad PCD header (WIDTH/HEIGHT)");
      // 32 bits each in PCL's cloud (2^32 was taken as 0); their product overflowed (2^32 x 2^32 gave 0 points).
      const long long width = number (header["WIDTH"][0], 0xffffffffll), height = number (header["HEIGHT"][0], 0xffffffffll);
      if (width > 0 && height > (1ll << 62) / width)
        throw Error (path + ": bad PCD header (WIDTH x HEIGHT = " + std::to_string (width) + " x " +
                     std::to_string (height) + " points)");
      const long long points = width * height;
      if (header.count ("POINTS") && (header["POINTS"].size () != 1 || number (header["POINTS"][0], 1ll << 62) != points))
        throw Error (path + ": bad PCD header (POINTS is not WIDTH * HEIGHT)");
      const long long remaining = file_size - static_cast<long long> (position);
      if (data_kind == "binary")
      {
        if (points > remaining / std::max (1ll, point_size) + 1 || points * point_size > remaining)
          throw Error (path + ": truncated PCD data (" + std::to_string (points) + " points of " +
                       std::to_string (point_size) + " bytes announced, " + std::to_string (remaining) + " bytes left)");
      }
      else if (data_kind == "ascii")
      {
        if (points > remaining)  // every point needs at least one character
          throw Error (path + ": truncated PCD data (" + std::to_string (points) + " points announced)");
      }
      else if (data_kind == "binary_compressed")
      {
        if (remaining < 8)
          throw Error (path + ": truncated PCD data");
      }
      else
        throw Error (path + ": unknown PCD DATA kind '" + data_kind.substr (0, 20) + "'");

      result.layout.width = static_cast<std::uint32_t> (width);
      result.layout.height = static_cast<std::uint32_t> (height);
      result.layout.point_step = static_cast<std::uint32_t> (point_size);
      result.layout.row_step = result.layout.point_step * result.layout.width;
      result.data_kind = data_kind;
      result.data_offset = position;
      if (header.count ("VIEWPOINT"))
        readViewpoint (header["VIEWPOINT"], path, result);
      return result;
    }

    namespace
    {
      /// Whether PCL's reader would take the first lines after the DATA line for header lines. Its header
      /// loop goes on after DATA while lines are empty, comments or start with a keyword (prefix match), and
      /// such a line in the data re-sizes the cloud it then fills from the file: a SIZE or POINTS line there
      /// made it copy past its buffer (found by bench/fuzz.sh inputs).
      bool
      pclReadsDataAsHeader (const std::string& path, std::size_t data_offset)
      {
        std::ifstream in (path, std::ios::binary);
        in.seekg (static_cast<std::streamoff> (data_offset));
        static const char* const keywords[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT", "WIDTH",
                                               "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
        const auto isKeyword = [] (const std::string& token) {
          return std::any_of (std::begin (keywords), std::end (keywords), [&] (const char* keyword) {
            return token.compare (0, std::strlen (keyword), keyword) == 0;
          });
        };
        // The first word of each line, as PCL's stream extraction sees it; lines without one and comments
        // are skipped (PCL goes on past empty lines and comments; we also past blank ones, to be safe).
        std::string token;
        bool comment = false;
        for (char c; in.get (c);)
        {
          if (c == '\n')
          {
            if (!token.empty () && !comment)
              return isKeyword (token);
            token.clear ();
            comment = false;
          }
          else if (comment)
            continue;
          else if (std::isspace (static_cast<unsigned char> (c)))
          {
            if (!token.empty ())
              return isKeyword (token);
          }
          else
          {
            token += c;
            if (token[0] == '#')
              comment = true;
            else if (token.size () == 9)  // longer than every keyword: decided
              return isKeyword (token);
          }
        }
        return isKeyword (token) && !comment;
      }

      /// The points of a DATA binary file, read at the layout our header check found (PCL's reader would
      /// parse data lines that look like header lines; see pclReadsDataAsHeader).
      void
      readBinaryBody (const std::string& path, const PcdHeader& header, PcdBlob& blob)
      {
        blob.cloud = header.layout;
        const std::size_t bytes = static_cast<std::size_t> (header.layout.width) * header.layout.height *
                                  header.layout.point_step;  // readPcdHeader checked that the file holds them
        blob.cloud.data.resize (bytes);
        std::FILE* file = std::fopen (path.c_str (), "rb");
        const bool read = file && std::fseek (file, static_cast<long> (header.data_offset), SEEK_SET) == 0 &&
                          (bytes == 0 || std::fread (blob.cloud.data.data (), 1, bytes, file) == bytes);
        if (file)
          std::fclose (file);
        if (!read)
          throw Error (path + ": cannot read the PCD data (truncated?)");
        blob.cloud.is_dense = false;  // unknown; the loaders look at every point
        blob.sensor_origin = header.sensor_origin;
        blob.sensor_orientation = header.sensor_orientation;
      }
      /// The two sizes that open binary_compressed data, checked before PCL's reader sees them: it takes
      /// them on trust, resizes the cloud to the stored uncompressed size and then copies WIDTH x HEIGHT
      /// points into it, so a smaller size (0, or a header announcing more points than were compressed)
      /// read and wrote past its buffers (sizes of 0 crashed every tool); a larger size made it allocate that
      /// much twice.
      void
      checkCompressedSizes (const std::string& path, const PcdHeader& header)
      {
        std::uint32_t stored[2] = {0, 0};
        std::ifstream in (path, std::ios::binary | std::ios::ate);
        const long long file_size = static_cast<long long> (in.tellg ());
        in.seekg (static_cast<std::streamoff> (header.data_offset));
        if (!in.read (reinterpret_cast<char*> (stored), sizeof (stored)))
          throw Error (path + ": truncated PCD data");
        const long long compressed = stored[0], uncompressed = stored[1];
        const long long left = file_size - static_cast<long long> (header.data_offset) - 8;
        if (compressed > left)
          throw Error (path + ": truncated PCD data (" + std::to_string (compressed) + " compressed bytes announced, " +
                       std::to_string (left) + " left)");
        const long long points = static_cast<long long> (header.layout.width) * header.layout.height;
        const long long point_size = header.layout.point_step;
        // PCL writes exactly WIDTH x HEIGHT points; its reader resizes the cloud to the stored size and
        // allocates as much again before decompressing, so a larger size (up to 4 GiB from a 100-byte file)
        // made it zero-fill 8 GiB before LZF found the data too short (found by bench/fuzz.sh inputs).
        if ((point_size > 0 && points > uncompressed / point_size) ||  // uncompressed < points * point_size
            uncompressed != points * point_size)
          throw Error (path + ": bad binary_compressed PCD data (" + std::to_string (uncompressed) +
                       " bytes uncompressed, but " + std::to_string (points) + " points of " +
                       std::to_string (point_size) + " bytes announced)");
      }
    } // namespace

    /// The lines of DATA ascii, checked before PCL's reader sees them: it skips (silently) every non-empty
    /// line without exactly one value per field and element, yet returns as many points as the header
    /// announced, the missing ones zeros (WIDTH 2 and the lines "5 6 7", "1 2 3 4" gave (5, 6, 7) and
    /// (0, 0, 0)); it splits each line into strings first (one 100 MB line took 3.3 GB); a value it cannot
    /// read becomes 0. Its values are separated by runs of ' ', '\t', '\r'; it stops after WIDTH x HEIGHT
    /// points, and so do we.
    void
    checkPcdAsciiData (const std::string& path, const PcdHeader& header)
    {
      long long values_per_point = 0;
      for (const pcl::PCLPointField& field : header.layout.fields)
        values_per_point += field.count;
      const long long points = static_cast<long long> (header.layout.width) * header.layout.height;
      long long read = 0, line = 1, values = 0, length = 0;
      std::string token;
      bool too_long = false;
      const auto where = [&] () { return " on line " + std::to_string (line) + " of the PCD data"; };
      const auto endValue = [&] () {
        if (token.empty ())
          return;
        char* end = nullptr;
        std::strtod (token.c_str (), &end);
        if (token[0] == '#')
          throw Error (path + ": a comment" + where () + " (PCL's reader takes it for a point)");
        if (too_long || end != token.c_str () + token.size ())
          throw Error (path + ": bad value '" + token.substr (0, 20) + (too_long ? "...'" : "'") + where ());
        if (++values > values_per_point)
          throw Error (path + ": more than " + std::to_string (values_per_point) + " values" + where ());
        token.clear ();
      };
      const auto endLine = [&] () {
        endValue ();
        if (length > 0 && values != values_per_point)
          throw Error (path + ": " + std::to_string (values) + " values" + where () + ", its fields need " +
                       std::to_string (values_per_point));
        read += length > 0;
        ++line;
        values = length = 0;
      };
      std::ifstream in (path, std::ios::binary);
      in.seekg (static_cast<std::streamoff> (header.data_offset));
      char buffer[65536];
      while (read < points && in)
      {
        in.read (buffer, sizeof buffer);
        const std::streamsize got = in.gcount ();
        for (std::streamsize i = 0; i < got && read < points; ++i)
        {
          const char c = buffer[i];
          if (c == '\n')
            endLine ();
          else
          {
            ++length;
            if (c == ' ' || c == '\t' || c == '\r')
              endValue ();
            else if (token.size () < 64)  // longer than any number
              token += c;
            else
              too_long = true;
          }
        }
      }
      if (read < points && length > 0)  // the last line needs no newline, but all its values
      {
        endValue ();
        read += values == values_per_point;
      }
      if (read < points)
        throw Error (path + ": truncated or bad ascii PCD data (the file ends after " + std::to_string (read) + " of " +
                     std::to_string (points) + " points)");
    }

    void
    readPcdBlob (const std::string& path, PcdBlob& blob)
    {
      checkReadableFile (path);
      const PcdHeader header = readPcdHeader (path);
      if (header.data_kind == "binary")
      {
        readBinaryBody (path, header, blob);
        return;
      }
      if (pclReadsDataAsHeader (path, header.data_offset))
        throw Error (path + ": not a readable PCD file (its data starts like a header line)");
      if (header.data_kind == "binary_compressed")
        checkCompressedSizes (path, header);
      else
        checkPcdAsciiData (path, header);
      QuietPclConsole quiet;
      pcl::PCDReader reader;
      int version = 0;
      int result = -1;
      try
      {
        result = reader.read (path, blob.cloud, blob.sensor_origin, blob.sensor_orientation, version);
      }
      catch (const pcl::PCLException&)
      {
      }
      catch (const std::exception&)
      {
        // PCL sizes some reads from the data itself (binary_compressed sizes): garbage can make it ask for
        // terabytes (length_error, bad_alloc) where our header check found nothing wrong.
      }
      if (result < 0)
        throw Error (path + ": not a readable PCD file (bad header or truncated data)");
    }
  } // namespace io_detail
} // namespace pcl_sparse
