/// Stanford PLY: ascii, binary_little_endian and binary_big_endian. The vertex element gives x, y, z of any
/// numeric type (other vertex properties skipped); the face element's list "vertex_indices" (or
/// "vertex_index") of any integer count and index type gives polygons, fan-triangulated; other elements and
/// properties are skipped. Every count is checked against the bytes left before anything is reserved.
/// readPlyPoints reads the same files for point clouds: chosen scalar vertex properties (normals, colours,
/// intensity) and the Stanford scanner's range_grid element (one list of 0 or 1 vertex index per grid cell).

#include "cloud_readers.h"
#include "mesh_readers.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <vector>

namespace pcl_sparse
{
  namespace io_detail
  {
    namespace
    {
      enum class PlyType
      {
        Int8,
        UInt8,
        Int16,
        UInt16,
        Int32,
        UInt32,
        Float32,
        Float64
      };

      bool
      parsePlyType (const std::string& name, PlyType& type)
      {
        if (name == "char" || name == "int8")
          type = PlyType::Int8;
        else if (name == "uchar" || name == "uint8")
          type = PlyType::UInt8;
        else if (name == "short" || name == "int16")
          type = PlyType::Int16;
        else if (name == "ushort" || name == "uint16")
          type = PlyType::UInt16;
        else if (name == "int" || name == "int32")
          type = PlyType::Int32;
        else if (name == "uint" || name == "uint32")
          type = PlyType::UInt32;
        else if (name == "float" || name == "float32")
          type = PlyType::Float32;
        else if (name == "double" || name == "float64")
          type = PlyType::Float64;
        else
          return false;
        return true;
      }

      std::size_t
      sizeOf (PlyType type)
      {
        switch (type)
        {
          case PlyType::Int8:
          case PlyType::UInt8:
            return 1;
          case PlyType::Int16:
          case PlyType::UInt16:
            return 2;
          case PlyType::Int32:
          case PlyType::UInt32:
          case PlyType::Float32:
            return 4;
          case PlyType::Float64:
            return 8;
        }
        return 0;
      }

      bool
      isInteger (PlyType type)
      {
        return type != PlyType::Float32 && type != PlyType::Float64;
      }

      /// Whether \a v lies in the range of the integer type \a type (floating-point types hold any value).
      bool
      fitsType (double v, PlyType type)
      {
        switch (type)
        {
          case PlyType::Int8:
            return v >= -128.0 && v <= 127.0;
          case PlyType::UInt8:
            return v >= 0.0 && v <= 255.0;
          case PlyType::Int16:
            return v >= -32768.0 && v <= 32767.0;
          case PlyType::UInt16:
            return v >= 0.0 && v <= 65535.0;
          case PlyType::Int32:
            return v >= -2147483648.0 && v <= 2147483647.0;
          case PlyType::UInt32:
            return v >= 0.0 && v <= 4294967295.0;
          case PlyType::Float32:
          case PlyType::Float64:
            return true;
        }
        return false;
      }

      struct PlyProperty
      {
        std::string name;
        PlyType type = PlyType::Float32;  // the value type (list entries for lists)
        bool is_list = false;
        PlyType count_type = PlyType::UInt8;
      };

      struct PlyElement
      {
        std::string name;
        long long count = 0;
        std::vector<PlyProperty> properties;
      };

      enum class PlyFormat
      {
        Ascii,
        BinaryLittleEndian,
        BinaryBigEndian
      };

      /// Whether the bytes [begin, end) are padding: zero bytes and white space only.
      bool
      isPadding (const char* begin, const char* end)
      {
        return std::all_of (begin, end, [] (char c) { return c == '\0' || std::isspace (static_cast<unsigned char> (c)); });
      }

      /// Reads one binary value of \a type at \a p (which has at least sizeOf (type) bytes) as double.
      template <bool swap>
      double
      readBinary (const char* p, PlyType type)
      {
        unsigned char bytes[8];
        const std::size_t n = sizeOf (type);
        if (swap)
          for (std::size_t i = 0; i < n; ++i)
            bytes[i] = static_cast<unsigned char> (p[n - 1 - i]);
        else
          std::memcpy (bytes, p, n);
        switch (type)
        {
          case PlyType::Int8: { std::int8_t v; std::memcpy (&v, bytes, 1); return v; }
          case PlyType::UInt8: { std::uint8_t v; std::memcpy (&v, bytes, 1); return v; }
          case PlyType::Int16: { std::int16_t v; std::memcpy (&v, bytes, 2); return v; }
          case PlyType::UInt16: { std::uint16_t v; std::memcpy (&v, bytes, 2); return v; }
          case PlyType::Int32: { std::int32_t v; std::memcpy (&v, bytes, 4); return v; }
          case PlyType::UInt32: { std::uint32_t v; std::memcpy (&v, bytes, 4); return v; }
          case PlyType::Float32: { float v; std::memcpy (&v, bytes, 4); return v; }
          case PlyType::Float64: { double v; std::memcpy (&v, bytes, 8); return v; }
        }
        return 0.0;
      }

      /// Splits a header line into words, at most \a max_words of them (no header line needs more than 5: a
      /// 100 MB line of 50 million words took 2.2 GB as strings before it was refused).
      std::vector<std::string>
      splitWords (const char* begin, const char* end, std::size_t max_words)
      {
        std::vector<std::string> words;
        const char* p = begin;
        while (p < end && words.size () < max_words)
        {
          while (p < end && TextCursor::isBlank (*p))
            ++p;
          const char* start = p;
          while (p < end && !TextCursor::isBlank (*p))
            ++p;
          if (p > start)
            words.emplace_back (start, p);
        }
        return words;
      }

      /// The parts of the body the mesh needs: which element and properties are the vertices and faces.
      struct PlyLayout
      {
        std::vector<PlyElement> elements;
        PlyFormat format = PlyFormat::Ascii;
        std::size_t body_offset = 0;
        std::vector<std::vector<std::string>> obj_info;  ///< the words after "obj_info" on each such line
      };

      PlyLayout
      parseHeader (const std::string& data, const std::string& path)
      {
        PlyLayout layout;
        if (data.size () < 4 || data.compare (0, 3, "ply") != 0 || (data[3] != '\n' && data[3] != '\r'))
          throw Error (path + ": not a PLY file (it does not start with 'ply')");
        const char* p = data.data ();
        const char* end = data.data () + data.size ();
        std::size_t line = 0;
        bool have_format = false;
        while (true)
        {
          const char* nl = static_cast<const char*> (std::memchr (p, '\n', static_cast<std::size_t> (end - p)));
          if (!nl)
            throw Error (path + ": truncated PLY header (no end_header)");
          ++line;
          const std::vector<std::string> words = splitWords (p, nl, 6);
          p = nl + 1;
          if (line == 1 || words.empty () || words[0] == "comment")
            continue;
          if (words[0] == "obj_info")
          {
            layout.obj_info.emplace_back (words.begin () + 1, words.end ());
            continue;
          }
          if (words[0] == "end_header")
            break;
          if (words[0] == "format")
          {
            if (words.size () < 2)
              throw Error (atLine (path, line, "bad PLY format line"));
            if (words[1] == "ascii")
              layout.format = PlyFormat::Ascii;
            else if (words[1] == "binary_little_endian")
              layout.format = PlyFormat::BinaryLittleEndian;
            else if (words[1] == "binary_big_endian")
              layout.format = PlyFormat::BinaryBigEndian;
            else
              throw Error (atLine (path, line, "unknown PLY format '" + words[1] + "'"));
            have_format = true;
          }
          else if (words[0] == "element")
          {
            PlyElement element;
            long long count = -1;
            if (words.size () == 3)
            {
              const auto result = std::from_chars (words[2].data (), words[2].data () + words[2].size (), count);
              if (result.ec != std::errc () || result.ptr != words[2].data () + words[2].size ())
                count = -1;
            }
            if (count < 0)
              throw Error (atLine (path, line, "bad PLY element line"));
            // A second element or property of one name would hold columns of another size than the first.
            for (const PlyElement& earlier : layout.elements)
              if (earlier.name == words[1])
                throw Error (atLine (path, line, "a second PLY element '" + words[1] + "'"));
            element.name = words[1];
            element.count = count;
            layout.elements.push_back (element);
          }
          else if (words[0] == "property")
          {
            if (layout.elements.empty ())
              throw Error (atLine (path, line, "PLY property before any element"));
            PlyProperty property;
            bool ok = false;
            if (words.size () == 3)
              ok = parsePlyType (words[1], property.type);
            else if (words.size () == 5 && words[1] == "list")
            {
              property.is_list = true;
              ok = parsePlyType (words[2], property.count_type) && isInteger (property.count_type) &&
                   parsePlyType (words[3], property.type);
            }
            if (!ok)
              throw Error (atLine (path, line, "bad PLY property line"));
            property.name = words.back ();
            for (const PlyProperty& earlier : layout.elements.back ().properties)
              if (earlier.name == property.name)
                throw Error (atLine (path, line, "a second PLY property '" + property.name + "' in one element"));
            layout.elements.back ().properties.push_back (property);
          }
          else
            throw Error (atLine (path, line, "unknown PLY header line '" + words[0] + "'"));
        }
        if (!have_format)
          throw Error (path + ": PLY header without a format line");
        layout.body_offset = static_cast<std::size_t> (p - data.data ());
        return layout;
      }

      /// What a point cloud reader wants from the body besides positions and faces: some scalar vertex
      /// properties (by name) and the range grid.
      struct PlyPointSink
      {
        const std::vector<std::string>* wanted = nullptr;
        std::map<std::string, std::vector<double>>* values = nullptr;
        std::vector<int>* range_grid = nullptr;
      };

      /// Reads the body: binary (templated on byte swapping) or ascii.
      class PlyBodyReader
      {
      public:
        PlyBodyReader (const std::string& data, const std::string& path, const PlyLayout& layout)
        : data_ (data), path_ (path), layout_ (layout)
        {
        }

        void
        read (TriangleMesh& mesh, const PlyPointSink& sink = PlyPointSink ())
        {
          const char* p = data_.data () + layout_.body_offset;
          const char* end = data_.data () + data_.size ();
          TextCursor cursor (data_);
          cursor.p = p;
          cursor.line = 1 + static_cast<std::size_t> (std::count (data_.data (), p, '\n'));
          for (const PlyElement& element : layout_.elements)
          {
            const ElementRoles roles = rolesOf (element, sink.range_grid != nullptr);
            const bool is_vertex = roles.is_vertex, is_face = roles.is_face, is_grid = roles.is_grid;
            const int x = roles.x, y = roles.y, z = roles.z, indices = roles.indices;
            const std::size_t min_record = roles.min_record;
            if (is_vertex && !mesh.vertices.empty ())
              throw Error (path_ + ": two PLY vertex elements");

            // Refuse a lying header before reserving: in binary every record has at least min_record bytes,
            // in ascii every value at least one character and one separator.
            const long long remaining =
                layout_.format == PlyFormat::Ascii ? static_cast<long long> (end - cursor.p) : static_cast<long long> (end - p);
            const long long min_bytes =
                layout_.format == PlyFormat::Ascii ? 2 * static_cast<long long> (element.properties.size ()) - 1
                                                   : static_cast<long long> (min_record);
            // (+1 in ascii: the last value of the file needs no separator.)
            const long long slack = layout_.format == PlyFormat::Ascii ? 1 : 0;
            if (element.count > 0 && min_bytes > 0 && element.count > (remaining + slack) / min_bytes)
              throw Error (path_ + ": truncated or lying header: the PLY element '" + element.name + "' announces " +
                           std::to_string (element.count) + " records, more than the " + std::to_string (remaining) +
                           " remaining bytes can hold");

            if (is_vertex && element.count > std::numeric_limits<int>::max ())
              throw Error (path_ + ": too many vertices (" + std::to_string (element.count) + ")");

            // Scalar vertex properties the caller asked for, one column each (x y z go to the vertices).
            std::vector<std::vector<double>*> columns (element.properties.size (), nullptr);
            if (is_vertex)
            {
              mesh.vertices.resize (static_cast<std::size_t> (element.count));
              for (std::size_t i = 0; sink.wanted && i < element.properties.size (); ++i)
              {
                const PlyProperty& property = element.properties[i];
                if (!property.is_list && static_cast<int> (i) != x && static_cast<int> (i) != y &&
                    static_cast<int> (i) != z &&
                    std::find (sink.wanted->begin (), sink.wanted->end (), property.name) != sink.wanted->end ())
                {
                  columns[i] = &(*sink.values)[property.name];
                  columns[i]->assign (static_cast<std::size_t> (element.count), 0.0);
                }
              }
            }
            if (is_grid)
            {
              if (!sink.range_grid->empty ())
                throw Error (path_ + ": two PLY range_grid elements");
              sink.range_grid->reserve (static_cast<std::size_t> (element.count));  // count checked above
            }
            if (is_face)
            {
              // At most as many triangles as full triangle records fit in the bytes left (a lying header with
              // one-byte empty lists must not reserve 12 bytes per claimed face).
              const PlyProperty& list = element.properties[static_cast<std::size_t> (indices)];
              const long long triangle_bytes = layout_.format == PlyFormat::Ascii
                                                   ? 8
                                                   : static_cast<long long> (sizeOf (list.count_type) + 3 * sizeOf (list.type));
              const long long fit = std::min (element.count, (remaining + 1) / triangle_bytes);
              mesh.triangles.reserve (mesh.triangles.size () + static_cast<std::size_t> (fit));
            }

            // An element without properties has nothing in the body, whatever its count says (and looping
            // over a count of 1e12 would hang).
            if (element.properties.empty ())
              continue;
            const Target target{is_vertex, is_face, is_grid, x, y, z, indices, &columns, sink.range_grid};
            switch (layout_.format)
            {
              case PlyFormat::Ascii:
                readAscii (cursor, element, target, mesh);
                break;
              case PlyFormat::BinaryLittleEndian:
                p = readBinaryElement<false> (p, end, element, target, mesh);
                break;
              case PlyFormat::BinaryBigEndian:
                p = readBinaryElement<true> (p, end, element, target, mesh);
                break;
            }
          }
          // After the last element: in ascii only blank lines; in binary only padding (zero bytes or white
          // space, which some writers append). Anything else is records the header does not count, which
          // would be dropped silently.
          if (layout_.format == PlyFormat::Ascii && cursor.skipToToken ())
            throw Error (atLine (path_, cursor.line, "data after the last element the header announces (a wrong "
                                                     "element count?)"));
          if (layout_.format != PlyFormat::Ascii && !isPadding (p, end))
            throw Error (path_ + ": " + std::to_string (end - p) +
                         " bytes of data after the last element the header announces (a wrong element count?)");
          const long long num_vertices = vertex_count_ >= 0 ? vertex_count_ : static_cast<long long> (mesh.vertices.size ());
          for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
            for (int k = 0; k < 3; ++k)
            {
              const int index = mesh.triangles[f][k];
              if (index < 0 || index >= num_vertices)
                throw Error (path_ + ": face index " + std::to_string (index) + " is out of range (the file has " +
                             std::to_string (num_vertices) + " vertices)");
            }
        }

        /// Checks face indices against \a n vertices instead of those read (for faces read without them).
        void
        setVertexCount (long long n)
        {
          vertex_count_ = n;
        }

        /// Throws as read () would for an element without its x y z or index list (read () checks each
        /// element when it gets to it; a reader of only the vertex records checks the others here).
        void
        checkElements () const
        {
          for (const PlyElement& element : layout_.elements)
            rolesOf (element, false);
        }

      private:
        /// What an element is to the reader and where its x, y, z and index list are.
        struct ElementRoles
        {
          bool is_vertex = false, is_face = false, is_grid = false;
          int x = -1, y = -1, z = -1, indices = -1;
          std::size_t min_record = 0;  ///< bytes of the smallest binary record
        };

        /// The roles of \a element's properties; throws if a vertex, face or range_grid element lacks its own.
        ElementRoles
        rolesOf (const PlyElement& element, bool wants_grid) const
        {
          ElementRoles roles;
          roles.is_vertex = element.name == "vertex";
          roles.is_face = element.name == "face";
          roles.is_grid = wants_grid && element.name == "range_grid";
          for (std::size_t i = 0; i < element.properties.size (); ++i)
          {
            const PlyProperty& property = element.properties[i];
            roles.min_record += property.is_list ? sizeOf (property.count_type) : sizeOf (property.type);
            if (roles.is_vertex && !property.is_list)
            {
              if (property.name == "x")
                roles.x = static_cast<int> (i);
              else if (property.name == "y")
                roles.y = static_cast<int> (i);
              else if (property.name == "z")
                roles.z = static_cast<int> (i);
            }
            if ((roles.is_face || roles.is_grid) && property.is_list &&
                (property.name == "vertex_indices" || property.name == "vertex_index"))
            {
              if (!isInteger (property.type))
                throw Error (path_ + ": PLY " + element.name + " indices of a floating-point type");
              roles.indices = static_cast<int> (i);
            }
          }
          if (roles.is_grid && roles.indices < 0)
            throw Error (path_ + ": the PLY range_grid element has no vertex_indices list");
          if (roles.is_vertex && (roles.x < 0 || roles.y < 0 || roles.z < 0))
            throw Error (path_ + ": the PLY vertex element has no x, y, z properties");
          if (roles.is_face && roles.indices < 0)
            throw Error (path_ + ": the PLY face element has no vertex_indices list");
          return roles;
        }

        struct Target
        {
          bool is_vertex, is_face, is_grid;
          int x, y, z, indices;
          const std::vector<std::vector<double>*>* columns;  ///< per property: where its values go, or null
          std::vector<int>* range_grid;
        };

        /// One range grid cell: no vertex (-1) or one.
        void
        addGridCell (const std::vector<long long>& cell, long long record, std::vector<int>& grid) const
        {
          if (cell.size () > 1)
            throw Error (path_ + ": PLY range_grid cell " + std::to_string (record) + " has " +
                         std::to_string (cell.size ()) + " vertices (at most 1)");
          if (!cell.empty () && (cell[0] < 0 || cell[0] > std::numeric_limits<int>::max ()))
            throw Error (path_ + ": range_grid vertex index " + std::to_string (cell[0]) + " is out of range");
          grid.push_back (cell.empty () ? -1 : static_cast<int> (cell[0]));
        }

        void
        addPolygon (const std::vector<long long>& polygon, long long record, TriangleMesh& mesh) const
        {
          if (polygon.size () < 3)
            throw Error (path_ + ": PLY face " + std::to_string (record) + " has " + std::to_string (polygon.size ()) +
                         " vertices (at least 3 needed)");
          for (long long index : polygon)
            if (index < 0 || index > std::numeric_limits<int>::max ())
              throw Error (path_ + ": face index " + std::to_string (index) + " is out of range");
          for (std::size_t i = 1; i + 1 < polygon.size (); ++i)
            mesh.triangles.emplace_back (static_cast<int> (polygon[0]), static_cast<int> (polygon[i]),
                                         static_cast<int> (polygon[i + 1]));
        }

        [[noreturn]] void
        truncated (const PlyElement& element, long long record) const
        {
          throw Error (path_ + ": truncated: the file ends in PLY " + element.name + " " + std::to_string (record) +
                       " of " + std::to_string (element.count));
        }

        template <bool swap>
        const char*
        readBinaryElement (const char* p, const char* end, const PlyElement& element, const Target& target,
                           TriangleMesh& mesh) const
        {
          // Fast path: fixed-size records (no lists), e.g. the vertex element of almost every file. The caller
          // has checked that count * record size bytes are left.
          std::size_t stride = 0;
          bool fixed = true;
          std::size_t offset[3] = {0, 0, 0};
          PlyType type[3] = {PlyType::Float32, PlyType::Float32, PlyType::Float32};
          for (std::size_t i = 0; i < element.properties.size (); ++i)
          {
            const PlyProperty& property = element.properties[i];
            fixed = fixed && !property.is_list;
            const int pi = static_cast<int> (i);
            for (int k = 0; k < 3; ++k)
              if (pi == (k == 0 ? target.x : (k == 1 ? target.y : target.z)))
              {
                offset[k] = stride;
                type[k] = property.type;
              }
            stride += sizeOf (property.type);
          }
          if (fixed)
          {
            if (target.is_vertex)
              for (long long r = 0; r < element.count; ++r)
              {
                const char* record = p + static_cast<std::size_t> (r) * stride;
                Eigen::Vector3d& v = mesh.vertices[static_cast<std::size_t> (r)];
                for (int k = 0; k < 3; ++k)
                  v[k] = readBinary<swap> (record + offset[k], type[k]);
              }
            // Other wanted vertex properties, column by column.
            std::size_t column_offset = 0;
            for (std::size_t i = 0; target.is_vertex && i < element.properties.size (); ++i)
            {
              const PlyType column_type = element.properties[i].type;
              if (std::vector<double>* column = (*target.columns)[i])
                for (long long r = 0; r < element.count; ++r)
                  (*column)[static_cast<std::size_t> (r)] =
                      readBinary<swap> (p + static_cast<std::size_t> (r) * stride + column_offset, column_type);
              column_offset += sizeOf (column_type);
            }
            return p + static_cast<std::size_t> (element.count) * stride;
          }

          long long r = 0;
          // Fast path: a face element holding only the index list, with triangles as uchar-counted lists of
          // 32-bit indices (what most writers, ours included, write). Leaves at the first other record.
          if (target.is_face && element.properties.size () == 1 && sizeOf (element.properties[0].count_type) == 1 &&
              sizeOf (element.properties[0].type) == 4)
          {
            const bool is_signed = element.properties[0].type == PlyType::Int32;
            for (; r < element.count && end - p >= 13 && *p == 3; ++r, p += 13)
            {
              long long index[3];
              for (int k = 0; k < 3; ++k)
              {
                std::uint32_t bits;
                std::memcpy (&bits, p + 1 + 4 * k, 4);
                if (swap)
                  bits = __builtin_bswap32 (bits);
                index[k] = is_signed ? static_cast<long long> (static_cast<std::int32_t> (bits)) : static_cast<long long> (bits);
                if (index[k] < 0 || index[k] > std::numeric_limits<int>::max ())
                  throw Error (path_ + ": face index " + std::to_string (index[k]) + " is out of range");
              }
              mesh.triangles.emplace_back (static_cast<int> (index[0]), static_cast<int> (index[1]),
                                           static_cast<int> (index[2]));
            }
          }

          std::vector<long long> polygon;
          for (; r < element.count; ++r)
          {
            for (std::size_t i = 0; i < element.properties.size (); ++i)
            {
              const PlyProperty& property = element.properties[i];
              const int pi = static_cast<int> (i);
              if (!property.is_list)
              {
                const std::size_t size = sizeOf (property.type);
                if (static_cast<std::size_t> (end - p) < size)
                  truncated (element, r);
                if (target.is_vertex && (pi == target.x || pi == target.y || pi == target.z))
                  mesh.vertices[static_cast<std::size_t> (r)][pi == target.x ? 0 : (pi == target.y ? 1 : 2)] =
                      readBinary<swap> (p, property.type);
                else if (target.is_vertex && (*target.columns)[i])
                  (*(*target.columns)[i])[static_cast<std::size_t> (r)] = readBinary<swap> (p, property.type);
                p += size;
                continue;
              }
              const std::size_t count_size = sizeOf (property.count_type);
              if (static_cast<std::size_t> (end - p) < count_size)
                truncated (element, r);
              const double count_value = readBinary<swap> (p, property.count_type);
              p += count_size;
              const std::size_t size = sizeOf (property.type);
              if (count_value < 0 || count_value * static_cast<double> (size) > static_cast<double> (end - p))
                truncated (element, r);
              const std::size_t count = static_cast<std::size_t> (count_value);
              if ((target.is_face || target.is_grid) && pi == target.indices)
              {
                polygon.resize (count);
                for (std::size_t k = 0; k < count; ++k)
                  polygon[k] = static_cast<long long> (readBinary<swap> (p + k * size, property.type));
                if (target.is_face)
                  addPolygon (polygon, r, mesh);
                else
                  addGridCell (polygon, r, *target.range_grid);
              }
              p += count * size;
            }
          }
          return p;
        }

        void
        readAscii (TextCursor& cursor, const PlyElement& element, const Target& target, TriangleMesh& mesh) const
        {
          std::vector<long long> polygon;
          auto value = [&] (long long record, PlyType type) {
            double v;
            if (!cursor.skipToToken ())
              truncated (element, record);
            if (!cursor.parseDouble (v) || !cursor.atDelimiter ())
              throw Error (atLine (path_, cursor.line, "bad PLY value " + cursor.tokenForMessage ()));
            if (isInteger (type) && v != std::floor (v))
              throw Error (atLine (path_, cursor.line, "non-integer value for an integer PLY property"));
            if (!fitsType (v, type))  // ascii holds any number; a binary file cannot
              throw Error (atLine (path_, cursor.line, "PLY value out of the range of its integer type"));
            return v;
          };
          for (long long r = 0; r < element.count; ++r)
          {
            for (std::size_t i = 0; i < element.properties.size (); ++i)
            {
              const PlyProperty& property = element.properties[i];
              const int pi = static_cast<int> (i);
              if (!property.is_list)
              {
                const double v = value (r, property.type);
                if (target.is_vertex && (pi == target.x || pi == target.y || pi == target.z))
                  mesh.vertices[static_cast<std::size_t> (r)][pi == target.x ? 0 : (pi == target.y ? 1 : 2)] = v;
                else if (target.is_vertex && (*target.columns)[i])
                  (*(*target.columns)[i])[static_cast<std::size_t> (r)] = v;
                continue;
              }
              const double count_value = value (r, property.count_type);
              if (count_value < 0 || count_value > static_cast<double> (cursor.end - cursor.p))
                throw Error (atLine (path_, cursor.line, "bad PLY list size"));
              const std::size_t count = static_cast<std::size_t> (count_value);
              polygon.resize (count);
              for (std::size_t k = 0; k < count; ++k)
              {
                const double entry = value (r, property.type);
                // Only index lists are integers (checked in range); other lists are read and dropped.
                polygon[k] = pi == target.indices ? static_cast<long long> (entry) : 0;
              }
              if (target.is_face && pi == target.indices)
                addPolygon (polygon, r, mesh);
              else if (target.is_grid && pi == target.indices)
                addGridCell (polygon, r, *target.range_grid);
            }
          }
        }

        const std::string& data_;
        const std::string& path_;
        const PlyLayout& layout_;
        long long vertex_count_ = -1;  ///< face indices are checked against it (-1: the vertices read)
      };
    } // namespace

    void
    readPly (const std::string& data, const std::string& path, TriangleMesh& mesh)
    {
      const PlyLayout layout = parseHeader (data, path);
      PlyBodyReader (data, path, layout).read (mesh);
    }

    void
    readPlyPoints (const std::string& data, const std::string& path, const std::vector<std::string>& wanted,
                   PlyPoints& points)
    {
      const PlyLayout layout = parseHeader (data, path);
      points = PlyPoints ();
      for (const PlyElement& element : layout.elements)
      {
        if (element.name == "vertex")
          for (const PlyProperty& property : element.properties)
            points.vertex_properties.push_back (property.name);
        if (element.name == "face")
          points.num_faces += element.count;
      }
      TriangleMesh mesh;
      PlyPointSink sink;
      sink.wanted = &wanted;
      sink.values = &points.values;
      sink.range_grid = &points.range_grid;
      PlyBodyReader (data, path, layout).read (mesh, sink);
      points.positions = std::move (mesh.vertices);

      const bool has_grid = std::any_of (layout.elements.begin (), layout.elements.end (),
                                         [] (const PlyElement& element) { return element.name == "range_grid"; });
      if (!has_grid)
        return;
      // The grid's shape is in the header (obj_info num_cols / num_rows); it must match the cell count and
      // put every vertex in exactly one cell, or the grid cannot be rebuilt from it.
      long long columns = -1, rows = -1;
      for (const std::vector<std::string>& info : layout.obj_info)
        if (info.size () == 2 && (info[0] == "num_cols" || info[0] == "num_rows"))
        {
          long long value = -1;
          const auto result = std::from_chars (info[1].data (), info[1].data () + info[1].size (), value);
          if (result.ec != std::errc () || result.ptr != info[1].data () + info[1].size () || value <= 0 ||
              value > std::numeric_limits<std::uint32_t>::max ())
            throw Error (path + ": bad PLY obj_info " + info[0] + " '" + info[1].substr (0, 20) + "'");
          (info[0] == "num_cols" ? columns : rows) = value;
        }
      if (columns < 0 || rows < 0)
        throw Error (path + ": PLY range_grid without obj_info num_cols and num_rows");
      // Each may be up to 2^32 - 1: their product overflowed a long long (undefined behaviour).
      if (columns > std::numeric_limits<std::uint32_t>::max () / rows)
        throw Error (path + ": PLY range_grid of num_cols x num_rows = " + std::to_string (columns) + " x " +
                     std::to_string (rows) + " cells, more than 2^32 - 1");
      if (static_cast<long long> (points.range_grid.size ()) != columns * rows)
        throw Error (path + ": PLY range_grid has " + std::to_string (points.range_grid.size ()) + " cells, not num_cols x num_rows = " +
                     std::to_string (columns) + " x " + std::to_string (rows));
      std::vector<char> seen (points.positions.size (), 0);
      for (const int vertex : points.range_grid)
      {
        if (vertex < 0)
          continue;
        if (static_cast<std::size_t> (vertex) >= points.positions.size ())
          throw Error (path + ": range_grid vertex index " + std::to_string (vertex) + " is out of range (the file has " +
                       std::to_string (points.positions.size ()) + " vertices)");
        if (seen[static_cast<std::size_t> (vertex)]++)
          throw Error (path + ": vertex " + std::to_string (vertex) + " is in two range_grid cells");
      }
      const auto missing = std::find (seen.begin (), seen.end (), 0);
      if (missing != seen.end ())
        throw Error (path + ": vertex " + std::to_string (missing - seen.begin ()) + " is in no range_grid cell");
      points.grid_width = static_cast<std::uint32_t> (columns);
      points.grid_height = static_cast<std::uint32_t> (rows);
    }

    struct PlyVertexRecords::Layout
    {
      PlyLayout header;             ///< the whole file's header
      std::size_t vertex = 0;       ///< index of the vertex element in header.elements
      bool streamable = false;
      std::size_t record_bytes = 0;
    };

    PlyVertexRecords::PlyVertexRecords (const std::string& head, const std::string& path) : path_ (path)
    {
      auto layout = std::make_shared<Layout> ();
      layout->header = parseHeader (head, path);
      PlyBodyReader (head, path, layout->header).checkElements ();
      const std::vector<PlyElement>& elements = layout->header.elements;
      // Streamable: binary, and the vertex element is the first with records in the body (an element
      // without properties or records takes no bytes), with fixed-size records.
      bool before = true;
      layout->streamable = layout->header.format != PlyFormat::Ascii;
      for (std::size_t e = 0; e < elements.size (); ++e)
      {
        if (elements[e].name == "range_grid")
          layout->streamable = false;  // the scan's order is the grid's, known only after the vertices
        if (elements[e].name == "vertex" && before)
        {
          layout->vertex = e;
          before = false;
          for (const PlyProperty& property : elements[e].properties)
          {
            layout->streamable = layout->streamable && !property.is_list;
            layout->record_bytes += sizeOf (property.type);
          }
        }
        else if (before && elements[e].count > 0 && !elements[e].properties.empty ())
          layout->streamable = false;
      }
      if (before)
        layout->streamable = false;  // no vertex element: the whole-file reader says what is wrong
      layout_ = layout;
    }

    bool
    PlyVertexRecords::streamable () const
    {
      return layout_->streamable;
    }

    std::size_t
    PlyVertexRecords::bodyOffset () const
    {
      return layout_->header.body_offset;
    }

    std::size_t
    PlyVertexRecords::recordBytes () const
    {
      return layout_->record_bytes;
    }

    long long
    PlyVertexRecords::count () const
    {
      return layout_->streamable ? layout_->header.elements[layout_->vertex].count : 0;
    }

    void
    PlyVertexRecords::decode (const std::string& records, const std::vector<std::string>& wanted, PlyPoints& points) const
    {
      if (!layout_->streamable || layout_->record_bytes == 0 || records.size () % layout_->record_bytes != 0)
        throw Error (path_ + ": PLY vertex records cannot be decoded in chunks");
      // The same body reader as for the whole file, over a layout of just these records.
      PlyLayout chunk;
      chunk.format = layout_->header.format;
      chunk.elements.push_back (layout_->header.elements[layout_->vertex]);
      chunk.elements[0].count = static_cast<long long> (records.size () / layout_->record_bytes);
      points.positions.clear ();
      points.values.clear ();
      points.range_grid.clear ();
      points.vertex_properties.clear ();
      for (const PlyProperty& property : chunk.elements[0].properties)
        points.vertex_properties.push_back (property.name);
      TriangleMesh mesh;
      PlyPointSink sink;
      sink.wanted = &wanted;
      sink.values = &points.values;
      PlyBodyReader (records, path_, chunk).read (mesh, sink);
      points.positions = std::move (mesh.vertices);
    }

    struct PlyFaceRecords::Layout
    {
      PlyLayout header;
      std::size_t face = 0;  ///< index of the face element
      bool streamable = false;
      bool faces_last = false;  ///< no element after the faces has bytes in the body
      std::size_t body_offset = 0;
      long long vertices = 0;
    };

    PlyFaceRecords::PlyFaceRecords (const std::string& head, const std::string& path) : path_ (path)
    {
      auto layout = std::make_shared<Layout> ();
      layout->header = parseHeader (head, path);
      PlyBodyReader (head, path, layout->header).checkElements ();
      const std::vector<PlyElement>& elements = layout->header.elements;
      // Streamable: binary, the vertex element first with fixed-size records, the face element next (only
      // elements without bytes between), so the faces start at a known offset.
      layout->streamable = layout->header.format != PlyFormat::Ascii;
      layout->body_offset = layout->header.body_offset;
      int stage = 0;  // 0: before the vertices, 1: between vertices and faces, 2: faces found
      for (std::size_t e = 0; e < elements.size () && stage < 2; ++e)
      {
        const PlyElement& element = elements[e];
        const bool empty = element.count == 0 || element.properties.empty ();
        if (element.name == "vertex" && stage == 0)
        {
          stage = 1;
          layout->vertices = element.count;
          std::size_t bytes = 0;
          for (const PlyProperty& property : element.properties)
          {
            layout->streamable = layout->streamable && !property.is_list;
            bytes += sizeOf (property.type);
          }
          layout->body_offset += bytes * static_cast<std::size_t> (element.count);
        }
        else if (element.name == "face" && stage == 1)
        {
          stage = 2;
          layout->face = e;
        }
        else if (!empty)
          layout->streamable = false;
      }
      layout->streamable = layout->streamable && stage == 2;
      layout->faces_last = true;
      for (std::size_t e = layout->face + 1; e < elements.size (); ++e)
        layout->faces_last = layout->faces_last && (elements[e].count == 0 || elements[e].properties.empty ());
      layout_ = layout;
    }

    void
    PlyFaceRecords::checkEnd (const std::string& rest) const
    {
      if (layout_->faces_last && !isPadding (rest.data (), rest.data () + rest.size ()))
        throw Error (path_ + ": data after the last element the header announces (a wrong element count?)");
    }

    bool
    PlyFaceRecords::streamable () const
    {
      return layout_->streamable;
    }

    std::size_t
    PlyFaceRecords::bodyOffset () const
    {
      return layout_->body_offset;
    }

    long long
    PlyFaceRecords::count () const
    {
      return layout_->streamable ? layout_->header.elements[layout_->face].count : 0;
    }

    std::size_t
    PlyFaceRecords::decode (const std::string& data, long long max_records, std::vector<Eigen::Vector3i>& triangles,
                            long long& records, std::size_t* next_record_bytes) const
    {
      if (!layout_->streamable)
        throw Error (path_ + ": PLY faces cannot be decoded in chunks");
      const PlyElement& element = layout_->header.elements[layout_->face];
      const bool swap = layout_->header.format == PlyFormat::BinaryBigEndian;
      // The complete records at the start of data (each list's size is in the record).
      const char* begin = data.data ();
      const char* end = begin + data.size ();
      const char* p = begin;
      records = 0;
      std::size_t next_bytes = 0;
      while (records < max_records)
      {
        const char* q = p;
        bool complete = true;
        for (const PlyProperty& property : element.properties)
        {
          std::size_t bytes = sizeOf (property.is_list ? property.count_type : property.type);
          if (static_cast<std::size_t> (end - q) < bytes)
          {
            complete = false;
            next_bytes = static_cast<std::size_t> (q - p) + bytes;
            break;
          }
          if (property.is_list)
          {
            const double count = swap ? readBinary<true> (q, property.count_type) : readBinary<false> (q, property.count_type);
            if (count < 0)
              throw Error (path_ + ": bad PLY face list size");
            q += bytes;
            bytes = static_cast<std::size_t> (count) * sizeOf (property.type);
            if (static_cast<std::size_t> (end - q) < bytes)
            {
              complete = false;
              next_bytes = static_cast<std::size_t> (q - p) + bytes;
              break;
            }
          }
          q += bytes;
        }
        if (!complete)
          break;
        p = q;
        ++records;
      }
      if (next_record_bytes)
        *next_record_bytes = next_bytes;
      // Those records through the same body reader as the whole file.
      PlyLayout chunk;
      chunk.format = layout_->header.format;
      chunk.elements.push_back (element);
      chunk.elements[0].count = records;
      const std::string bytes (begin, p);
      TriangleMesh mesh;
      PlyBodyReader reader (bytes, path_, chunk);
      reader.setVertexCount (layout_->vertices);
      reader.read (mesh);
      triangles.insert (triangles.end (), mesh.triangles.begin (), mesh.triangles.end ());
      return static_cast<std::size_t> (p - begin);
    }
  } // namespace io_detail
} // namespace pcl_sparse
