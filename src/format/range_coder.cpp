#include <pcl_sparse/format/range_coder.h>

#include <pcl_sparse/common/error.h>

#include <stdexcept>

namespace pcl_sparse
{
  namespace
  {
    constexpr int kProbabilityBits = 12;                    ///< probabilities in 1/4096
    constexpr std::uint32_t kOne = 1u << kProbabilityBits;
    constexpr int kAdaptationShift = 4;                     ///< move 1/16 of the way to each bit
    constexpr std::uint32_t kTop = 1u << 24;                ///< renormalise below this range

    /// Adapts \a model to a coded \a bit. p0 stays within [15, 4081]: never 0 or 1.
    void
    adapt (AdaptiveBit& model, bool bit)
    {
      if (bit)
        model.p0 = static_cast<std::uint16_t> (model.p0 - (model.p0 >> kAdaptationShift));
      else
        model.p0 = static_cast<std::uint16_t> (model.p0 + ((kOne - model.p0) >> kAdaptationShift));
    }
  } // namespace

  void
  RangeEncoder::put (AdaptiveBit& model, bool bit)
  {
    used_ = true;
    const std::uint32_t bound = (range_ >> kProbabilityBits) * model.p0;
    if (bit)
    {
      low_ += bound;
      range_ -= bound;
    }
    else
      range_ = bound;
    adapt (model, bit);
    normalise ();
  }

  void
  RangeEncoder::putEqualProbable (bool bit)
  {
    used_ = true;
    range_ >>= 1;
    if (bit)
      low_ += range_;
    normalise ();
  }

  void
  RangeEncoder::normalise ()
  {
    while (range_ < kTop)
    {
      range_ <<= 8;
      shiftLow ();
    }
  }

  void
  RangeEncoder::shiftLow ()
  {
    // low_ holds 32 bits and a carry: a byte can be written only once no carry can reach it any more.
    if (static_cast<std::uint32_t> (low_) < 0xFF000000u || (low_ >> 32) != 0)
    {
      const auto carry = static_cast<std::uint8_t> (low_ >> 32);
      std::uint8_t byte = cache_;
      do
      {
        const auto out = static_cast<std::uint8_t> (byte + carry);
        if (first_)
        {
          if (out != 0)
            throw std::logic_error ("RangeEncoder: the first byte is not 0");
          first_ = false;
        }
        else
          bytes_.push_back (out);
        byte = 0xFF;
      } while (--pending_ != 0);
      cache_ = static_cast<std::uint8_t> (low_ >> 24);
    }
    ++pending_;
    low_ = (low_ & 0x00FFFFFFu) << 8;
  }

  std::vector<std::uint8_t>
  RangeEncoder::finish ()
  {
    if (!used_)
      return {};
    for (int i = 0; i < 5; ++i)
      shiftLow ();
    return std::move (bytes_);
  }

  RangeDecoder::RangeDecoder (const std::uint8_t* data, std::size_t size, std::string what)
    : data_ (data), size_ (size), what_ (std::move (what))
  {
  }

  void
  RangeDecoder::start ()
  {
    started_ = true;
    for (int i = 0; i < 4; ++i)
      code_ = (code_ << 8) | nextByte ();
    if (code_ >= range_)
      fail ("is not a range-coded stream");
  }

  std::uint8_t
  RangeDecoder::nextByte ()
  {
    if (position_ >= size_)
      fail ("ends before its last value (truncated or corrupt)");
    return data_[position_++];
  }

  void
  RangeDecoder::normalise ()
  {
    while (range_ < kTop)
    {
      range_ <<= 8;
      code_ = (code_ << 8) | nextByte ();
    }
    // Holds for every stream an encoder wrote: code_ is the offset of its value in the current interval.
    if (code_ >= range_)
      fail ("is corrupt (its value left the coder's interval)");
  }

  bool
  RangeDecoder::get (AdaptiveBit& model)
  {
    if (!started_)
      start ();
    const std::uint32_t bound = (range_ >> kProbabilityBits) * model.p0;
    const bool bit = code_ >= bound;
    if (bit)
    {
      code_ -= bound;
      range_ -= bound;
    }
    else
      range_ = bound;
    adapt (model, bit);
    normalise ();
    return bit;
  }

  bool
  RangeDecoder::getEqualProbable ()
  {
    if (!started_)
      start ();
    range_ >>= 1;
    const bool bit = code_ >= range_;
    if (bit)
      code_ -= range_;
    normalise ();
    return bit;
  }

  void
  RangeDecoder::expectEnd () const
  {
    if (position_ != size_)
      fail (std::to_string (size_ - position_) + " unexpected trailing bytes after its last value");
  }

  void
  RangeDecoder::fail (const std::string& message) const
  {
    throw Error (what_ + ": " + message);
  }

  BitTreeModel::BitTreeModel (int bits)
    : bits_ (bits)
  {
    if (bits < 1 || bits > 16)
      throw std::invalid_argument ("BitTreeModel: bits must be in 1..16");
    nodes_.resize (std::size_t (1) << bits);
  }

  void
  BitTreeModel::put (RangeEncoder& out, std::uint32_t value)
  {
    if (value > max ())
      throw std::invalid_argument ("BitTreeModel: value too wide");
    std::size_t node = 1;
    for (int b = bits_ - 1; b >= 0; --b)
    {
      const bool bit = (value >> b) & 1u;
      out.put (nodes_[node], bit);
      node = 2 * node + (bit ? 1 : 0);
    }
  }

  std::uint32_t
  BitTreeModel::get (RangeDecoder& in)
  {
    std::size_t node = 1;
    for (int b = 0; b < bits_; ++b)
      node = 2 * node + (in.get (nodes_[node]) ? 1 : 0);
    return static_cast<std::uint32_t> (node - (std::size_t (1) << bits_));
  }

  void
  SignedIntegerModel::put (RangeEncoder& out, std::int64_t value)
  {
    out.put (nonzero_, value != 0);
    if (value == 0)
      return;
    out.put (negative_, value < 0);
    const std::uint64_t magnitude = value < 0 ? 0 - static_cast<std::uint64_t> (value) : static_cast<std::uint64_t> (value);
    if (magnitude >> 63)
      throw std::invalid_argument ("SignedIntegerModel: magnitude of 2^63");
    int e = 0;
    while ((magnitude >> (e + 1)) != 0)
      ++e;
    for (int i = 0; i < e; ++i)
      out.put (exponent_[i], true);
    if (e < max_exponent)
      out.put (exponent_[e], false);
    if (e >= 1)
      out.put (below_leading_[e], (magnitude >> (e - 1)) & 1u);
    for (int b = e - 2; b >= 0; --b)
      out.putEqualProbable ((magnitude >> b) & 1u);
  }

  std::int64_t
  SignedIntegerModel::get (RangeDecoder& in)
  {
    if (!in.get (nonzero_))
      return 0;
    const bool negative = in.get (negative_);
    int e = 0;
    while (e < max_exponent && in.get (exponent_[e]))
      ++e;
    std::uint64_t magnitude = 1;
    if (e >= 1)
      magnitude = (magnitude << 1) | (in.get (below_leading_[e]) ? 1u : 0u);
    for (int b = e - 2; b >= 0; --b)
      magnitude = (magnitude << 1) | (in.getEqualProbable () ? 1u : 0u);
    return negative ? -static_cast<std::int64_t> (magnitude) : static_cast<std::int64_t> (magnitude);
  }
} // namespace pcl_sparse
