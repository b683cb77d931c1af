#pragma once
/// \file range_coder.h
/// An adaptive binary range coder (the scheme of LZMA's: 32-bit range, carry propagation through a cached
/// byte, probabilities in 1/4096 that move 1/16 of the way towards each coded bit) and the integer codings
/// built on it. The model file codes its per-patch fields with it (docs/FORMAT.md, "Range-coded fields"):
/// each field's bits get their own probability, which adapts to that model's statistics, where zstd over
/// varints only sees bytes.
///
/// A stream of coded bits takes the sum of -log2 p(bit) bits plus 4 bytes; a stream of no bits takes none.
/// The decoder reads exactly the bytes the encoder wrote: reading past them, or leaving some unread, means
/// the stream is not what the encoder produced, and both are refused.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Probability that the next bit is 0, in 1/4096, adapted after every bit coded with it.
  struct AdaptiveBit
  {
    std::uint16_t p0 = 2048;
  };

  /// Codes bits into bytes.
  class RangeEncoder
  {
  public:
    /// Codes \a bit with (and then adapts) \a model.
    void put (AdaptiveBit& model, bool bit);
    /// Codes \a bit at probability 1/2 (for bits close to uniform: the low bits of large numbers).
    void putEqualProbable (bool bit);
    /// Flushes the coder and returns the stream; the encoder is spent.
    std::vector<std::uint8_t> finish ();

  private:
    /// Shifts bytes out while the range is below 2^24.
    void normalise ();
    void shiftLow ();

    std::uint64_t low_ = 0;
    std::uint32_t range_ = 0xFFFFFFFFu;
    std::uint8_t cache_ = 0;
    std::uint64_t pending_ = 1;  ///< bytes waiting for a possible carry: the cached byte and 0xFF bytes after it
    bool first_ = true;          ///< the scheme's first byte is always 0: not stored
    bool used_ = false;          ///< a bit was coded (an empty stream is no bytes)
    std::vector<std::uint8_t> bytes_;
  };

  /// Decodes what RangeEncoder wrote, from a byte range it does not own.
  class RangeDecoder
  {
  public:
    /// \param[in] data  first byte; the range must outlive the decoder
    /// \param[in] size  number of bytes
    /// \param[in] what  names the stream in error messages ("model file x.psm: section ATOM")
    RangeDecoder (const std::uint8_t* data, std::size_t size, std::string what);

    /// Decodes one bit with (and then adapts) \a model.
    bool get (AdaptiveBit& model);
    /// Decodes a bit coded by putEqualProbable.
    bool getEqualProbable ();
    /// Throws pcl_sparse::Error unless every byte was read (the stream ended where its encoder ended it;
    /// no bytes if no bit was decoded).
    void expectEnd () const;
    /// Throws pcl_sparse::Error "<what>: <message>".
    [[noreturn]] void fail (const std::string& message) const;

  private:
    void start ();
    void normalise ();
    std::uint8_t nextByte ();

    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t position_ = 0;
    std::uint32_t range_ = 0xFFFFFFFFu;
    std::uint32_t code_ = 0;
    bool started_ = false;  ///< the first 4 bytes are read with the first bit
    std::string what_;
  };

  /// An unsigned number of a fixed number of bits, coded from its top bit down, each bit with the
  /// probability of the bits above it (a binary tree of 2^bits - 1 models): learns any distribution of
  /// small numbers, such as counts.
  class BitTreeModel
  {
  public:
    /// \param[in] bits  width of the numbers (1..16)
    explicit BitTreeModel (int bits);
    /// Largest number it codes.
    std::uint32_t max () const { return (1u << bits_) - 1u; }

    /// Codes \a value (<= max ()).
    void put (RangeEncoder& out, std::uint32_t value);
    /// Decodes a value.
    std::uint32_t get (RangeDecoder& in);

  private:
    int bits_;
    std::vector<AdaptiveBit> nodes_;
  };

  /// A signed integer as: zero or not; its sign; the exponent e of its magnitude m (2^e <= m < 2^(e+1)) in
  /// unary, each position with its own model; the bit below the leading one with a model per e; the
  /// lower bits at probability 1/2. Learns magnitudes of any scale in a few dozen values.
  class SignedIntegerModel
  {
  public:
    /// Largest exponent: magnitudes up to 2^63 - 1.
    static constexpr int max_exponent = 62;

    /// Codes \a value (|value| < 2^63).
    void put (RangeEncoder& out, std::int64_t value);
    /// Decodes a value (any value of the coding is a valid int64; callers check their own range).
    std::int64_t get (RangeDecoder& in);

  private:
    AdaptiveBit nonzero_;
    AdaptiveBit negative_;
    AdaptiveBit exponent_[max_exponent + 1];
    AdaptiveBit below_leading_[max_exponent + 1];
  };
} // namespace pcl_sparse
