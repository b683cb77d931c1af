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
    /// Appends one byte.
    void putU8 (std::uint8_t v) { bytes_.push_back (v); }
    /// Appends \a v as 2 bytes, little endian.
    void putU16 (std::uint16_t v);
    /// Appends \a v as 4 bytes, little endian.
    void putU32 (std::uint32_t v);
    /// Appends \a v as 8 bytes, little endian.
    void putU64 (std::uint64_t v);
    /// Appends the IEEE 754 bits of \a v as 4 bytes, little endian.
    void putF32 (float v);
    /// Appends the IEEE 754 bits of \a v as 8 bytes, little endian.
    void putF64 (double v);
    /// Appends \a v as LEB128: 7 bits per byte, high bit = more follows. Small values take one byte,
    /// which zstd's Huffman stage then codes close to their entropy.
    void putVarint (std::uint64_t v);
    /// Appends \a v as a zigzag-mapped varint (0, -1, 1, -2, ... -> 0, 1, 2, 3, ...).
    void putSignedVarint (std::int64_t v);
    /// Appends \a size bytes from \a data.
    void putBytes (const std::uint8_t* data, std::size_t size);

    /// The bytes written so far.
    const std::vector<std::uint8_t>& bytes () const { return bytes_; }
    /// The bytes written so far, for moving out or patching in place.
    std::vector<std::uint8_t>& bytes () { return bytes_; }
    /// Number of bytes written so far.
    std::size_t size () const { return bytes_.size (); }

  private:
    std::vector<std::uint8_t> bytes_;
  };

  /// Reads little-endian values from a byte range it does not own. Every get* names the field it reads
  /// (\a field) and throws pcl_sparse::Error "<what>: ... <field>" when the range ends before it.
  class ByteReader
  {
  public:
    /// Reads from a byte range.
    /// \param[in] data  first byte; the range must outlive the reader
    /// \param[in] size  number of bytes
    /// \param[in] what  names the range in error messages ("model file x.psm: section ATOM")
    ByteReader (const std::uint8_t* data, std::size_t size, std::string what)
      : data_ (data), size_ (size), what_ (std::move (what)) {}

    /// Reads one byte.
    std::uint8_t getU8 (const char* field);
    /// Reads 2 bytes, little endian.
    std::uint16_t getU16 (const char* field);
    /// Reads 4 bytes, little endian.
    std::uint32_t getU32 (const char* field);
    /// Reads 8 bytes, little endian.
    std::uint64_t getU64 (const char* field);
    /// Reads an IEEE 754 float from 4 bytes, little endian.
    float getF32 (const char* field);
    /// Reads an IEEE 754 double from 8 bytes, little endian.
    double getF64 (const char* field);
    /// Reads a LEB128 varint; refuses encodings longer than 10 bytes or overflowing 64 bits.
    std::uint64_t getVarint (const char* field);
    /// Reads a zigzag-mapped varint (ByteWriter::putSignedVarint).
    std::int64_t getSignedVarint (const char* field);
    /// Reads a count: a varint that must not exceed a bound, refused before anything is allocated.
    /// \param[in] field  name of the field, for error messages
    /// \param[in] max    largest value accepted
    /// \return the count
    /// \throws pcl_sparse::Error if the range ends or the value exceeds \a max
    std::uint64_t getCount (const char* field, std::uint64_t max);
    /// Skips the next bytes.
    /// \param[in] size   number of bytes
    /// \param[in] field  name of the field, for error messages
    /// \return pointer to the first skipped byte (inside the reader's range)
    /// \throws pcl_sparse::Error if fewer than \a size bytes remain
    const std::uint8_t* getBytes (std::size_t size, const char* field);

    /// Number of bytes not read yet.
    std::size_t remaining () const { return size_ - position_; }
    /// Number of bytes read so far.
    std::size_t position () const { return position_; }
    /// Whether every byte was read.
    bool atEnd () const { return position_ == size_; }
    /// Throws pcl_sparse::Error unless every byte was consumed (trailing garbage means a lying count
    /// somewhere).
    void expectEnd () const;
    /// Throws pcl_sparse::Error "<what>: <message>".
    /// \param[in] message  the problem
    [[noreturn]] void fail (const std::string& message) const;
    /// What the range is called in error messages.
    const std::string& what () const { return what_; }

  private:
    void need (std::size_t n, const char* field) const;

    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t position_ = 0;
    std::string what_;
  };
} // namespace pcl_sparse
