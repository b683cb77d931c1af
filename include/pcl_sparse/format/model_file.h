#pragma once
/// \file model_file.h
/// The .psm file format for SparseSurfaceModel: save, load, and inspect. docs/FORMAT.md is the
/// byte-level specification; this header is the API.
///
/// Two modes:
///  - lossless (tolerance 0): every double and float stored as it is in memory; a loaded model has
///    bit-identical fields and therefore resamples to a bit-identical cloud;
///  - quantised (tolerance t > 0): seeds, frames (quaternions), radii (log scale), coefficients and
///    footprint extents are quantised with steps chosen so that every surface point s + r R (x, y, h(x, y))
///    of every patch, at any (x, y) of its footprint, moves by at most t * bbox_diagonal (worst case;
///    see docs/FORMAT.md for the error budget). Atoms of a patch come back sorted by frequency shell
///    (max(i, j), then i, j); footprints keep at most max_footprint_angles angles. Colour / intensity codes
///    are quantised so that no attribute value moves by more than attribute_tolerance x its range.
/// All streams are zstd-coded; every section carries a CRC-32; the loader refuses anything malformed
/// with pcl_sparse::Error and never allocates more than the file's declared, bounds-checked sizes.

#include <pcl_sparse/model/sparse_surface_model.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  struct FootprintSlack;  // resampling/footprint_slack.h

  /// Options for saveModel / encodeModel.
  struct ModelWriteOptions
  {
    /// Largest displacement of any surface point, as a fraction of the model's bbox_diagonal.
    /// 0 (default) stores everything losslessly. 1e-4 is well below what resampling shows.
    double tolerance = 0.0;
    /// Bits per footprint extent in quantised mode (2..8). Extents only bound where resampling draws
    /// points, they do not move the surface; 4 bits = 1/15 of the largest extent (on spot, 6 bits cost
    /// 10 % more bytes for no measurable change of the Chamfer distance). Where the model's error is concentrated
    /// at creases, footprint borders across them overshoot by up to half a level: derivedWriteOptions takes 5.
    int extent_bits = 4;
    /// In quantised mode, every patch keeps this many footprint angles (every 2nd, 4th, ... extent, while the
    /// count stays a multiple; the others only where footprint_refine_steps needs them); 0 keeps all. 2 (two
    /// opposite angles, the refinement adding the rest where the border needs them) against 8, the default
    /// until 2026-12-01: default files 0.5-3.8 % smaller on 24 of the 25 shared meshes (couplingdown 0.5 %
    /// larger), the Chamfer distance over the lossless model's within 0.1 points or lower on every one
    /// (bench/results/file_tolerance_rule.md, notes); 1 codes the same as 2 within 0.2 %.
    int max_footprint_angles = 2;
    /// In quantised mode, the angles between two kept ones are kept where the footprint drawn from those two
    /// strays from the full one by more than this many extent steps (the largest extent / (2^extent_bits -
    /// 1)) summed over the angles between them: the middle angle, then each half the same way
    /// (footprint_coding.h). Footprints clipped at a crease or an open border keep their angles there and
    /// only there. 0: every patch keeps max_footprint_angles. With 8 angles everywhere the default file added
    /// 3-174 % to the Chamfer distance of the lossless model on the shared meshes (footprints clipped at
    /// borders and creases overshoot or cut the surface between 8 rays); at 2 steps it adds at most 10 % on
    /// 23 of 25 (anchor-dense 15 %, fandisk 12.8 %: their 4-bit extents; derivedWriteOptions gives those two
    /// 5-bit extents at the same 2 steps: 8.0 %, 7.0 %), 0.2-6.6 % on the others (file_footprints.md; footprint_slack.md
    /// with the slack below).
    double footprint_refine_steps = 2.0;
    /// In quantised mode, refine a footprint only where its border must stay put: where a same-side neighbour
    /// holds the places at the border more centrally, resampling gives them to the neighbour whether the
    /// border is drawn a little in or out, so the refinement measures the drawn border against that slack
    /// (resampling/footprint_slack.h) instead of the exact extent. Only the writer's choice of angles changes;
    /// readers need nothing. On the 25 shared meshes: default files 1.2-11.2 % smaller, the Chamfer distance
    /// the same or lower on 22 (cheese-cgal +0.8 points, igea +0.2, couplingdown +0.1), the writer 10-180 ms
    /// slower (bench/results/footprint_slack.md). With it, a border on a knife edge is also drawn at most one
    /// level inside its extent (FootprintSlack::knife_edge), which readers clear past (footprint_step).
    bool footprint_slack = true;
    /// Store each patch's input vertices and their local (x', y') (needed only to reconstruct the
    /// input vertices, docs/METHOD.md step 10). Off by default: decoding and resampling do not need them.
    bool include_vertices = false;
    /// Quantised mode, models with colour / intensity: the largest change of an attribute value, as a
    /// fraction of its channel's range (AttributeChannelInfo; 255 for colour, so 1/2 grey level by default).
    /// Lossless files store the attribute codes bit for bit.
    double attribute_tolerance = 0.5 / 255.0;
    /// Quantised mode: code the per-patch fields FRAM FOOT ATOM COEF (and AATM ACOF) with an adaptive range
    /// coder, each field with its own probabilities (docs/FORMAT.md, "Range-coded fields"), instead of zstd
    /// over varints: 12.0-15.0 % smaller default files on eight shared meshes (bench/results/format_entropy.md,
    /// with the sections of each). false writes the varint
    /// layout (readable by builds since the adaptive footprints of 2026-12-01, as the range-coded one).
    bool range_coding = true;
    /// zstd level (1..22) of every section up to zstd_large_section bytes; 19 compresses well, at about
    /// 6 MB/s. 0 stores every section uncompressed (for inspection and the fuzzer's seed corpus).
    int zstd_level = 19;
    /// Sections larger than this (uncompressed bytes) take zstd_large_level when that is lower. At level 19
    /// encoding office1's lossless model (11 MB) took 3.0 s, twice the model's own encoding; with level 9
    /// above 1 MiB it takes 0.7 s for 1.2 % more bytes (bench/results/file_write_speed.md). No quantised file
    /// of the shared meshes and scans, and no lossless file of a shared mesh, has a section that large: their
    /// bytes stay level 19's (level 9 everywhere would cost cheese-cgal's lossless file 6 %, to save 0.1 s).
    std::size_t zstd_large_section = std::size_t (1) << 20;
    /// zstd level (1..22) of the sections larger than zstd_large_section (at most zstd_level).
    int zstd_large_level = 9;
  };

  /// The zstd level encodeModel gives a section of \a raw_bytes uncompressed bytes (0: stored): zstd_level,
  /// or above zstd_large_section the lower of it and zstd_large_level.
  int
  zstdLevelFor (std::size_t raw_bytes, const ModelWriteOptions& options);

  /// One section of a model file as stored.
  struct ModelFileSection
  {
    std::string tag;                ///< four letters, e.g. "COEF"
    std::uint64_t stored_bytes = 0; ///< bytes in the file (compressed), excluding its 32-byte header
    std::uint64_t raw_bytes = 0;    ///< bytes after decompression
  };

  /// What a model file holds, without decoding its patches (for pcl_sparse_info).
  struct ModelFileInfo
  {
    std::uint16_t version = 0;              ///< format version
    bool quantised = false;                 ///< written with a tolerance > 0
    bool range_coded = false;               ///< quantised, with range-coded per-patch fields (ModelWriteOptions::range_coding)
    bool has_vertices = false;              ///< holds the patches' input vertices and their (x', y')
    std::vector<std::string> attributes;    ///< attribute channels ("r", "g", "b", "a", "intensity"); empty: none
    std::string basis;                      ///< "cosine nxn" (the paper's atoms), "dct cosine nxn" or "quadric + dct cosine nxn"
    std::uint32_t num_patches = 0;          ///< M
    std::uint64_t num_input_vertices = 0;   ///< N_V of the encoded mesh
    double bbox_diagonal = 0.0;             ///< of the encoded mesh
    double tolerance = 0.0;                 ///< as written (fraction of bbox_diagonal)
    std::uint64_t file_bytes = 0;           ///< total size
    std::size_t num_tiles = 0;              ///< tiles of a tiled file (version 2 or 3, tiled_model_file.h); 0 otherwise
    std::vector<ModelFileSection> sections; ///< in file order
  };

  /// Encodes a model into the bytes of a .psm file.
  /// \param[in] model    the model
  /// \param[in] options  tolerance, footprint bits and angles, vertices, zstd level
  /// \return the file's bytes
  /// \throws pcl_sparse::Error for a model the format cannot hold (basis other than CosineDictionary /
  ///         DctCosineDictionary, non-finite values, tolerance > 0 with bbox_diagonal <= 0) or options out
  ///         of range
  std::vector<std::uint8_t>
  encodeModel (const SparseSurfaceModel& model, const ModelWriteOptions& options = ModelWriteOptions ());

  /// encodeModel with the footprints' slack found beforehand: a writer that tries several options on one model
  /// (measuredWriteOptions) finds it once. The same bytes as encodeModel (model, options).
  /// \param[in] model    the model
  /// \param[in] options  as for encodeModel
  /// \param[in] slack    footprintSlack (model) (resampling/footprint_slack.h), one per patch; empty: found here
  ///                     where the options take it
  /// \throws pcl_sparse::Error as encodeModel, or for a slack that is not the model's (counts of patches or angles)
  std::vector<std::uint8_t>
  encodeModel (const SparseSurfaceModel& model, const ModelWriteOptions& options, const std::vector<FootprintSlack>& slack);

  /// Decodes the bytes of a .psm file; a tiled file (version 2 or 3, tiled_model_file.h) gives its tiles' patches
  /// merged into one model.
  /// \param[in] data  first byte
  /// \param[in] size  number of bytes
  /// \param[in] name  names the data in error messages
  /// \return the model
  /// \throws pcl_sparse::Error with a one-line message for anything malformed
  SparseSurfaceModel
  decodeModel (const std::uint8_t* data, std::size_t size, const std::string& name = "model");

  /// Header and section sizes of the bytes of a .psm file (checksums verified, patches not decoded).
  /// \param[in] data  first byte
  /// \param[in] size  number of bytes
  /// \param[in] name  names the data in error messages
  /// \return what the file holds
  /// \throws pcl_sparse::Error for anything malformed
  ModelFileInfo
  inspectModel (const std::uint8_t* data, std::size_t size, const std::string& name = "model");

  /// encodeModel, written atomically (writeBytesAtomically).
  /// \param[in] path     the file
  /// \param[in] model    the model
  /// \param[in] options  as for encodeModel
  /// \throws pcl_sparse::Error as encodeModel, or for a failed write
  void
  saveModel (const std::string& path, const SparseSurfaceModel& model,
             const ModelWriteOptions& options = ModelWriteOptions ());

  /// Reads a .psm file and decodes it.
  /// \param[in] path  the file
  /// \return the model
  /// \throws pcl_sparse::Error naming the file if it cannot be read or is malformed
  SparseSurfaceModel
  loadModel (const std::string& path);

  /// Reads a .psm file and inspects it (inspectModel).
  /// \param[in] path  the file
  /// \return what the file holds
  /// \throws pcl_sparse::Error naming the file if it cannot be read or is malformed
  ModelFileInfo
  inspectModelFile (const std::string& path);
} // namespace pcl_sparse
