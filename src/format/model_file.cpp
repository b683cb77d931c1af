#include <pcl_sparse/format/model_file.h>

#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/radius_grid.h>
#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/memory_limit.h>
#include <pcl_sparse/format/attribute_sections.h>
#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/crc32.h>
#include <pcl_sparse/format/footprint_coding.h>
#include <pcl_sparse/format/frame_quantization.h>
#include <pcl_sparse/format/model_sections.h>
#include <pcl_sparse/format/range_coder.h>
#include <pcl_sparse/format/seed_coding.h>
#include <pcl_sparse/format/sparse_code_stream.h>
#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/format/zstd_codec.h>
#include <pcl_sparse/model/tiled_model.h>
#include <pcl_sparse/resampling/footprint_slack.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

namespace pcl_sparse
{
  namespace
  {
    // ---- constants of format version 1 (docs/FORMAT.md) -------------------------------------------
    constexpr std::uint8_t kMagic[8] = {0x89, 'P', 'S', 'M', '\r', '\n', 0x1a, '\n'};
    constexpr std::uint16_t kVersion = 1;
    constexpr std::size_t kHeaderBytes = 52;
    constexpr std::size_t kSectionHeaderBytes = 32;
    constexpr std::uint8_t kBasisCosine = 1;     ///< CosineDictionary: cos(i pi x) cos(j pi y)
    constexpr std::uint8_t kBasisDctCosine = 2;  ///< DctCosineDictionary: cos(i pi (x + 1) / 2) cos(j pi (y + 1) / 2)
    constexpr std::uint8_t kBasisQuadricDct = 3; ///< QuadricDctDictionary: the Dct atoms, then x, y, x^2, x y, y^2
    constexpr std::uint8_t kCodecStored = 0;
    constexpr std::uint8_t kCodecZstd = 1;
    constexpr std::uint64_t kMaxPatches = std::numeric_limits<std::int32_t>::max ();
    constexpr std::uint64_t kMaxFootprintAngles = max_file_footprint_angles;
    // A run's footprints may hold at most kFootprintAnglesAllowance + kFootprintAnglesPerByte x (FOOT bytes)
    // angles in all (1 KiB of extents a byte; default files of the shared meshes hold 4-7 a byte).
    constexpr std::size_t kFootprintAnglesAllowance = 65536;
    constexpr std::size_t kFootprintAnglesPerByte = 256;
    // A zstd section may decompress to at most kMaxExpansion times its stored size plus kExpansionSlack
    // bytes: bounds every allocation by what the file can justify, zip bombs included. Real sections
    // compress 1-10x; the writer stores a section uncompressed if it would exceed the bound.
    constexpr std::uint64_t kMaxExpansion = 64;
    constexpr std::uint64_t kExpansionSlack = 4096;
    // Memory of a decoded patch (PatchCode with its footprint and atoms), measured: 285 bytes.
    constexpr double kDecodedBytesPerPatch = 285.0;
    // Share of the tolerance given to each quantised quantity, about proportional to how many values
    // of each a model has (3 seed, 3 frame, 1 radius, ~12 coefficient values per patch), which minimises
    // the total bits for a given sum of bounds; the remaining 5 % covers the second-order cross terms
    // (docs/FORMAT.md, "Error budget").
    constexpr double kSeedShare = 0.16;
    constexpr double kRadiusShare = 0.05;
    constexpr double kFrameShare = 0.16;
    constexpr double kCoefficientShare = 0.58;

    const char* const kLosslessTags[] = {"SEED", "FRAM", "RADI", "FOOT", "ATOM", "COEF"};
    const char* const kQuantisedTags[] = {"QUAN", "SEED", "FRAM", "RADI", "FOOT", "ATOM", "COEF"};
    const char* const kAttributeTags[] = {"ACHN", "AATM", "ACOF"};

    /// The sections a file with \a flags has, in order.
    std::vector<std::string>
    expectedTags (std::uint16_t flags)
    {
      std::vector<std::string> tags;
      if (flags & header_flag::quantised)
        tags.assign (std::begin (kQuantisedTags), std::end (kQuantisedTags));
      else
        tags.assign (std::begin (kLosslessTags), std::end (kLosslessTags));
      if (flags & header_flag::vertices)
        tags.push_back ("VERT");
      if (flags & header_flag::attributes)
        tags.insert (tags.end (), std::begin (kAttributeTags), std::end (kAttributeTags));
      return tags;
    }

    /// Quantisation parameters of a quantised file (section QUAN, stored uncompressed).
    struct QuantisationParameters
    {
      double seed_min[3] = {0.0, 0.0, 0.0};
      double seed_step = 1.0;
      int seed_bytes = 1;
      double log_radius_min = 0.0;
      double log_radius_step = 1.0;
      int radius_bytes = 1;
      double extent_max = 1.0;
      int extent_bits = 6;
      double frame_budget = 0.0;
      double coefficient_budget = 0.0;

      double extentStep () const { return extent_max / static_cast<double> ((1 << extent_bits) - 1); }
      FootprintLevels footprintLevels () const { return {extentStep (), extent_bits}; }
    };

#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    // The fuzzer would otherwise spend all its time failing checksums, never reaching the decoder.
    constexpr bool kVerifyChecksums = false;
#else
    constexpr bool kVerifyChecksums = true;
#endif

    struct Section
    {
      std::string tag;
      std::uint8_t codec = kCodecZstd;
      std::vector<std::uint8_t> raw;
    };

    int
    bytesFor (std::uint64_t max_value)
    {
      int bytes = 1;
      while (bytes < 8 && (max_value >> (8 * bytes)) != 0)
        ++bytes;
      return bytes;
    }

    /// Byte planes: all low bytes, then all second bytes, ... (zstd finds the slowly varying high
    /// bytes much easier this way).
    void
    putPlanes (ByteWriter& out, const std::vector<std::uint64_t>& values, int bytes)
    {
      for (int b = 0; b < bytes; ++b)
        for (std::uint64_t v : values)
          out.putU8 (static_cast<std::uint8_t> (v >> (8 * b)));
    }

    /// Entry \a index of \a count integers stored as \a bytes byte planes at \a planes (all low bytes, then
    /// the next, ...; putPlanes).
    std::uint64_t
    planeValue (const std::uint8_t* planes, std::size_t count, int bytes, std::size_t index)
    {
      std::uint64_t value = 0;
      for (int b = 0; b < bytes; ++b)
        value |= static_cast<std::uint64_t> (planes[static_cast<std::size_t> (b) * count + index]) << (8 * b);
      return value;
    }

    double
    sumAbs (const std::vector<double>& values)
    {
      double s = 0.0;
      for (double v : values)
        s += std::abs (v);
      return s;
    }

    /// Bound on |(x, y, h(x, y))| over a decoded patch's footprint, from decoded values only, so that
    /// the encoder and the decoder derive the same frame step (docs/FORMAT.md).
    double
    decodedReach (const PatchCode& patch, const QuantisationParameters& q)
    {
      const double step = coefficientStep (q.coefficient_budget, patch.radius, patch.atoms.size ());
      // The largest extent over the whole model (stored, exact), not the patch's decoded extents: those
      // are rounded and may have lost angles (max_footprint_angles).
      const double e = q.extent_max;
      const double h = sumAbs (patch.coefficients) + 0.5 * step * static_cast<double> (patch.coefficients.size ());
      return std::max (std::sqrt (e * e + h * h), 1e-12);
    }

    void
    requireFinite (double v, const std::string& what)
    {
      if (!std::isfinite (v))
        throw Error ("encodeModel: " + what + " is not finite");
    }

    /// The model's cosine basis (CosineAtoms: the paper's, the half-period or the quadric one); throws for any other.
    const CosineAtoms&
    cosineBasis (const SparseSurfaceModel& model)
    {
      if (!model.basis)
        throw Error ("encodeModel: the model has no basis");
      const auto* cosine = dynamic_cast<const CosineAtoms*> (model.basis.get ());
      if (!cosine)
        throw Error ("encodeModel: the file format stores only models over a cosine basis (CosineDictionary or "
                     "DctCosineDictionary)");
      return *cosine;
    }

    void
    validateModel (const SparseSurfaceModel& model, bool with_vertices)
    {
      if (model.patches.size () > kMaxPatches)
        throw Error ("encodeModel: too many patches");
      requireFinite (model.bbox_diagonal, "bbox_diagonal");
      if (model.bbox_diagonal < 0.0)
        throw Error ("encodeModel: bbox_diagonal is negative");
      model.checkPatches ("encodeModel: ");
      for (std::size_t p = 0; p < model.patches.size (); ++p)
      {
        const PatchCode& patch = model.patches[p];
        const std::string name = "patch " + std::to_string (p);
        if (patch.footprint.extent.size () > kMaxFootprintAngles)
          throw Error ("encodeModel: " + name + " footprint has too many angles");
        if (with_vertices && patch.vertices.size () != patch.vertex_xy.size ())
          throw Error ("encodeModel: " + name + " vertices and vertex_xy differ in size");
      }
    }

    // ---- lossless sections ------------------------------------------------------------------------

    /// The six per-patch sections of patches [first, first + count), lossless.
    std::vector<std::vector<std::uint8_t>>
    encodeLosslessRun (const SparseSurfaceModel& model, std::size_t first, std::size_t count)
    {
      ByteWriter seed, frame, radius, foot, atom, coef;
      for (std::size_t p = first; p < first + count; ++p)
      {
        const PatchCode& patch = model.patches[p];
        for (int i = 0; i < 3; ++i)
          seed.putF64 (patch.origin[i]);
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r)
            frame.putF64 (patch.frame (r, c));
        radius.putF64 (patch.radius);
        foot.putVarint (patch.footprint.extent.size ());
        for (float e : patch.footprint.extent)
          foot.putF32 (e);
        putCodeCoefficients (coef, patch.coefficients, putCodeAtoms (atom, patch.atoms, false, 0), 0.0);
      }
      return {std::move (seed.bytes ()), std::move (frame.bytes ()), std::move (radius.bytes ()),
              std::move (foot.bytes ()), std::move (atom.bytes ()),  std::move (coef.bytes ())};
    }

    // ---- quantised sections -----------------------------------------------------------------------

    /// Seed and radius step counts are stored in at most 32 bits.
    constexpr double kMaxStepCount = 4294967295.0;

    /// Integer steps of q.seed_step from the smallest corner of coordinate \a i of \a origin.
    std::uint64_t
    seedSteps (const Eigen::Vector3d& origin, int i, const QuantisationParameters& q)
    {
      const double steps = std::round ((origin[i] - q.seed_min[i]) / q.seed_step);
      if (!(steps < kMaxStepCount))
        throw Error ("encodeModel: tolerance too small for the seed range (more than 2^32 steps; 1e-8 of the bbox "
                     "diagonal or more fits, 0 writes the lossless file)");
      return static_cast<std::uint64_t> (steps);
    }

    /// Seeds: the smallest corner and the bytes of the largest step count over the model (sets
    /// q.seed_min and q.seed_bytes).
    void
    chooseSeedRange (const SparseSurfaceModel& model, QuantisationParameters& q)
    {
      const std::size_t m = model.patches.size ();
      for (int i = 0; i < 3; ++i)
      {
        q.seed_min[i] = m ? std::numeric_limits<double>::infinity () : 0.0;
        for (const PatchCode& patch : model.patches)
          q.seed_min[i] = std::min (q.seed_min[i], patch.origin[i]);
      }
      std::uint64_t seed_max = 0;
      for (const PatchCode& patch : model.patches)
        for (int i = 0; i < 3; ++i)
          seed_max = std::max (seed_max, seedSteps (patch.origin, i, q));
      q.seed_bytes = bytesFor (seed_max);
    }

    /// Radii: log scale, the step from the largest radius * reach over the patches (original values);
    /// sets q.log_radius_min and q.log_radius_step.
    void
    chooseRadiusScale (const SparseSurfaceModel& model, double tolerance, QuantisationParameters& q)
    {
      double largest_arm = 0.0, largest_radius = 0.0;
      q.log_radius_min = model.patches.empty () ? 0.0 : std::numeric_limits<double>::infinity ();
      for (const PatchCode& patch : model.patches)
      {
        const double e = patch.footprint.largestExtent ();
        const double h = sumAbs (patch.coefficients);
        largest_arm = std::max (largest_arm, patch.radius * std::sqrt (e * e + h * h));
        largest_radius = std::max (largest_radius, patch.radius);
        q.log_radius_min = std::min (q.log_radius_min, std::log (patch.radius));
      }
      const double relative = kRadiusShare * tolerance / std::max (largest_arm, 1e-300);
      q.log_radius_step = 2.0 * std::log1p (std::min (relative, 1.0));
      // Radii on the encoder's grid (coding/radius_grid.h) are held exactly by its step, or a multiple of it
      // where the tolerance allows one: a few bits a patch instead of the tolerance's fine step.
      // A radius counts as on it only within half the tolerance's step (the file's bound holds either way).
      const double grid = std::log (2.0) / kRadiusStepsPerOctave;
      std::int64_t smallest_step = std::numeric_limits<std::int64_t>::max (), step = 0;
      bool on_grid = !model.patches.empty ();
      for (const PatchCode& patch : model.patches)
      {
        on_grid = on_grid && radiusGridStep (patch.radius, step) &&
                  std::abs (std::log (patch.radius) - grid * static_cast<double> (step)) <= 0.5 * q.log_radius_step;
        if (!on_grid)
          break;
        smallest_step = std::min (smallest_step, step);
      }
      if (on_grid)
      {
        q.log_radius_min = grid * static_cast<double> (smallest_step);
        q.log_radius_step = grid * std::max (1.0, std::floor (q.log_radius_step / grid));
      }
      // A vertex far from the rest (one coordinate at 1e20 in a unit mesh) makes one patch's reach dwarf the
      // tolerance, which comes from the model's error: the scale would need more steps than 32 bits count.
      if (!model.patches.empty () && !((std::log (largest_radius) - q.log_radius_min) / q.log_radius_step < kMaxStepCount))
      {
        std::ostringstream message;
        message << "a quantised file cannot hold patch radii from " << std::exp (q.log_radius_min) << " to "
                << largest_radius << " on a log scale fine enough for its tolerance (a vertex far from the rest of "
                << "the surface?); a lossless file (tolerance 0, pcl_sparse_encode -tolerance 0) holds it";
        throw Error (message.str ());
      }
    }

    /// Step count of \a radius on the log scale of \a q.
    std::uint64_t
    quantiseRadius (double radius, const QuantisationParameters& q)
    {
      const double radius_steps = std::round ((std::log (radius) - q.log_radius_min) / q.log_radius_step);
      if (!(radius_steps < kMaxStepCount))
        throw Error ("encodeModel: tolerance too small for the radius range");
      return static_cast<std::uint64_t> (radius_steps);
    }

    /// The adaptive models of the range-coded per-patch fields of a run (docs/FORMAT.md, "Range-coded
    /// fields"); the writer and the reader build the same ones and code the same values in the same order.
    struct PatchFieldContexts
    {
      PatchFieldContexts (int extent_bits, int frequencies, int monomials)
        : footprint (extent_bits), code (frequencies, monomials) {}

      /// FOOT (files without header_flag::adaptive_footprints use its angles, first_level and level_delta models alone)
      FootprintContexts footprint;
      BitTreeModel frame_header{3};         ///< dropped component and reflection
      SignedIntegerModel frame_component[3];  ///< the quaternion's other three components, by position
      SparseCodeContexts code;              ///< ATOM and COEF
    };

    /// Atoms sorted by shell rank (the deltas are small and the code is the same sum), then their
    /// coefficients in that order, in steps of the patch's coefficient step. \a decoded (its radius
    /// already set) receives the atoms and coefficients as the decoder will read them.
    void
    putQuantisedCode (ByteWriter& atom, ByteWriter& coef, const PatchCode& patch, const QuantisationParameters& q,
                      int frequencies, int monomials, PatchCode& decoded)
    {
      const std::vector<std::size_t> order = putCodeAtoms (atom, patch.atoms, true, frequencies, monomials);
      for (std::size_t k : order)
        decoded.atoms.push_back (patch.atoms[k]);
      const double step = coefficientStep (q.coefficient_budget, decoded.radius, order.size ());
      decoded.coefficients = putCodeCoefficients (coef, patch.coefficients, order, step);
    }

    void
    putQuantisedCode (RangeEncoder& atom, RangeEncoder& coef, SparseCodeContexts& contexts, const PatchCode& patch,
                      const QuantisationParameters& q, PatchCode& decoded)
    {
      const std::vector<std::size_t> order = contexts.putAtoms (atom, patch.atoms);
      for (std::size_t k : order)
        decoded.atoms.push_back (patch.atoms[k]);
      const double step = coefficientStep (q.coefficient_budget, decoded.radius, order.size ());
      decoded.coefficients = contexts.putCoefficients (coef, patch.atoms, patch.coefficients, order, step);
    }

    /// The frame as a quantised quaternion, its step from the decoded patch (as the decoder derives it).
    QuantisedFrame
    quantisedFrame (const Eigen::Matrix3d& rotation, const PatchCode& decoded, const QuantisationParameters& q)
    {
      return quantiseFrame (rotation, frameStep (q.frame_budget, decoded.radius, decodedReach (decoded, q)));
    }

    /// Frame header: bits 0-1 the dropped component, bit 2 reflected.
    std::uint8_t
    frameHeader (const QuantisedFrame& code)
    {
      return static_cast<std::uint8_t> (code.largest | (code.reflected ? 4 : 0));
    }

    /// A quantised frame with the dropped component and reflection of \a header (frameHeader, <= 7) and
    /// no components yet.
    QuantisedFrame
    frameOfHeader (std::uint32_t header)
    {
      QuantisedFrame code;
      code.largest = static_cast<int> (header & 3);
      code.reflected = header & 4;
      return code;
    }

    void
    putQuantisedFrame (ByteWriter& frame, const QuantisedFrame& code)
    {
      frame.putU8 (frameHeader (code));
      for (std::int64_t v : code.q)
        frame.putSignedVarint (v);
    }

    void
    putQuantisedFrame (RangeEncoder& frame, PatchFieldContexts& contexts, const QuantisedFrame& code)
    {
      contexts.frame_header.put (frame, frameHeader (code));
      for (int i = 0; i < 3; ++i)
        contexts.frame_component[i].put (frame, code.q[i]);
    }

    /// Section QUAN.
    std::vector<std::uint8_t>
    quantisationBytes (const QuantisationParameters& q)
    {
      ByteWriter params;
      for (double v : q.seed_min)
        params.putF64 (v);
      params.putF64 (q.seed_step);
      params.putU8 (static_cast<std::uint8_t> (q.seed_bytes));
      params.putF64 (q.log_radius_min);
      params.putF64 (q.log_radius_step);
      params.putU8 (static_cast<std::uint8_t> (q.radius_bytes));
      params.putF64 (q.extent_max);
      params.putU8 (static_cast<std::uint8_t> (q.extent_bits));
      params.putF64 (q.frame_budget);
      params.putF64 (q.coefficient_budget);
      return std::move (params.bytes ());
    }

    /// Quantisation parameters over every patch of \a model (QUAN).
    QuantisationParameters
    chooseQuantisation (const SparseSurfaceModel& model, const ModelWriteOptions& options)
    {
      const double tolerance = options.tolerance * model.bbox_diagonal;
      QuantisationParameters q;
      q.seed_step = 2.0 * kSeedShare * tolerance / std::sqrt (3.0);
      q.frame_budget = kFrameShare * tolerance;
      q.coefficient_budget = kCoefficientShare * tolerance;
      q.extent_bits = options.extent_bits;
      chooseSeedRange (model, q);

      // Extents: a common scale, (2^bits - 1) levels.
      q.extent_max = 0.0;
      for (const PatchCode& patch : model.patches)
        q.extent_max = std::max (q.extent_max, patch.footprint.largestExtent ());
      if (!(q.extent_max > 0.0))
        q.extent_max = 1.0;
      chooseRadiusScale (model, tolerance, q);
      std::uint64_t radius_max = 0;
      for (const PatchCode& patch : model.patches)
        radius_max = std::max (radius_max, quantiseRadius (patch.radius, q));
      q.radius_bytes = bytesFor (radius_max);
      return q;
    }

    /// The six per-patch sections of patches [first, first + count), quantised with \a q.
    std::vector<std::vector<std::uint8_t>>
    encodeQuantisedRun (const SparseSurfaceModel& model, std::size_t first, std::size_t count,
                        const QuantisationParameters& q, const ModelWriteOptions& options, int frequencies, int monomials,
                        const std::vector<FootprintSlack>& slack)  // of the run's patches, or empty
    {
      // Decode as we go, so that the steps derived from decoded values match the decoder's.
      std::vector<std::vector<std::uint64_t>> seeds (3, std::vector<std::uint64_t> (count));
      std::vector<std::uint64_t> radii (count);
      ByteWriter frame, foot, atom, coef;  // the varint layout
      RangeEncoder coded_frame, coded_foot, coded_atom, coded_coef;
      PatchFieldContexts contexts (q.extent_bits, frequencies, monomials);
      const FootprintRefinement refinement{options.max_footprint_angles, options.footprint_refine_steps};
      std::size_t angles = 0;  // the footprints' angles as a reader gets them
      for (std::size_t k = 0; k < count; ++k)
      {
        const PatchCode& patch = model.patches[first + k];
        for (int i = 0; i < 3; ++i)
          seeds[i][k] = seedSteps (patch.origin, i, q);
        PatchCode decoded;
        radii[k] = quantiseRadius (patch.radius, q);
        decoded.radius = std::exp (q.log_radius_min + static_cast<double> (radii[k]) * q.log_radius_step);
        if (options.range_coding)
        {
          angles += putFootprint (coded_foot, contexts.footprint, patch.footprint, q.footprintLevels (), refinement,
                                  slack.empty () ? nullptr : &slack[k]);
          putQuantisedCode (coded_atom, coded_coef, contexts.code, patch, q, decoded);
          putQuantisedFrame (coded_frame, contexts, quantisedFrame (patch.frame, decoded, q));
        }
        else
        {
          angles += putFootprint (foot, patch.footprint, q.footprintLevels (), refinement,
                                  slack.empty () ? nullptr : &slack[k]);
          putQuantisedCode (atom, coef, patch, q, frequencies, monomials, decoded);
          putQuantisedFrame (frame, quantisedFrame (patch.frame, decoded, q));
        }
      }
      std::vector<std::uint8_t> foot_bytes = options.range_coding ? coded_foot.finish () : std::move (foot.bytes ());
      if (angles > kFootprintAnglesAllowance + kFootprintAnglesPerByte * foot_bytes.size ())
        throw Error ("encodeModel: the footprints hold " + std::to_string (angles) + " angles in " +
                     std::to_string (foot_bytes.size ()) + " bytes, more than a reader accepts (footprints of " +
                     "thousands of angles coded from a few: keep fewer, or max_footprint_angles 0)");
      ByteWriter seed, radius;
      putPlanes (radius, radii, q.radius_bytes);
      if (options.range_coding)
      {
        RangeEncoder coded_seed;
        SeedStepCoder seed_coder;
        for (std::size_t k = 0; k < count; ++k)
          seed_coder.put (coded_seed, {seeds[0][k], seeds[1][k], seeds[2][k]});
        return {coded_seed.finish (),   coded_frame.finish (), std::move (radius.bytes ()),
                std::move (foot_bytes), coded_atom.finish (),  coded_coef.finish ()};
      }
      for (int i = 0; i < 3; ++i)
        putPlanes (seed, seeds[i], q.seed_bytes);
      return {std::move (seed.bytes ()), std::move (frame.bytes ()), std::move (radius.bytes ()),
              std::move (foot_bytes),    std::move (atom.bytes ()), std::move (coef.bytes ())};
    }

    std::vector<std::uint8_t>
    encodeVertices (const SparseSurfaceModel& model, std::size_t first, std::size_t count, bool quantised)
    {
      ByteWriter out;
      for (std::size_t p = first; p < first + count; ++p)
      {
        const PatchCode& patch = model.patches[p];
        putVertexNumbers (out, patch.vertices, model.num_input_vertices);
        for (const Eigen::Vector2d& xy : patch.vertex_xy)
          for (int i = 0; i < 2; ++i)
          {
            requireFinite (xy[i], "vertex_xy");
            if (quantised)
              out.putF32 (static_cast<float> (xy[i]));
            else
              out.putF64 (xy[i]);
          }
      }
      return std::move (out.bytes ());
    }

    // ---- container --------------------------------------------------------------------------------

    struct Header
    {
      std::uint16_t version = 0;
      std::uint16_t flags = 0;
      std::uint8_t basis_kind = 0;
      std::uint16_t basis_parameter = 0;
      std::uint32_t num_patches = 0;
      std::uint32_t num_sections = 0;
      std::uint64_t num_input_vertices = 0;
      double bbox_diagonal = 0.0;
      double tolerance = 0.0;
    };

    struct StoredSection
    {
      std::string tag;
      std::uint8_t codec = 0;
      std::uint64_t stored = 0;
      std::uint64_t raw = 0;
      const std::uint8_t* payload = nullptr;
    };

    struct Container
    {
      Header header;
      std::vector<StoredSection> sections;
    };

    /// The checks of the header's values (shared by version-1 files and the shared fields of tiled files).
    void
    checkHeaderValues (std::uint16_t flags, std::uint8_t basis_kind, std::uint16_t basis_parameter, std::uint64_t num_patches,
                       std::uint64_t num_input_vertices, double bbox_diagonal, double tolerance, const std::string& what)
    {
      if ((flags & ~header_flag::known) != 0)
        throw Error (what + ": unknown header flags (written by a newer pcl_sparse?)");
      if ((flags & header_flag::range_coded) && !(flags & header_flag::quantised))
        throw Error (what + ": the range-coded flag needs the quantised flag");
      if ((flags & header_flag::adaptive_footprints) && !(flags & header_flag::quantised))
        throw Error (what + ": the adaptive-footprint flag needs the quantised flag");
      if ((flags & header_flag::coded_seeds) && !(flags & header_flag::range_coded))
        throw Error (what + ": the coded-seed flag needs the range-coded flag");
      if (!isBasisKindByte (basis_kind))
        throw Error (what + ": unknown basis kind " + std::to_string (basis_kind));
      if (basis_parameter < 1 || basis_parameter > CosineDictionary::max_frequencies)
        throw Error (what + ": cosine basis with " + std::to_string (basis_parameter) + " frequencies is out of range");
      if (num_patches > kMaxPatches)
        throw Error (what + ": number of patches " + std::to_string (num_patches) + " out of range");
      if (num_input_vertices > static_cast<std::uint64_t> (std::numeric_limits<std::int32_t>::max ()))
        throw Error (what + ": number of input vertices out of range");
      if (!std::isfinite (bbox_diagonal) || bbox_diagonal < 0.0)
        throw Error (what + ": bbox diagonal is negative or not finite");
      const bool quantised = flags & header_flag::quantised;
      if (!std::isfinite (tolerance) || tolerance < 0.0 || (tolerance > 0.0) != quantised ||
          (quantised && !(bbox_diagonal > 0.0)))
        throw Error (what + ": tolerance does not match the quantised flag");
    }

    /// Parses and checks the header and the section table (CRCs, sizes, tags, expansion bound).
    Container
    readContainer (const std::uint8_t* data, std::size_t size, const std::string& name)
    {
      const std::string what = name;
      if (size < sizeof kMagic || std::memcmp (data, kMagic, sizeof kMagic) != 0)
        throw Error (what + ": not a pcl_sparse model file (wrong magic bytes)");
      ByteReader in (data, size, what);
      in.getBytes (sizeof kMagic, "magic");
      Container c;
      Header& h = c.header;
      h.version = in.getU16 ("version");
      if (h.version != kVersion)
        throw Error (what + ": unsupported model file version " + std::to_string (h.version) + " (this build reads version " +
                     std::to_string (kVersion) + ")");
      h.flags = in.getU16 ("flags");
      h.basis_kind = in.getU8 ("basis kind");
      const std::uint8_t reserved = in.getU8 ("reserved");
      h.basis_parameter = in.getU16 ("basis parameter");
      h.num_patches = in.getU32 ("number of patches");
      h.num_sections = in.getU32 ("number of sections");
      h.num_input_vertices = in.getU64 ("number of input vertices");
      h.bbox_diagonal = in.getF64 ("bbox diagonal");
      h.tolerance = in.getF64 ("tolerance");
      const std::uint32_t header_crc = in.getU32 ("header checksum");
      if (kVerifyChecksums && crc32 (data, kHeaderBytes - 4) != header_crc)
        throw Error (what + ": header checksum mismatch (corrupt file)");
      if (reserved != 0)
        throw Error (what + ": unknown header flags");
      checkHeaderValues (h.flags, h.basis_kind, h.basis_parameter, h.num_patches, h.num_input_vertices, h.bbox_diagonal,
                         h.tolerance, what);
      const std::vector<std::string> tags = expectedTags (h.flags);
      if (h.num_sections != tags.size ())
        throw Error (what + ": " + std::to_string (h.num_sections) + " sections, expected " + std::to_string (tags.size ()));

      for (std::uint32_t s = 0; s < h.num_sections; ++s)
      {
        const std::size_t start = in.position ();
        StoredSection section;
        const std::uint8_t* tag = in.getBytes (4, "section tag");
        section.tag.assign (reinterpret_cast<const char*> (tag), 4);
        section.codec = in.getU8 ("section codec");
        const std::uint8_t* pad = in.getBytes (3, "section padding");
        section.stored = in.getU64 ("section size");
        section.raw = in.getU64 ("section raw size");
        const std::uint32_t payload_crc = in.getU32 ("section checksum");
        const std::uint32_t section_header_crc = in.getU32 ("section header checksum");
        if (kVerifyChecksums && crc32 (data + start, kSectionHeaderBytes - 4) != section_header_crc)
          throw Error (what + ": section " + std::to_string (s) + " header checksum mismatch (corrupt file)");
        if (section.tag != tags[s])
          throw Error (what + ": section " + std::to_string (s) + " is '" + section.tag + "', expected '" + tags[s] + "'");
        if (pad[0] || pad[1] || pad[2] || (section.codec != kCodecStored && section.codec != kCodecZstd))
          throw Error (what + ": section " + section.tag + " has an unknown codec");
        if (section.stored > in.remaining ())
          throw Error (what + ": section " + section.tag + " claims " + std::to_string (section.stored) + " bytes, only " +
                       std::to_string (in.remaining ()) + " left (truncated file?)");
        if (section.codec == kCodecStored && section.raw != section.stored)
          throw Error (what + ": stored section " + section.tag + " has different raw and stored sizes");
        if (section.codec == kCodecZstd && section.raw > kMaxExpansion * section.stored + kExpansionSlack)
          throw Error (what + ": section " + section.tag + " claims " + std::to_string (section.raw) +
                       " decompressed bytes, more than its " + std::to_string (section.stored) + " stored bytes can justify");
        section.payload = in.getBytes (static_cast<std::size_t> (section.stored), "section payload");
        if (kVerifyChecksums && crc32 (section.payload, static_cast<std::size_t> (section.stored)) != payload_crc)
          throw Error (what + ": section " + section.tag + " checksum mismatch (corrupt file)");
        c.sections.push_back (section);
      }
      if (!in.atEnd ())
        throw Error (what + ": " + std::to_string (in.remaining ()) + " trailing bytes after the last section");
      return c;
    }

    std::vector<std::uint8_t>
    sectionBytes (const StoredSection& section, const std::string& name)
    {
      const std::string what = name + ": section " + section.tag;
      if (section.codec == kCodecStored)
        return std::vector<std::uint8_t> (section.payload, section.payload + section.stored);
      return decompressBytes (section.payload, static_cast<std::size_t> (section.stored),
                              static_cast<std::size_t> (section.raw), what);
    }

    double
    readFinite (ByteReader& in, const char* field)
    {
      const double v = in.getF64 (field);
      if (!std::isfinite (v))
        in.fail (std::string (field) + " is not finite");
      return v;
    }

    QuantisationParameters
    readQuantisation (ByteReader& in)
    {
      QuantisationParameters q;
      for (double& v : q.seed_min)
        v = readFinite (in, "seed minimum");
      q.seed_step = readFinite (in, "seed step");
      q.seed_bytes = in.getU8 ("seed bytes");
      q.log_radius_min = readFinite (in, "log radius minimum");
      q.log_radius_step = readFinite (in, "log radius step");
      q.radius_bytes = in.getU8 ("radius bytes");
      q.extent_max = readFinite (in, "extent maximum");
      q.extent_bits = in.getU8 ("extent bits");
      q.frame_budget = readFinite (in, "frame budget");
      q.coefficient_budget = readFinite (in, "coefficient budget");
      in.expectEnd ();
      if (!(q.seed_step > 0.0) || !(q.log_radius_step > 0.0) || !(q.extent_max > 0.0) || !(q.frame_budget > 0.0) ||
          !(q.coefficient_budget > 0.0))
        in.fail ("quantisation steps must be positive");
      if (q.seed_bytes < 1 || q.seed_bytes > 4 || q.radius_bytes < 1 || q.radius_bytes > 4 || q.extent_bits < 2 ||
          q.extent_bits > 8)
        in.fail ("quantisation widths out of range");
      return q;
    }

    // ---- decoding, one patch field at a time ------------------------------------------------------

    /// Fixed-size sections must hold exactly \a m entries, and in the varint layout every patch takes at
    /// least one byte in each variable-size section: checked before allocating patches (range-coded patches
    /// can take less, but RADI's exact size already bounds m).
    void
    checkSectionSizes (const ByteReader& seed, const ByteReader& frame, const ByteReader& radius, const ByteReader& foot,
                       const ByteReader& atom, std::size_t m, bool quantised, bool range_coded, bool coded_seeds,
                       const QuantisationParameters& q)
    {
      const std::size_t seed_entry = quantised ? 3 * static_cast<std::size_t> (q.seed_bytes) : 24;
      const std::size_t radius_entry = quantised ? static_cast<std::size_t> (q.radius_bytes) : 8;
      if (!coded_seeds && seed.remaining () != m * seed_entry)
        seed.fail ("holds " + std::to_string (seed.remaining ()) + " bytes, " + std::to_string (m) + " patches need " +
                   std::to_string (m * seed_entry));
      if (radius.remaining () != m * radius_entry)
        radius.fail ("holds " + std::to_string (radius.remaining ()) + " bytes, " + std::to_string (m) + " patches need " +
                     std::to_string (m * radius_entry));
      if (!range_coded && (frame.remaining () < m * (quantised ? 4 : 72) || foot.remaining () < m || atom.remaining () < m))
        frame.fail ("too short for " + std::to_string (m) + " patches");
    }

    /// Seed and radius of patch \a p of \a m: in a quantised file, the seed from \a seed_steps (coded seeds)
    /// or the byte planes \a seed_planes (x, y, z one after the other), the radius from \a radius_planes;
    /// else both read from \a seed and \a radius.
    void
    readPlacement (ByteReader& seed, ByteReader& radius, bool quantised, const QuantisationParameters& q,
                   const std::array<std::uint64_t, 3>* seed_steps, const std::uint8_t* seed_planes,
                   const std::uint8_t* radius_planes, std::size_t m, std::size_t p, PatchCode& patch)
    {
      if (quantised)
      {
        const std::size_t axis_bytes = m * static_cast<std::size_t> (q.seed_bytes);
        for (int i = 0; i < 3; ++i)
        {
          const std::uint64_t steps =
            seed_steps ? (*seed_steps)[i] : planeValue (seed_planes + i * axis_bytes, m, q.seed_bytes, p);
          patch.origin[i] = q.seed_min[i] + static_cast<double> (steps) * q.seed_step;
        }
        patch.radius = std::exp (q.log_radius_min +
                                 static_cast<double> (planeValue (radius_planes, m, q.radius_bytes, p)) * q.log_radius_step);
        if (!patch.origin.allFinite ())
          seed.fail ("patch " + std::to_string (p) + " seed is not finite");
      }
      else
      {
        for (int i = 0; i < 3; ++i)
          patch.origin[i] = readFinite (seed, "seed");
        patch.radius = readFinite (radius, "radius");
      }
      if (!(patch.radius > 0.0) || !std::isfinite (patch.radius))
        radius.fail ("patch " + std::to_string (p) + " radius is not a positive finite number");
    }

    /// The extent of a quantised footprint \a level; \a in names a non-finite one.
    template <typename Reader>
    float
    extentOfLevel (const Reader& in, unsigned level, const QuantisationParameters& q, std::size_t p)
    {
      const auto extent = static_cast<float> (level * q.extentStep ());
      if (!std::isfinite (extent))
        in.fail ("patch " + std::to_string (p) + " extent is not finite");
      return extent;
    }

    /// A range-coded footprint without header_flag::adaptive_footprints: K, then K level deltas, with the models the
    /// adaptive footprints code K and their coarse levels with (the same ones such files were written with).
    void
    readUniformFootprint (RangeDecoder& foot, FootprintContexts& contexts, const QuantisationParameters& q,
                          std::size_t p, PatchFootprint& footprint)
    {
      const std::uint32_t k = contexts.angles.get (foot);
      if (k > kMaxFootprintAngles)
        foot.fail ("patch " + std::to_string (p) + " has " + std::to_string (k) + " footprint angles, more than " +
                   std::to_string (kMaxFootprintAngles));
      footprint.extent.resize (k);
      const unsigned extent_mask = (1u << q.extent_bits) - 1u;
      unsigned level = 0;
      for (std::size_t i = 0; i < k; ++i)
      {
        level = (level + (i == 0 ? contexts.first_level : contexts.level_delta).get (foot)) & extent_mask;
        footprint.extent[i] = extentOfLevel (foot, level, q, p);
      }
    }

    /// A footprint of the varint layout: lossless, or quantised without header_flag::adaptive_footprints (K, then K
    /// level deltas).
    void
    readUniformFootprint (ByteReader& foot, bool quantised, const QuantisationParameters& q, std::size_t p,
                          PatchFootprint& footprint)
    {
      const unsigned extent_mask = (1u << q.extent_bits) - 1u;
      const std::size_t k = foot.getCount ("footprint angles", std::min<std::uint64_t> (kMaxFootprintAngles, foot.remaining ()));
      footprint.extent.resize (k);
      unsigned level = 0;
      for (std::size_t i = 0; i < k; ++i)
      {
        if (quantised)
        {
          const unsigned delta = foot.getU8 ("extent");
          if (delta > extent_mask)
            foot.fail ("extent delta out of range");
          level = (level + delta) & extent_mask;
          footprint.extent[i] = extentOfLevel (foot, level, q, p);
        }
        else
        {
          const float e = foot.getF32 ("extent");
          if (!std::isfinite (e) || e < 0.0f)
            foot.fail ("patch " + std::to_string (p) + " extent is negative or not finite");
          footprint.extent[i] = e;
        }
      }
    }

    /// One coefficient per atom of \a patch (its radius already read).
    void
    readCoefficients (ByteReader& coef, bool quantised, const QuantisationParameters& q, PatchCode& patch)
    {
      const std::size_t n = patch.atoms.size ();
      getCodeCoefficients (coef, n, quantised ? coefficientStep (q.coefficient_budget, patch.radius, n) : 0.0,
                           patch.coefficients);
    }

    /// Sets \a patch's frame from its quantised \a code (its radius and sparse code already read: the
    /// step depends on them); \a in names a code that is not a unit quaternion.
    template <typename Reader>
    void
    setQuantisedFrame (const Reader& in, const QuantisedFrame& code, const QuantisationParameters& q, std::size_t p,
                       PatchCode& patch)
    {
      const double frame_step = frameStep (q.frame_budget, patch.radius, decodedReach (patch, q));
      if (!std::isfinite (frame_step) || !dequantiseFrame (code, frame_step, patch.frame))
        in.fail ("patch " + std::to_string (p) + " frame is not a unit quaternion");
    }

    void
    readFrame (RangeDecoder& frame, PatchFieldContexts& contexts, const QuantisationParameters& q, std::size_t p,
               PatchCode& patch)
    {
      QuantisedFrame code = frameOfHeader (contexts.frame_header.get (frame));
      for (int i = 0; i < 3; ++i)
        code.q[i] = contexts.frame_component[i].get (frame);
      setQuantisedFrame (frame, code, q, p, patch);
    }

    /// Frame of patch \a p (its radius and code already read: a quantised frame's step depends on them).
    void
    readFrame (ByteReader& frame, bool quantised, const QuantisationParameters& q, std::size_t p, PatchCode& patch)
    {
      if (quantised)
      {
        const std::uint8_t header = frame.getU8 ("frame header");
        if (header > 7)
          frame.fail ("frame header out of range");
        QuantisedFrame code = frameOfHeader (header);
        for (std::int64_t& v : code.q)
          v = frame.getSignedVarint ("frame component");
        setQuantisedFrame (frame, code, q, p, patch);
      }
      else
      {
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r)
            patch.frame (r, c) = readFinite (frame, "frame");
        const double off = (patch.frame.transpose () * patch.frame - Eigen::Matrix3d::Identity ()).cwiseAbs ().maxCoeff ();
        if (!(off <= 1e-6))
          frame.fail ("patch " + std::to_string (p) + " frame is not orthonormal");
      }
    }

    /// The range-coded sections FRAM, FOOT, ATOM and COEF of a model: one decoder per section over all its
    /// bytes, and the probability models they share, read patch by patch.
    class RangeCodedPatchSections
    {
    public:
      RangeCodedPatchSections (ByteReader& frame, ByteReader& foot, ByteReader& atom, ByteReader& coef, int extent_bits,
                               int basis_parameter, int monomials, bool adaptive_footprints)
        : frame_ (rangeDecoderOverRest (frame)), foot_ (rangeDecoderOverRest (foot)), atom_ (rangeDecoderOverRest (atom)),
          coef_ (rangeDecoderOverRest (coef)), contexts_ (extent_bits, basis_parameter, monomials),
          adaptive_footprints_ (adaptive_footprints)
      {}

      /// The footprint, code and frame of patch \a p (its seed and radius already read).
      void
      readPatch (const QuantisationParameters& q, std::size_t p, PatchCode& patch)
      {
        if (adaptive_footprints_)
          getFootprint (foot_, contexts_.footprint, q.footprintLevels (), p, patch.footprint);
        else
          readUniformFootprint (foot_, contexts_.footprint, q, p, patch.footprint);
        contexts_.code.getAtoms (atom_, "patch " + std::to_string (p), patch.atoms);
        contexts_.code.getCoefficients (coef_, patch.atoms,
                                        coefficientStep (q.coefficient_budget, patch.radius, patch.atoms.size ()),
                                        patch.coefficients);
        readFrame (frame_, contexts_, q, p, patch);
      }

      /// Throws unless every section was read to its end.
      void
      expectEnd () const
      {
        frame_.expectEnd ();
        foot_.expectEnd ();
        atom_.expectEnd ();
        coef_.expectEnd ();
      }

    private:
      RangeDecoder frame_, foot_, atom_, coef_;
      PatchFieldContexts contexts_;
      bool adaptive_footprints_;
    };

    /// Section VERT: every patch's input vertices and their local (x', y').
    void
    readVertices (ByteReader& vert, bool quantised, std::uint64_t num_input_vertices, std::vector<PatchCode>& patches)
    {
      const std::size_t xy_bytes = quantised ? 8 : 16;
      for (std::size_t p = 0; p < patches.size (); ++p)
      {
        PatchCode& patch = patches[p];
        getVertexNumbers (vert, num_input_vertices, xy_bytes, p, patch.vertices);
        const std::size_t count = patch.vertices.size ();
        patch.vertex_xy.resize (count);
        for (std::size_t i = 0; i < count; ++i)
          for (int c = 0; c < 2; ++c)
          {
            const double v = quantised ? static_cast<double> (vert.getF32 ("vertex_xy")) : vert.getF64 ("vertex_xy");
            if (!std::isfinite (v))
              vert.fail ("vertex_xy is not finite");
            patch.vertex_xy[i][c] = v;
          }
      }
      vert.expectEnd ();
    }
  } // namespace

  void
  putVertexNumbers (ByteWriter& out, const std::vector<int>& vertices, std::uint64_t num_input_vertices)
  {
    out.putVarint (vertices.size ());
    std::int64_t previous = 0;
    for (const int v : vertices)
    {
      if (v < 0 || static_cast<std::uint64_t> (v) >= num_input_vertices)
        throw Error ("a patch lists vertex " + std::to_string (v) + ", outside the input's " +
                     std::to_string (num_input_vertices) + " vertices");
      out.putSignedVarint (v - previous);
      previous = v;
    }
  }

  void
  getVertexNumbers (ByteReader& in, std::uint64_t num_input_vertices, std::size_t bytes_after, std::size_t patch,
                    std::vector<int>& vertices)
  {
    // Each vertex needs >= 1 index byte and bytes_after more: bound before resizing.
    const std::size_t count =
      in.getCount ("vertex count", std::min<std::uint64_t> (num_input_vertices, in.remaining () / (1 + bytes_after)));
    vertices.resize (count);
    std::int64_t previous = 0;
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::int64_t delta = in.getSignedVarint ("vertex index");
      if (delta < -previous || delta >= static_cast<std::int64_t> (num_input_vertices) - previous)
        in.fail ("patch " + std::to_string (patch) + " vertex index outside num_input_vertices");
      previous += delta;
      vertices[i] = static_cast<int> (previous);
    }
  }

  std::vector<std::string>
  runSectionTags (std::uint16_t flags)
  {
    std::vector<std::string> tags (std::begin (kLosslessTags), std::end (kLosslessTags));
    if (flags & header_flag::vertices)
      tags.push_back ("VERT");
    if (flags & header_flag::attributes)
    {
      tags.push_back ("AATM");
      tags.push_back ("ACOF");
    }
    return tags;
  }

  std::uint8_t
  basisKindByte (CosineBasisKind kind)
  {
    switch (kind)
    {
      case CosineBasisKind::Dct: return kBasisDctCosine;
      case CosineBasisKind::DctQuadric: return kBasisQuadricDct;
      default: return kBasisCosine;
    }
  }

  bool
  isBasisKindByte (std::uint8_t byte)
  {
    return byte == kBasisCosine || byte == kBasisDctCosine || byte == kBasisQuadricDct;
  }

  CosineBasisKind
  basisKindOfByte (std::uint8_t byte)
  {
    return byte == kBasisDctCosine ? CosineBasisKind::Dct : byte == kBasisQuadricDct ? CosineBasisKind::DctQuadric
                                                                                      : CosineBasisKind::Paper;
  }

  int
  monomialsOfKindByte (std::uint8_t byte)
  {
    return byte == kBasisQuadricDct ? CosineAtoms::quadric_monomials : 0;
  }

  std::string
  basisDescription (std::uint8_t basis_kind, std::uint16_t basis_parameter)
  {
    const std::string n = std::to_string (basis_parameter);
    const char* kind = basis_kind == kBasisDctCosine ? "dct cosine " : basis_kind == kBasisQuadricDct ? "quadric + dct cosine " : "cosine ";
    return kind + n + "x" + n;
  }

  ModelSections
  encodeModelSections (const SparseSurfaceModel& model, const ModelWriteOptions& options,
                       const std::vector<std::pair<std::size_t, std::size_t>>& runs,
                       const std::vector<FootprintSlack>* model_slack)
  {
    const CosineAtoms& cosine = cosineBasis (model);
    const int frequencies = cosine.frequencies ();
    validateModel (model, options.include_vertices);
    if (!std::isfinite (options.tolerance) || options.tolerance < 0.0)
      throw Error ("encodeModel: tolerance must be >= 0");
    if (options.max_footprint_angles < 0)
      throw Error ("encodeModel: max_footprint_angles must be >= 0");
    if (!(options.footprint_refine_steps >= 0.0) || !std::isfinite (options.footprint_refine_steps))
      throw Error ("encodeModel: footprint_refine_steps must be >= 0 and finite");
    if (options.extent_bits < 2 || options.extent_bits > 8)
      throw Error ("encodeModel: extent_bits must be in 2..8");
    if (options.zstd_level < 0 || options.zstd_level > 22)
      throw Error ("encodeModel: zstd_level must be in 0..22");
    if (options.zstd_large_level < 1 || options.zstd_large_level > 22)
      throw Error ("encodeModel: zstd_large_level must be in 1..22");
    if (model.num_input_vertices > static_cast<std::uint64_t> (std::numeric_limits<std::int32_t>::max ()))
      throw Error ("encodeModel: num_input_vertices out of range");
    const bool quantised = options.tolerance > 0.0;
    if (quantised && !(model.bbox_diagonal > 0.0))
      throw Error ("encodeModel: a tolerance needs the model's bbox_diagonal (> 0)");
    for (const auto& run : runs)
      if (run.first > model.patches.size () || run.second > model.patches.size () - run.first)
        throw Error ("encodeModel: a run of patches lies outside the model");
    if (model_slack)
    {
      bool fits = model_slack->size () == model.patches.size ();
      for (std::size_t i = 0; fits && i < model_slack->size (); ++i)
        fits = (*model_slack)[i].lower.size () == model.patches[i].footprint.extent.size () &&
               (*model_slack)[i].upper.size () == model.patches[i].footprint.extent.size ();
      if (!fits)
        throw Error ("encodeModel: the footprint slack given is not the model's (one per patch, one per footprint angle)");
    }

    ModelSections out;
    SharedModelFields& shared = out.shared;
    const bool attributes = model.hasAttributes ();
    const bool range_coded = quantised && options.range_coding;
    shared.flags = static_cast<std::uint16_t> (
      (quantised ? header_flag::quantised | header_flag::adaptive_footprints : 0) |
      (options.include_vertices ? header_flag::vertices : 0) | (attributes ? header_flag::attributes : 0) |
      (range_coded ? header_flag::range_coded | header_flag::coded_seeds : 0));
    shared.basis_kind = basisKindByte (cosine.kind ());
    shared.basis_parameter = static_cast<std::uint16_t> (frequencies);
    shared.num_input_vertices = model.num_input_vertices;
    shared.bbox_diagonal = model.bbox_diagonal;
    shared.tolerance = options.tolerance;
    QuantisationParameters q;
    if (quantised)
    {
      q = chooseQuantisation (model, options);
      shared.quantisation = quantisationBytes (q);
    }
    if (attributes && quantised && !(options.attribute_tolerance > 0.0 && std::isfinite (options.attribute_tolerance)))
      throw Error ("encodeModel: attribute_tolerance must be > 0");
    const double attribute_tolerance = quantised ? options.attribute_tolerance : 0.0;
    for (const auto& [first, count] : runs)
    {
      // Each run's slack apart (the whole model's, found among the patches near the run): a tile's memory, not
      // the whole model's (a 100 M-point terrain has half a million patches).
      std::vector<FootprintSlack> slack;
      if (quantised && options.footprint_slack && options.footprint_refine_steps > 0.0)
        slack = model_slack ? std::vector<FootprintSlack> (model_slack->begin () + static_cast<std::ptrdiff_t> (first),
                                                           model_slack->begin () + static_cast<std::ptrdiff_t> (first + count))
                            : footprintSlack (model, first, count);
      std::vector<std::vector<std::uint8_t>> sections =
        quantised ? encodeQuantisedRun (model, first, count, q, options, frequencies, cosine.monomials (), slack)
                  : encodeLosslessRun (model, first, count);
      if (options.include_vertices)
        sections.push_back (encodeVertices (model, first, count, quantised));
      if (attributes)
      {
        AttributeSectionBytes bytes = first == 0 && count == model.patches.size ()
                                        ? encodeAttributeSections (model, attribute_tolerance, range_coded)
                                        : encodeAttributeSections (subModel (model, first, count), attribute_tolerance, range_coded);
        sections.push_back (std::move (bytes.atoms));
        sections.push_back (std::move (bytes.coefficients));
        if (shared.channels.empty ())
          shared.channels = std::move (bytes.channels);
      }
      out.runs.push_back (std::move (sections));
    }
    if (attributes && shared.channels.empty ())
      shared.channels = encodeAttributeSections (subModel (model, 0, 0), attribute_tolerance, range_coded).channels;
    return out;
  }

  int
  zstdLevelFor (std::size_t raw_bytes, const ModelWriteOptions& options)
  {
    if (options.zstd_level == 0 || raw_bytes <= options.zstd_large_section)
      return options.zstd_level;
    return std::min (options.zstd_level, options.zstd_large_level);
  }

  std::vector<std::uint8_t>
  encodeModel (const SparseSurfaceModel& model, const ModelWriteOptions& options)
  {
    return encodeModel (model, options, {});
  }

  std::vector<std::uint8_t>
  encodeModel (const SparseSurfaceModel& model, const ModelWriteOptions& options, const std::vector<FootprintSlack>& slack)
  {
    ModelSections parts = encodeModelSections (model, options, {{0, model.patches.size ()}}, slack.empty () ? nullptr : &slack);
    const SharedModelFields& shared = parts.shared;
    const bool quantised = shared.flags & header_flag::quantised;
    std::vector<Section> sections;
    if (quantised)
      sections.push_back ({"QUAN", kCodecStored, std::move (parts.shared.quantisation)});
    const std::vector<std::string> tags = runSectionTags (shared.flags);
    for (std::size_t i = 0; i < tags.size (); ++i)
    {
      if (tags[i] == "AATM")
        sections.push_back ({"ACHN", kCodecStored, std::move (parts.shared.channels)});
      sections.push_back ({tags[i], kCodecZstd, std::move (parts.runs[0][i])});
    }

    ByteWriter out;
    out.putBytes (kMagic, sizeof kMagic);
    out.putU16 (kVersion);
    out.putU16 (shared.flags);
    out.putU8 (shared.basis_kind);
    out.putU8 (0);
    out.putU16 (shared.basis_parameter);
    out.putU32 (static_cast<std::uint32_t> (model.patches.size ()));
    out.putU32 (static_cast<std::uint32_t> (sections.size ()));
    out.putU64 (model.num_input_vertices);
    out.putF64 (model.bbox_diagonal);
    out.putF64 (options.tolerance);
    out.putU32 (crc32 (out.bytes ().data (), out.size ()));
    for (Section& section : sections)
    {
      std::vector<std::uint8_t> payload = section.raw;
      if (options.zstd_level == 0)
        section.codec = kCodecStored;
      if (section.codec == kCodecZstd)
      {
        payload = compressBytes (section.raw.data (), section.raw.size (), zstdLevelFor (section.raw.size (), options));
        // Stored where zstd does not help (range-coded sections), or where the reader would refuse the ratio.
        if (payload.size () >= section.raw.size () || section.raw.size () > kMaxExpansion * payload.size () + kExpansionSlack)
        {
          section.codec = kCodecStored;
          payload = section.raw;
        }
      }
      const std::size_t start = out.size ();
      out.putBytes (reinterpret_cast<const std::uint8_t*> (section.tag.data ()), 4);
      out.putU8 (section.codec);
      out.putU8 (0);
      out.putU8 (0);
      out.putU8 (0);
      out.putU64 (payload.size ());
      out.putU64 (section.raw.size ());
      out.putU32 (crc32 (payload.data (), payload.size ()));
      out.putU32 (crc32 (out.bytes ().data () + start, kSectionHeaderBytes - 4));
      out.putBytes (payload.data (), payload.size ());
    }
    return std::move (out.bytes ());
  }

  void
  checkSharedModelFields (const SharedModelFields& shared, const std::string& name)
  {
    checkHeaderValues (shared.flags, shared.basis_kind, shared.basis_parameter, 0, shared.num_input_vertices,
                       shared.bbox_diagonal, shared.tolerance, name);
    if (shared.quantisation.empty () != !(shared.flags & header_flag::quantised) ||
        shared.channels.empty () != !(shared.flags & header_flag::attributes))
      throw Error (name + ": the shared sections do not match the flags");
  }

  SparseSurfaceModel
  decodeModelSections (const SharedModelFields& shared, std::size_t num_patches,
                       const std::vector<std::pair<const std::uint8_t*, std::size_t>>& payloads, const std::string& name)
  {
    const bool quantised = shared.flags & header_flag::quantised;
    const std::size_t m = num_patches;
    const std::vector<std::string> tags = runSectionTags (shared.flags);
    if (payloads.size () != tags.size ())
      throw Error (name + ": " + std::to_string (payloads.size ()) + " sections, expected " + std::to_string (tags.size ()));
    if (m > kMaxPatches)
      throw Error (name + ": number of patches " + std::to_string (m) + " out of range");

    SparseSurfaceModel model;
    model.basis = makeCosineBasis (basisKindOfByte (shared.basis_kind), shared.basis_parameter);
    model.num_input_vertices = shared.num_input_vertices;
    model.bbox_diagonal = shared.bbox_diagonal;

    std::size_t next = 0;
    auto open = [&] () {
      const std::size_t i = next++;
      return ByteReader (payloads[i].first, payloads[i].second, name + ": section " + tags[i]);
    };
    QuantisationParameters q;
    if (quantised)
    {
      ByteReader in (shared.quantisation.data (), shared.quantisation.size (), name + ": section QUAN");
      q = readQuantisation (in);
      model.footprint_step = q.extentStep ();
    }
    ByteReader seed = open ();
    ByteReader frame = open ();
    ByteReader radius = open ();
    ByteReader foot = open ();
    ByteReader atom = open ();
    ByteReader coef = open ();
    const bool range_coded = shared.flags & header_flag::range_coded;
    const bool adaptive_footprints = shared.flags & header_flag::adaptive_footprints;
    const bool coded_seeds = shared.flags & header_flag::coded_seeds;
    checkSectionSizes (seed, frame, radius, foot, atom, m, quantised, range_coded, coded_seeds, q);
    // A range-coded patch may take less than a byte (a 155 KB file decoded to 1 GB of patches): what the
    // header promises must fit in memory before the first patch is decoded, or a few MB end in an OOM kill.
    checkFitsInMemory (static_cast<double> (m) * kDecodedBytesPerPatch, name + ": " + std::to_string (m) + " patches");
    // Patches are added as they decode, not made for the m the header promises up front: SEED and RADI
    // hold only a few bytes a patch, which zstd may shrink 64 times (and a range-coded patch may take less
    // than a byte), so a 280 KB file promising 4 million patches had the reader take 1.1 GB (285 bytes a
    // patch and 32 of unpacked seed and radius integers) before its first patch failed to decode.
    model.patches.reserve (std::min<std::size_t> (m, 4096));
    // Adaptive footprints draw the angles no split reached from the coded ones, so a few bits of FOOT can
    // stand for 4096 extents: the run's extents are held to what its FOOT bytes justify (default files
    // of the shared meshes: 4-7 angles a byte).
    const std::size_t max_angles = kFootprintAnglesAllowance + kFootprintAnglesPerByte * foot.remaining ();
    std::size_t angles = 0;
    // Range-coded: one decoder per section over all its bytes (the ByteReaders are then at their end).
    std::optional<RangeCodedPatchSections> coded;
    if (range_coded)
      coded.emplace (frame, foot, atom, coef, q.extent_bits, shared.basis_parameter, monomialsOfKindByte (shared.basis_kind),
                     adaptive_footprints);

    const std::uint8_t* seed_planes = nullptr;
    const std::uint8_t* radius_planes = nullptr;
    std::optional<RangeDecoder> coded_seed;
    SeedStepCoder seed_coder;
    if (coded_seeds)
      coded_seed.emplace (rangeDecoderOverRest (seed));
    else if (quantised)
      seed_planes = seed.getBytes (3 * m * static_cast<std::size_t> (q.seed_bytes), "seed");
    if (quantised)
      radius_planes = radius.getBytes (m * static_cast<std::size_t> (q.radius_bytes), "radius");
    const std::uint64_t seed_limit = std::uint64_t{1} << (8 * q.seed_bytes);
    for (std::size_t p = 0; p < m; ++p)
    {
      model.patches.emplace_back ();
      PatchCode& patch = model.patches.back ();
      std::array<std::uint64_t, 3> seed_steps{};
      if (coded_seed)
        seed_steps = seed_coder.get (*coded_seed, seed_limit);
      readPlacement (seed, radius, quantised, q, coded_seed ? &seed_steps : nullptr, seed_planes, radius_planes, m, p,
                     patch);
      if (coded)
        coded->readPatch (q, p, patch);
      else if (adaptive_footprints)
        getFootprint (foot, q.footprintLevels (), p, patch.footprint);
      else
        readUniformFootprint (foot, quantised, q, p, patch.footprint);
      angles += patch.footprint.extent.size ();
      if (angles > max_angles)
        foot.fail ("the footprints hold more angles than its bytes justify (patch " + std::to_string (p) + ")");
      if (coded)
        continue;
      getCodeAtoms (atom, quantised, shared.basis_parameter, "patch " + std::to_string (p), patch.atoms,
                    monomialsOfKindByte (shared.basis_kind));
      readCoefficients (coef, quantised, q, patch);
      readFrame (frame, quantised, q, p, patch);
    }
    if (coded)
      coded->expectEnd ();
    if (coded_seed)
      coded_seed->expectEnd ();
    seed.expectEnd ();
    frame.expectEnd ();
    radius.expectEnd ();
    foot.expectEnd ();
    atom.expectEnd ();
    coef.expectEnd ();

    if (shared.flags & header_flag::vertices)
    {
      ByteReader vert = open ();
      readVertices (vert, quantised, shared.num_input_vertices, model.patches);
    }
    if (shared.flags & header_flag::attributes)
    {
      ByteReader channels (shared.channels.data (), shared.channels.size (), name + ": section ACHN");
      ByteReader attribute_atoms = open ();
      ByteReader attribute_coefs = open ();
      decodeAttributeSections (channels, attribute_atoms, attribute_coefs, quantised, range_coded, model);
    }
    return model;
  }

  SparseSurfaceModel
  decodeModel (const std::uint8_t* data, std::size_t size, const std::string& name)
  {
    if (isTiledModelData (data, size))
      return decodeTiledModel (data, size, name).model;
    const Container container = readContainer (data, size, name);
    const Header& h = container.header;
    SharedModelFields shared;
    shared.flags = h.flags;
    shared.basis_kind = h.basis_kind;
    shared.basis_parameter = h.basis_parameter;
    shared.num_input_vertices = h.num_input_vertices;
    shared.bbox_diagonal = h.bbox_diagonal;
    shared.tolerance = h.tolerance;
    std::vector<std::vector<std::uint8_t>> storage;
    std::vector<std::pair<const std::uint8_t*, std::size_t>> payloads;
    storage.reserve (container.sections.size ());
    for (const StoredSection& section : container.sections)
    {
      std::vector<std::uint8_t> bytes = sectionBytes (section, name);
      if (section.tag == "QUAN")
        shared.quantisation = std::move (bytes);
      else if (section.tag == "ACHN")
        shared.channels = std::move (bytes);
      else
      {
        storage.push_back (std::move (bytes));
        payloads.emplace_back (storage.back ().data (), storage.back ().size ());
      }
    }
    return decodeModelSections (shared, h.num_patches, payloads, name);
  }

  ModelFileInfo
  inspectModel (const std::uint8_t* data, std::size_t size, const std::string& name)
  {
    if (isTiledModelData (data, size))
      return inspectTiledModel (data, size, name);
    const Container container = readContainer (data, size, name);
    ModelFileInfo info;
    info.version = container.header.version;
    info.quantised = container.header.flags & header_flag::quantised;
    info.range_coded = container.header.flags & header_flag::range_coded;
    info.has_vertices = container.header.flags & header_flag::vertices;
    if (container.header.flags & header_flag::attributes)
    {
      const StoredSection& section = container.sections[container.sections.size () - 3];
      const std::vector<std::uint8_t> bytes = sectionBytes (section, name);
      ByteReader channels (bytes.data (), bytes.size (), name + ": section " + section.tag);
      for (const AttributeChannelInfo& channel : decodeAttributeChannels (channels, info.quantised))
        info.attributes.push_back (attributeChannelName (channel.channel));
    }
    info.basis = basisDescription (container.header.basis_kind, container.header.basis_parameter);
    info.num_patches = container.header.num_patches;
    info.num_input_vertices = container.header.num_input_vertices;
    info.bbox_diagonal = container.header.bbox_diagonal;
    info.tolerance = container.header.tolerance;
    info.file_bytes = size;
    for (const StoredSection& s : container.sections)
      info.sections.push_back ({s.tag, s.stored, s.raw});
    return info;
  }

  void
  saveModel (const std::string& path, const SparseSurfaceModel& model, const ModelWriteOptions& options)
  {
    const std::vector<std::uint8_t> bytes = encodeModel (model, options);
    writeBytesAtomically (path, bytes.data (), bytes.size ());
  }

  namespace
  {
    std::vector<std::uint8_t>
    readWholeFile (const std::string& path)
    {
      std::error_code error;
      if (!std::filesystem::is_regular_file (path, error))
        throw Error (path + ": no such model file (or not a regular file)");
      std::ifstream in (path, std::ios::binary | std::ios::ate);
      if (!in)
        throw Error (path + ": cannot open model file");
      const std::streamoff size = in.tellg ();
      if (size < 0)
        throw Error (path + ": cannot read model file (not a regular file?)");
      in.seekg (0);
      std::vector<std::uint8_t> bytes (static_cast<std::size_t> (size));
      if (size > 0 && !in.read (reinterpret_cast<char*> (bytes.data ()), size))
        throw Error (path + ": cannot read model file");
      return bytes;
    }
  } // namespace

  SparseSurfaceModel
  loadModel (const std::string& path)
  {
    const std::vector<std::uint8_t> bytes = readWholeFile (path);
    return decodeModel (bytes.data (), bytes.size (), path);
  }

  ModelFileInfo
  inspectModelFile (const std::string& path)
  {
    const std::vector<std::uint8_t> bytes = readWholeFile (path);
    return inspectModel (bytes.data (), bytes.size (), path);
  }
} // namespace pcl_sparse
