#pragma once
/// \file model_sections.h
/// A model file's sections without their container (docs/FORMAT.md): what every part of a model shares (the
/// header's flags and basis, the quantisation parameters QUAN and the attribute channels ACHN, both chosen over the
/// whole model) and, for runs of patches, the raw payloads of the per-patch sections. A version-1 file
/// (model_file.h) holds one run covering every patch, each section framed and compressed on its own; a tiled file
/// (tiled_model_file.h, version 3) stores the shared part once and each tile's run with a few bytes of framing.
/// Quantising with the whole model's parameters makes a run decode to exactly the patches the version-1 file of the
/// whole model gives.

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/format/model_file.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  struct FootprintSlack;  // resampling/footprint_slack.h

  /// The header's flag bits (docs/FORMAT.md), the same in version-1 and tiled files.
  namespace header_flag
  {
    constexpr std::uint16_t quantised = 1;
    constexpr std::uint16_t vertices = 2;             ///< VERT present
    constexpr std::uint16_t attributes = 4;           ///< ACHN, AATM, ACOF present
    constexpr std::uint16_t range_coded = 8;          ///< quantised: FRAM FOOT ATOM COEF AATM ACOF range-coded
    /// Quantised: FOOT codes coarse angles and the others only where needed (footprint_coding.h); files
    /// without it (written before 2026-12-01) keep every stride-th angle of a footprint.
    constexpr std::uint16_t adaptive_footprints = 16;
    /// Range-coded: SEED codes each seed as steps from the previous patch's (seed_coding.h); files without
    /// it (written before 2026-12-02) store byte planes.
    constexpr std::uint16_t coded_seeds = 32;
    constexpr std::uint16_t known = 63;               ///< every flag this build reads
  } // namespace header_flag

  /// What the parts of a model share.
  struct SharedModelFields
  {
    std::uint16_t flags = 0;                 ///< as the version-1 header (header_flag)
    std::uint8_t basis_kind = 0;             ///< 1 the paper's cosines, 2 half-period cosines, 3 those and the quadric
    std::uint16_t basis_parameter = 0;       ///< n, frequencies per axis
    std::uint64_t num_input_vertices = 0;    ///< of the whole input
    double bbox_diagonal = 0.0;              ///< of the whole input
    double tolerance = 0.0;                  ///< 0: lossless
    std::vector<std::uint8_t> quantisation;  ///< QUAN payload (quantised only)
    std::vector<std::uint8_t> channels;      ///< ACHN payload (with attributes only)
  };

  /// A model as its shared fields and, per run of patches, its per-patch sections' raw payloads.
  struct ModelSections
  {
    SharedModelFields shared;                                   ///< as above
    std::vector<std::vector<std::vector<std::uint8_t>>> runs;   ///< per run, per tag of runSectionTags (shared.flags)
  };

  /// \brief The basis of a header as pcl_sparse_info prints it, e.g. "dct cosine 12x12".
  std::string
  basisDescription (std::uint8_t basis_kind, std::uint16_t basis_parameter);

  /// \brief The basis kind byte of a cosine basis (docs/FORMAT.md: 1 paper, 2 dct, 3 quadric), as the header
  /// and the attribute channel table ACHN store it.
  std::uint8_t
  basisKindByte (CosineBasisKind kind);

  /// \brief Whether \a byte is a basis kind this build reads.
  bool
  isBasisKindByte (std::uint8_t byte);

  /// \brief The cosine basis of a kind byte (isBasisKindByte).
  CosineBasisKind
  basisKindOfByte (std::uint8_t byte);

  /// \brief Monomial atoms after the cosines of a kind byte (shellRank): 5 for the quadric, else 0.
  int
  monomialsOfKindByte (std::uint8_t byte);

  class ByteReader;
  class ByteWriter;

  /// \brief Appends a patch's input vertex numbers as section VERT stores them (its (x', y') follow there):
  /// the count, then each number's difference from the previous one as a signed varint.
  /// \param[in,out] out            receives the bytes
  /// \param[in] vertices           the numbers
  /// \param[in] num_input_vertices the numbers' bound
  /// \throws pcl_sparse::Error for a number outside [0, \a num_input_vertices)
  void
  putVertexNumbers (ByteWriter& out, const std::vector<int>& vertices, std::uint64_t num_input_vertices);

  /// \brief Reads putVertexNumbers' numbers into \a vertices.
  /// \param[in,out] in             the bytes
  /// \param[in] num_input_vertices the numbers' bound
  /// \param[in] bytes_after        bytes that follow each vertex's number (its (x', y') in VERT): bound the count
  /// \param[in] patch              the patch's index, for error messages
  /// \param[out] vertices          the numbers
  /// \throws pcl_sparse::Error for a count or number out of range or bytes missing
  void
  getVertexNumbers (ByteReader& in, std::uint64_t num_input_vertices, std::size_t bytes_after, std::size_t patch,
                    std::vector<int>& vertices);

  /// \brief The per-patch sections of a file with \a flags, in file order: SEED FRAM RADI FOOT ATOM COEF
  /// [VERT] [AATM ACOF].
  std::vector<std::string>
  runSectionTags (std::uint16_t flags);

  /// \brief Encodes \a model (checked as encodeModel does) with quantisation chosen over all its patches.
  /// \param[in] model    the model
  /// \param[in] options  as for encodeModel (zstd_level unused)
  /// \param[in] runs     (first patch, count) of each run; runs may be in any order
  /// \param[in] slack    the whole model's footprintSlack (resampling/footprint_slack.h) if found beforehand;
  ///                     null: each run's is found where the options take it
  /// \return the shared fields and each run's sections
  /// \throws pcl_sparse::Error as encodeModel, or for runs outside the model or a slack not the model's
  ModelSections
  encodeModelSections (const SparseSurfaceModel& model, const ModelWriteOptions& options,
                       const std::vector<std::pair<std::size_t, std::size_t>>& runs,
                       const std::vector<FootprintSlack>* slack = nullptr);

  /// \brief Checks the shared fields as the version-1 reader checks its header (flags, basis, counts,
  /// tolerance; QUAN and ACHN are checked by decodeModelSections).
  /// \throws pcl_sparse::Error "<name>: ..." for anything out of range
  void
  checkSharedModelFields (const SharedModelFields& shared, const std::string& name);

  /// \brief Decodes one run of \a num_patches patches.
  /// \param[in] shared       the shared fields (checkSharedModelFields passed)
  /// \param[in] num_patches  patches of the run
  /// \param[in] payloads     (first byte, size) per tag of runSectionTags (shared.flags)
  /// \param[in] name         names the data in error messages ("<name>: section SEED: ...")
  /// \return the run as a model (basis, vertex count, diagonal and attribute channels of the shared fields)
  /// \throws pcl_sparse::Error for anything malformed
  SparseSurfaceModel
  decodeModelSections (const SharedModelFields& shared, std::size_t num_patches,
                       const std::vector<std::pair<const std::uint8_t*, std::size_t>>& payloads, const std::string& name);
} // namespace pcl_sparse
