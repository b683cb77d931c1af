#pragma once
/// \file byte_stream.h
/// Little-endian byte writing and bounds-checked reading for the model file format. The reader trusts
/// nothing: every read checks the remaining length and throws pcl_sparse::Error naming what it was
/// reading, so a truncated or lying file can never make it read past its buffer.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Appends little-endian values to a growing byte vector.
  class ByteWriter
  {
  public:
    void putU8 (std::uint8_t v) { bytes_.push_back (v); }
    void putU16 (std::uint16_t v);
    void putU32 (std::uint32_t v);
    void putU64 (std::uint64_t v);
    void putF32 (float v);
    void putF64 (double v);
    /// LEB128: 7 bits per byte, high bit = more follows. Small values take one byte, which zstd's
    /// Huffman stage then codes close to their entropy.
    void putVarint (std::uint64_t v);
    /// Zigzag-mapped varint (0, -1, 1, -2, ... -> 0, 1, 2, 3, ...).
    void putSignedVarint (std::int64_t v);
    void putBytes (const std::uint8_t* data, std::size_t size);

    const std::vector<std::uint8_t>& bytes () const { return bytes_; }
    std::vector<std::uint8_t>& bytes () { return bytes_; }
    std::size_t size () const { return bytes_.size (); }

  private:
    std::vector<std::uint8_t> bytes_;
  };

  /// Reads little-endian values from a byte range it does not own. \a what names the range in error
  /// messages ("model file x.psm: section ATOM").
  class ByteReader
  {
  public:
    ByteReader (const std::uint8_t* data, std::size_t size, std::string what)
      : data_ (data), size_ (size), what_ (std::move (what)) {}

    std::uint8_t getU8 (const char* field);
    std::uint16_t getU16 (const char* field);
    std::uint32_t getU32 (const char* field);
    std::uint64_t getU64 (const char* field);
    float getF32 (const char* field);
    double getF64 (const char* field);
    /// Refuses encodings longer than 10 bytes or overflowing 64 bits.
    std::uint64_t getVarint (const char* field);
    std::int64_t getSignedVarint (const char* field);
    /// A varint that must be <= \a max (counts): refuses larger values before anything is allocated.
    std::uint64_t getCount (const char* field, std::uint64_t max);
    /// Pointer to the next \a size bytes, which are skipped.
    const std::uint8_t* getBytes (std::size_t size, const char* field);

    std::size_t remaining () const { return size_ - position_; }
    std::size_t position () const { return position_; }
    bool atEnd () const { return position_ == size_; }
    /// Throws unless every byte was consumed (trailing garbage means a lying count somewhere).
    void expectEnd () const;
    /// Throws pcl_sparse::Error "<what>: <message>".
    [[noreturn]] void fail (const std::string& message) const;

  private:
    void need (std::size_t n, const char* field) const;

    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t position_ = 0;
    std::string what_;
  };
} // namespace pcl_sparse
