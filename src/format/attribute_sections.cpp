#include <pcl_sparse/format/attribute_sections.h>

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/frame_quantization.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/format/sparse_code_stream.h>

#include <cmath>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// What ACHN holds besides the channels.
    struct ChannelTable
    {
      CosineBasisKind kind = CosineBasisKind::Dct;
      int frequencies = 12;
      int monomials = 0;  ///< the quadric's monomials after the cosines (shellRank)
      std::vector<AttributeChannelInfo> channels;
      std::vector<double> budgets;  ///< quantised: largest change of a value, per channel
    };

    /// Largest change of channel \a info's values a tolerance allows: of the range (1 for a constant channel),
    /// and never finer than the values' own float precision (2^-24 of the largest magnitude), which a channel
    /// of one huge value asked for (intensity 1e30 everywhere: 1e34 steps, "coefficient too large").
    double
    channelBudget (const AttributeChannelInfo& info, double tolerance)
    {
      const double range = info.upper - info.lower;
      const double magnitude = std::max (std::abs (info.lower), std::abs (info.upper));
      return tolerance * std::max (range > 0.0 ? range : 1.0, std::ldexp (magnitude, -24));
    }

    /// The model's attribute basis; throws unless it is a cosine one.
    const CosineAtoms&
    attributeBasis (const SparseSurfaceModel& model)
    {
      const auto* cosine = dynamic_cast<const CosineAtoms*> (model.attribute_basis.get ());
      if (!cosine)
        throw Error ("encodeModel: the attribute basis must be a cosine basis (CosineDictionary, DctCosineDictionary or QuadricDctDictionary)");
      return *cosine;
    }

    double
    readFiniteF64 (ByteReader& in, const char* field)
    {
      const double v = in.getF64 (field);
      if (!std::isfinite (v))
        in.fail (std::string (field) + " is not finite");
      return v;
    }

    ChannelTable
    readChannelTable (ByteReader& in, bool quantised)
    {
      ChannelTable table;
      const std::uint8_t kind = in.getU8 ("attribute basis kind");
      if (!isBasisKindByte (kind))
        in.fail ("unknown attribute basis kind " + std::to_string (kind));
      table.kind = basisKindOfByte (kind);
      table.monomials = monomialsOfKindByte (kind);
      table.frequencies = in.getU16 ("attribute basis parameter");
      if (table.frequencies < 1 || table.frequencies > CosineAtoms::max_frequencies)
        in.fail ("attribute basis with " + std::to_string (table.frequencies) + " frequencies is out of range");
      const std::size_t count = in.getU8 ("channel count");
      const std::size_t entry = quantised ? 25 : 17;
      if (count < 1 || count > static_cast<std::size_t> (num_attribute_channels) || in.remaining () != count * entry)
        in.fail ("holds " + std::to_string (in.remaining ()) + " bytes for " + std::to_string (count) + " channels");
      std::vector<bool> seen (num_attribute_channels, false);
      for (std::size_t c = 0; c < count; ++c)
      {
        AttributeChannelInfo info;
        const std::uint8_t id = in.getU8 ("channel");
        if (id >= num_attribute_channels || seen[id])
          in.fail ("attribute channel " + std::to_string (id) + " unknown or repeated");
        seen[id] = true;
        info.channel = static_cast<AttributeChannel> (id);
        info.lower = readFiniteF64 (in, "channel lower bound");
        info.upper = readFiniteF64 (in, "channel upper bound");
        if (info.lower > info.upper)
          in.fail ("channel range is empty");
        table.channels.push_back (info);
        if (quantised)
        {
          table.budgets.push_back (readFiniteF64 (in, "channel budget"));
          if (!(table.budgets.back () > 0.0))
            in.fail ("channel budget must be positive");
        }
      }
      in.expectEnd ();
      return table;
    }

    /// "patch 3 channel r", for error messages.
    std::string
    codeName (std::size_t patch, const AttributeChannelInfo& channel)
    {
      return "patch " + std::to_string (patch) + " channel " + attributeChannelName (channel.channel);
    }

    /// AATM and ACOF range-coded (quantised files with the range-coded flag): every byte of both sections.
    void
    decodeRangeCodedAttributes (const ChannelTable& table, ByteReader& atoms, ByteReader& coefficients,
                                SparseSurfaceModel& model)
    {
      RangeDecoder coded_atoms = rangeDecoderOverRest (atoms);
      RangeDecoder coded_coefficients = rangeDecoderOverRest (coefficients);
      std::vector<SparseCodeContexts> contexts (table.channels.size (),
                                                SparseCodeContexts (table.frequencies, table.monomials));
      for (std::size_t p = 0; p < model.patches.size (); ++p)
      {
        std::vector<SparseCode>& codes = model.patches[p].attributes;
        codes.resize (table.channels.size ());
        for (std::size_t c = 0; c < codes.size (); ++c)
        {
          contexts[c].getAtoms (coded_atoms, codeName (p, table.channels[c]), codes[c].atoms);
          contexts[c].getCoefficients (coded_coefficients, codes[c].atoms,
                                       coefficientStep (table.budgets[c], 1.0, codes[c].atoms.size ()),
                                       codes[c].coefficients);
        }
      }
      coded_atoms.expectEnd ();
      coded_coefficients.expectEnd ();
    }
  } // namespace

  AttributeSectionBytes
  encodeAttributeSections (const SparseSurfaceModel& model, double tolerance, bool range_coded)
  {
    const CosineAtoms& basis = attributeBasis (model);
    const int n = basis.frequencies ();  // the codes were checked by SparseSurfaceModel::checkPatches
    const bool quantised = tolerance > 0.0;
    ByteWriter channels, atoms, coefficients;
    channels.putU8 (basisKindByte (basis.kind ()));
    channels.putU16 (static_cast<std::uint16_t> (n));
    channels.putU8 (static_cast<std::uint8_t> (model.attribute_channels.size ()));
    std::vector<double> budgets;
    for (const AttributeChannelInfo& info : model.attribute_channels)
    {
      channels.putU8 (static_cast<std::uint8_t> (info.channel));
      channels.putF64 (info.lower);
      channels.putF64 (info.upper);
      budgets.push_back (channelBudget (info, tolerance));
      if (quantised)
        channels.putF64 (budgets.back ());
    }
    range_coded = range_coded && quantised;
    RangeEncoder coded_atoms, coded_coefficients;
    std::vector<SparseCodeContexts> contexts (model.attribute_channels.size (),
                                              SparseCodeContexts (n, basis.monomials ()));
    for (const PatchCode& patch : model.patches)
      for (std::size_t c = 0; c < patch.attributes.size (); ++c)
      {
        const SparseCode& code = patch.attributes[c];
        // A value moves by at most n_atoms step / 2 (cosine atoms are bounded by 1): the channel's budget.
        if (range_coded)
        {
          const std::vector<std::size_t> order = contexts[c].putAtoms (coded_atoms, code.atoms);
          contexts[c].putCoefficients (coded_coefficients, code.atoms, code.coefficients, order,
                                       coefficientStep (budgets[c], 1.0, order.size ()));
          continue;
        }
        const std::vector<std::size_t> order = putCodeAtoms (atoms, code.atoms, quantised, n, basis.monomials ());
        putCodeCoefficients (coefficients, code.coefficients, order,
                             quantised ? coefficientStep (budgets[c], 1.0, order.size ()) : 0.0);
      }
    if (range_coded)
      return {std::move (channels.bytes ()), coded_atoms.finish (), coded_coefficients.finish ()};
    return {std::move (channels.bytes ()), std::move (atoms.bytes ()), std::move (coefficients.bytes ())};
  }

  std::vector<AttributeChannelInfo>
  decodeAttributeChannels (ByteReader& channels, bool quantised)
  {
    return readChannelTable (channels, quantised).channels;
  }

  void
  decodeAttributeSections (ByteReader& channels, ByteReader& atoms, ByteReader& coefficients, bool quantised,
                           bool range_coded, SparseSurfaceModel& model)
  {
    const ChannelTable table = readChannelTable (channels, quantised);
    const std::size_t m = model.patches.size (), count = table.channels.size ();
    model.attribute_channels = table.channels;
    model.attribute_basis = makeCosineBasis (table.kind, table.frequencies);
    if (range_coded)
    {
      decodeRangeCodedAttributes (table, atoms, coefficients, model);
      return;
    }
    // Every code takes at least its count byte in AATM: checked before the codes are allocated.
    if (atoms.remaining () < m * count)
      atoms.fail ("holds " + std::to_string (atoms.remaining ()) + " bytes, " + std::to_string (m) + " patches x " +
                  std::to_string (count) + " channels need at least " + std::to_string (m * count));
    for (std::size_t p = 0; p < m; ++p)
    {
      std::vector<SparseCode>& codes = model.patches[p].attributes;
      codes.resize (count);
      for (std::size_t c = 0; c < count; ++c)
      {
        getCodeAtoms (atoms, quantised, table.frequencies, codeName (p, table.channels[c]), codes[c].atoms,
                      table.monomials);
        const std::size_t k = codes[c].atoms.size ();
        getCodeCoefficients (coefficients, k, quantised ? coefficientStep (table.budgets[c], 1.0, k) : 0.0,
                             codes[c].coefficients);
      }
    }
    atoms.expectEnd ();
    coefficients.expectEnd ();
  }
} // namespace pcl_sparse
