#include <pcl_sparse/format/byte_stream.h>

#include <pcl_sparse/common/error.h>

#include <cstring>

namespace pcl_sparse
{
  namespace
  {
    template <typename T>
    void
    appendLittleEndian (std::vector<std::uint8_t>& bytes, T v)
    {
      for (std::size_t i = 0; i < sizeof (T); ++i)
        bytes.push_back (static_cast<std::uint8_t> (static_cast<std::uint64_t> (v) >> (8 * i)));
    }

    template <typename T>
    T
    readLittleEndian (const std::uint8_t* p)
    {
      std::uint64_t v = 0;
      for (std::size_t i = 0; i < sizeof (T); ++i)
        v |= static_cast<std::uint64_t> (p[i]) << (8 * i);
      return static_cast<T> (v);
    }
  } // namespace

  void ByteWriter::putU16 (std::uint16_t v) { appendLittleEndian (bytes_, v); }
  void ByteWriter::putU32 (std::uint32_t v) { appendLittleEndian (bytes_, v); }
  void ByteWriter::putU64 (std::uint64_t v) { appendLittleEndian (bytes_, v); }

  void
  ByteWriter::putF32 (float v)
  {
    std::uint32_t bits;
    std::memcpy (&bits, &v, sizeof bits);
    putU32 (bits);
  }

  void
  ByteWriter::putF64 (double v)
  {
    std::uint64_t bits;
    std::memcpy (&bits, &v, sizeof bits);
    putU64 (bits);
  }

  void
  ByteWriter::putVarint (std::uint64_t v)
  {
    while (v >= 0x80)
    {
      bytes_.push_back (static_cast<std::uint8_t> (v | 0x80));
      v >>= 7;
    }
    bytes_.push_back (static_cast<std::uint8_t> (v));
  }

  void
  ByteWriter::putSignedVarint (std::int64_t v)
  {
    const std::uint64_t u = static_cast<std::uint64_t> (v);
    putVarint ((u << 1) ^ (v < 0 ? ~std::uint64_t (0) : std::uint64_t (0)));
  }

  void
  ByteWriter::putBytes (const std::uint8_t* data, std::size_t size)
  {
    bytes_.insert (bytes_.end (), data, data + size);
  }

  void
  ByteReader::fail (const std::string& message) const
  {
    throw Error (what_ + ": " + message);
  }

  void
  ByteReader::need (std::size_t n, const char* field) const
  {
    if (n > size_ - position_)
      fail (std::string ("truncated while reading ") + field + " (needs " + std::to_string (n) + " bytes at offset " +
            std::to_string (position_) + ", " + std::to_string (size_ - position_) + " left)");
  }

  std::uint8_t
  ByteReader::getU8 (const char* field)
  {
    need (1, field);
    return data_[position_++];
  }

  std::uint16_t
  ByteReader::getU16 (const char* field)
  {
    need (2, field);
    const auto v = readLittleEndian<std::uint16_t> (data_ + position_);
    position_ += 2;
    return v;
  }

  std::uint32_t
  ByteReader::getU32 (const char* field)
  {
    need (4, field);
    const auto v = readLittleEndian<std::uint32_t> (data_ + position_);
    position_ += 4;
    return v;
  }

  std::uint64_t
  ByteReader::getU64 (const char* field)
  {
    need (8, field);
    const auto v = readLittleEndian<std::uint64_t> (data_ + position_);
    position_ += 8;
    return v;
  }

  float
  ByteReader::getF32 (const char* field)
  {
    const std::uint32_t bits = getU32 (field);
    float v;
    std::memcpy (&v, &bits, sizeof v);
    return v;
  }

  double
  ByteReader::getF64 (const char* field)
  {
    const std::uint64_t bits = getU64 (field);
    double v;
    std::memcpy (&v, &bits, sizeof v);
    return v;
  }

  std::uint64_t
  ByteReader::getVarint (const char* field)
  {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7)
    {
      need (1, field);
      const std::uint8_t byte = data_[position_++];
      if (shift == 63 && byte > 1)
        fail (std::string ("varint overflow in ") + field);
      v |= static_cast<std::uint64_t> (byte & 0x7f) << shift;
      if (!(byte & 0x80))
        return v;
    }
    fail (std::string ("varint longer than 10 bytes in ") + field);
  }

  std::int64_t
  ByteReader::getSignedVarint (const char* field)
  {
    const std::uint64_t u = getVarint (field);
    return static_cast<std::int64_t> ((u >> 1) ^ (~(u & 1) + 1));
  }

  std::uint64_t
  ByteReader::getCount (const char* field, std::uint64_t max)
  {
    const std::uint64_t v = getVarint (field);
    if (v > max)
      fail (std::string (field) + " = " + std::to_string (v) + " exceeds the limit " + std::to_string (max));
    return v;
  }

  const std::uint8_t*
  ByteReader::getBytes (std::size_t size, const char* field)
  {
    need (size, field);
    const std::uint8_t* p = data_ + position_;
    position_ += size;
    return p;
  }

  void
  ByteReader::expectEnd () const
  {
    if (position_ != size_)
      fail (std::to_string (size_ - position_) + " unexpected trailing bytes");
  }
} // namespace pcl_sparse
