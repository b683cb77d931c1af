#include <pcl_sparse/format/footprint_coding.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    constexpr unsigned kMaxStrideLog2 = 12;

    unsigned
    levelMask (const FootprintLevels& levels)
    {
      return (1u << levels.bits) - 1u;
    }

    unsigned
    levelOf (float extent, const FootprintLevels& levels)
    {
      return std::min (levelMask (levels), static_cast<unsigned> (std::lround (static_cast<double> (extent) / levels.step)));
    }

    /// The extent a reader draws at \a w in [0, 1] of the way between levels \a a and \a b.
    double
    interpolatedExtent (unsigned a, unsigned b, double w, const FootprintLevels& levels)
    {
      return ((1.0 - w) * static_cast<double> (a) + w * static_cast<double> (b)) * levels.step;
    }

    /// What the middle level of an interval is coded against.
    unsigned
    midpointPrediction (unsigned a, unsigned b)
    {
      return (a + b + 1) / 2;
    }

    /// The models of an interval's split and middle level: by its depth and by how far apart its ends' levels
    /// are (0, 1, 2-3, more: a steep stretch of border is split more often, and its middles stray more).
    int
    intervalContext (int depth, unsigned a, unsigned b)
    {
      const unsigned apart = a > b ? a - b : b - a;
      const int ends = apart == 0 ? 0 : apart == 1 ? 1 : apart <= 3 ? 2 : 3;
      return std::min (depth, FootprintContexts::depth_contexts - 1) * FootprintContexts::end_contexts + ends;
    }

    // ---- writing: the symbols in their order, to either layout ------------------------------------

    struct ByteFootprintSymbols
    {
      ByteWriter& out;
      void angles (std::uint32_t k) { out.putVarint (k); }
      void strideLog2 (unsigned s) { out.putU8 (static_cast<std::uint8_t> (s)); }
      void level (bool, unsigned delta) { out.putU8 (static_cast<std::uint8_t> (delta)); }
      void split (int, bool yes) { out.putU8 (yes ? 1 : 0); }
      void residual (int, unsigned r) { out.putU8 (static_cast<std::uint8_t> (r)); }
    };

    struct RangeFootprintSymbols
    {
      RangeEncoder& out;
      FootprintContexts& c;
      void angles (std::uint32_t k) { c.angles.put (out, k); }
      void strideLog2 (unsigned s) { c.stride_log2.put (out, s); }
      void level (bool first, unsigned delta) { (first ? c.first_level : c.level_delta).put (out, delta); }
      void split (int context, bool yes) { c.split[context].put (out, yes ? 1u : 0u); }
      void residual (int context, unsigned r) { c.residual[context].put (out, r); }
    };

    /// Where each extent of a footprint may be drawn: references to the slack's vectors or to the extents.
    struct FootprintBounds
    {
      const std::vector<float>& lower;
      const std::vector<float>& upper;
      const std::vector<char>* knife_edge;  ///< one per angle, or nullptr: no angle is one
      const std::vector<char>* trimmed;     ///< one per angle (PatchFootprint::trimmed), or nullptr: none

      bool isKnifeEdge (std::size_t a) const { return knife_edge && (*knife_edge)[a]; }
      bool isTrimmed (std::size_t a) const { return trimmed && (*trimmed)[a]; }
    };

    /// How far outside a trim cut its border may be drawn, relative: the extent's float rounding (an extent
    /// that is a whole number of levels but for it keeps that level).
    constexpr double kTrimCutRounding = 1e-6;

    /// The level coded for angle \a a: the nearest, but at a trim cut the nearest not outside it (past the
    /// cut the code's normal points away from the surface; within a level inside, also as a knife edge needs).
    unsigned
    codedLevel (const std::vector<float>& extent, const FootprintBounds& bounds, std::size_t a, const FootprintLevels& levels)
    {
      if (!bounds.isTrimmed (a))
        return levelOf (extent[a], levels);
      const double below = std::floor (static_cast<double> (extent[a]) * (1.0 + kTrimCutRounding) / levels.step);
      return std::min (levelMask (levels), static_cast<unsigned> (below));
    }

    /// How far the extents strictly inside [a, a + len) (angles mod K) lie from the line between the levels at
    /// its ends, summed over the angles: the area (steps x angles) between the border drawn and the true one,
    /// where the true one may be drawn anywhere in [lower, upper] (FootprintSlack; both the extent without).
    /// 0 where more angles could not change the drawing: every level inside already is the line's, rounded
    /// (a round footprint whose extent lies between two levels).
    double
    intervalDeviation (const std::vector<float>& extent, const FootprintBounds& bounds, const std::vector<unsigned>& level,
                       std::size_t a, std::size_t len, const FootprintLevels& levels)
    {
      const std::size_t b = (a + len) % extent.size ();
      double deviation = 0.0;
      bool improvable = false;
      for (std::size_t j = 1; j < len; ++j)
      {
        const double drawn = interpolatedExtent (level[a], level[b], static_cast<double> (j) / static_cast<double> (len), levels);
        if (bounds.isKnifeEdge (a + j) && drawn < static_cast<double> (extent[a + j]) - levels.step)
          return std::numeric_limits<double>::infinity ();  // over a level in at a knife edge: split
        if (bounds.isTrimmed (a + j) && drawn > static_cast<double> (extent[a + j]) * (1.0 + kTrimCutRounding))
          return std::numeric_limits<double>::infinity ();  // past a trim cut: split
        const double nearest = std::clamp (drawn, static_cast<double> (bounds.lower[a + j]), static_cast<double> (bounds.upper[a + j]));
        deviation += std::abs (drawn - nearest);
        improvable = improvable || levelOf (static_cast<float> (nearest), levels) != levelOf (static_cast<float> (drawn), levels);
      }
      return improvable ? deviation : 0.0;
    }

    /// Codes the splits of [a, a + len); whether any was split.
    template <typename Symbols>
    bool
    putInterval (Symbols& symbols, const std::vector<float>& extent, const FootprintBounds& bounds, std::vector<unsigned>& level,
                 std::size_t a, std::size_t len, int depth, const FootprintLevels& levels, const FootprintRefinement& refinement)
    {
      if (len < 2)
        return false;
      const bool split = refinement.max_deviation_steps > 0.0 &&
                         intervalDeviation (extent, bounds, level, a, len, levels) > refinement.max_deviation_steps * levels.step;
      const std::size_t half = len / 2, middle = a + half, b = (a + len) % extent.size ();
      const int context = intervalContext (depth, level[a], level[b]);
      symbols.split (context, split);
      if (!split)
        return false;
      level[middle] = codedLevel (extent, bounds, middle, levels);
      symbols.residual (context, (level[middle] - midpointPrediction (level[a], level[b])) & levelMask (levels));
      putInterval (symbols, extent, bounds, level, a, half, depth + 1, levels, refinement);
      putInterval (symbols, extent, bounds, level, middle, half, depth + 1, levels, refinement);
      return true;
    }

    /// \return the number of angles a reader gets
    template <typename Symbols>
    std::size_t
    putFootprintSymbols (Symbols& symbols, const PatchFootprint& footprint, const FootprintLevels& levels,
                         const FootprintRefinement& refinement, const FootprintSlack* slack)
    {
      const std::vector<float>& extent = footprint.extent;
      const std::size_t k = extent.size ();
      const bool slack_given = slack && slack->lower.size () == k && slack->upper.size () == k;
      const bool knife_given = slack && slack->knife_edge.size () == k;
      const FootprintBounds bounds{slack_given ? slack->lower : extent, slack_given ? slack->upper : extent,
                                   knife_given ? &slack->knife_edge : nullptr,
                                   footprint.trimmed.size () == k ? &footprint.trimmed : nullptr};
      std::size_t stride = 1;
      unsigned stride_log2 = 0;
      while (refinement.max_coarse_angles > 0 && k / stride > static_cast<std::size_t> (refinement.max_coarse_angles) &&
             k % (2 * stride) == 0)
      {
        stride *= 2;
        ++stride_log2;
      }
      symbols.angles (static_cast<std::uint32_t> (k));
      symbols.strideLog2 (stride_log2);
      std::vector<unsigned> level (k, 0);
      unsigned previous = 0;
      for (std::size_t a = 0; a < k; a += stride)
      {
        level[a] = codedLevel (extent, bounds, a, levels);
        symbols.level (a == 0, (level[a] - previous) & levelMask (levels));
        previous = level[a];
      }
      bool refined = false;
      for (std::size_t a = 0; a < k; a += stride)
        refined = putInterval (symbols, extent, bounds, level, a, stride, 0, levels, refinement) || refined;
      return refined ? k : k / stride;
    }

    // ---- reading ------------------------------------------------------------------------------------

    struct ByteFootprintSource
    {
      ByteReader& in;
      unsigned mask;
      [[noreturn]] void fail (const std::string& message) const { in.fail (message); }
      std::uint32_t angles ()
      {
        // Not bounded by the bytes left: interpolated angles take none.
        return static_cast<std::uint32_t> (in.getCount ("footprint angles", max_file_footprint_angles));
      }
      unsigned strideLog2 () { return in.getU8 ("footprint stride"); }
      unsigned level (bool) { return byteAtMost (mask, "extent level"); }
      bool split (int) { return byteAtMost (1, "footprint split") != 0; }
      unsigned residual (int) { return byteAtMost (mask, "extent level"); }
      unsigned
      byteAtMost (unsigned max, const char* field)
      {
        const unsigned v = in.getU8 (field);
        if (v > max)
          in.fail (std::string (field) + " out of range");
        return v;
      }
    };

    struct RangeFootprintSource
    {
      RangeDecoder& in;
      FootprintContexts& c;
      [[noreturn]] void fail (const std::string& message) const { in.fail (message); }
      std::uint32_t angles () { return c.angles.get (in); }
      unsigned strideLog2 () { return c.stride_log2.get (in); }
      unsigned level (bool first) { return (first ? c.first_level : c.level_delta).get (in); }
      bool split (int context) { return c.split[context].get (in) != 0; }
      unsigned residual (int context) { return c.residual[context].get (in); }
    };

    /// Reads the splits of [a, a + len), marking the coded angles in \a coded; whether any was split.
    template <typename Source>
    bool
    getInterval (Source& source, std::vector<unsigned>& level, std::vector<char>& coded, std::size_t a, std::size_t len,
                 int depth, unsigned mask)
    {
      if (len < 2)
        return false;
      const std::size_t half = len / 2, middle = a + half, b = (a + len) % level.size ();
      const int context = intervalContext (depth, level[a], level[b]);
      if (!source.split (context))
        return false;
      level[middle] = (midpointPrediction (level[a], level[b]) + source.residual (context)) & mask;
      coded[middle] = 1;
      getInterval (source, level, coded, a, half, depth + 1, mask);
      getInterval (source, level, coded, middle, half, depth + 1, mask);
      return true;
    }

    template <typename Source>
    void
    getFootprintSymbols (Source& source, const FootprintLevels& levels, std::size_t patch, PatchFootprint& footprint)
    {
      const std::string name = "patch " + std::to_string (patch);
      const std::uint32_t k = source.angles ();
      if (k > max_file_footprint_angles)
        source.fail (name + " has " + std::to_string (k) + " footprint angles, more than " +
                     std::to_string (max_file_footprint_angles));
      const unsigned stride_log2 = source.strideLog2 ();
      const std::size_t stride = std::size_t{1} << std::min (stride_log2, kMaxStrideLog2);
      if (stride_log2 > kMaxStrideLog2 || k % stride != 0)
        source.fail (name + " footprint stride 2^" + std::to_string (stride_log2) + " does not divide its " +
                     std::to_string (k) + " angles");
      if (!std::isfinite (static_cast<float> (levelMask (levels) * levels.step)))
        source.fail (name + " extent is not finite");
      const unsigned mask = levelMask (levels);
      std::vector<unsigned> level (k, 0);
      std::vector<char> coded (k, 0);
      unsigned previous = 0;
      for (std::size_t a = 0; a < k; a += stride)
      {
        previous = (previous + source.level (a == 0)) & mask;
        level[a] = previous;
        coded[a] = 1;
      }
      bool refined = false;
      for (std::size_t a = 0; a < k; a += stride)
        refined = getInterval (source, level, coded, a, stride, 0, mask) || refined;

      if (!refined)  // the coarse angles draw it
      {
        footprint.extent.resize (k / stride);
        for (std::size_t i = 0; i < footprint.extent.size (); ++i)
          footprint.extent[i] = static_cast<float> (level[i * stride] * levels.step);
        return;
      }
      // Every angle, linear between the coded ones (what resampling draws from them).
      footprint.extent.resize (k);
      for (std::size_t a = 0; a < k;)
      {
        std::size_t b = a + 1;
        while (b < k && !coded[b])
          ++b;
        const std::size_t len = b - a;
        for (std::size_t j = 0; j < len; ++j)
          footprint.extent[a + j] = static_cast<float> (
            interpolatedExtent (level[a], level[b % k], static_cast<double> (j) / static_cast<double> (len), levels));
        a = b;
      }
    }
  } // namespace

  FootprintContexts::FootprintContexts (int bits)
    : first_level (bits), level_delta (bits), split (depth_contexts * end_contexts, BitTreeModel (1)),
      residual (depth_contexts * end_contexts, BitTreeModel (bits))
  {}

  std::size_t
  putFootprint (ByteWriter& out, const PatchFootprint& footprint, const FootprintLevels& levels,
                const FootprintRefinement& refinement, const FootprintSlack* slack)
  {
    ByteFootprintSymbols symbols{out};
    return putFootprintSymbols (symbols, footprint, levels, refinement, slack);
  }

  std::size_t
  putFootprint (RangeEncoder& out, FootprintContexts& contexts, const PatchFootprint& footprint,
                const FootprintLevels& levels, const FootprintRefinement& refinement, const FootprintSlack* slack)
  {
    RangeFootprintSymbols symbols{out, contexts};
    return putFootprintSymbols (symbols, footprint, levels, refinement, slack);
  }

  void
  getFootprint (ByteReader& in, const FootprintLevels& levels, std::size_t patch, PatchFootprint& footprint)
  {
    ByteFootprintSource source{in, levelMask (levels)};
    getFootprintSymbols (source, levels, patch, footprint);
  }

  void
  getFootprint (RangeDecoder& in, FootprintContexts& contexts, const FootprintLevels& levels, std::size_t patch,
                PatchFootprint& footprint)
  {
    RangeFootprintSource source{in, contexts};
    getFootprintSymbols (source, levels, patch, footprint);
  }
} // namespace pcl_sparse
