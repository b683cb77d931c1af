#pragma once
/// \file attribute_sections.h
/// The model file's attribute sections (docs/FORMAT.md): ACHN, the colour / intensity channels and the
/// basis their codes are over; AATM and ACOF, per patch and channel one sparse code (sparse_code_stream.h).
/// Present only in files of models with attributes (header flag bit 2), so files without them are unchanged.

#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/model/sparse_surface_model.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Payloads of the three sections.
  struct AttributeSectionBytes
  {
    std::vector<std::uint8_t> channels;      ///< ACHN
    std::vector<std::uint8_t> atoms;         ///< AATM
    std::vector<std::uint8_t> coefficients;  ///< ACOF
  };

  /// \brief Encodes the attributes of \a model. Lossless when \a tolerance is 0; else quantised so that no
  /// attribute value of any patch, anywhere, moves by more than \a tolerance x its channel's range (upper -
  /// lower; 1 for a channel of range 0). Throws pcl_sparse::Error ("encodeModel: ...") for attributes the
  /// format cannot hold: a basis other than the cosine ones, repeated or unknown channels, a patch without
  /// one code per channel, atoms outside the basis or repeated, non-finite values.
  /// \param[in] model a model with attribute channels
  /// \param[in] tolerance 0, or > 0 (fraction of each channel's range)
  /// \param[in] range_coded quantised only: AATM and ACOF range-coded, each channel with its own models
  ///            (SparseCodeContexts), instead of varints
  AttributeSectionBytes
  encodeAttributeSections (const SparseSurfaceModel& model, double tolerance, bool range_coded);

  /// \brief Decodes the three sections into \a model (attribute_channels, attribute_basis and every patch's
  /// attributes; model.patches already sized). Every count is checked against the bytes left before
  /// anything is allocated (range-coded: the patch count, bounded by the caller); failures throw
  /// pcl_sparse::Error through the readers (naming the section).
  void
  decodeAttributeSections (ByteReader& channels, ByteReader& atoms, ByteReader& coefficients, bool quantised,
                           bool range_coded, SparseSurfaceModel& model);

  /// \brief The channels section alone (for inspectModel): the channels with their ranges.
  std::vector<AttributeChannelInfo>
  decodeAttributeChannels (ByteReader& channels, bool quantised);
} // namespace pcl_sparse
