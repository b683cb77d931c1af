#pragma once
/// \file footprint_coding.h
/// A quantised file's footprints (section FOOT, docs/FORMAT.md): extents as levels of one step, every
/// stride-th angle always, and the angles between two of them only where the line between their levels
/// strays too far from the footprint (summed over the angles between them). Such an interval is split at its middle angle, whose level is coded
/// against the mean of the ends, and each half is treated the same way. A footprint clipped at a crease
/// keeps its angles there and only there; a round one keeps its coarse angles. Readers draw the footprint
/// through the coded levels (linear between them, as resampling interpolates extents anyway). Where a
/// border lies on a knife edge (FootprintSlack::knife_edge) it is drawn at most one level inside the extent:
/// the other side's places there are left unsampled only within this footprint, which a reader widens by
/// one level (SparseSurfaceModel::footprint_step, PatchOwnership). At a trim cut (PatchFootprint::trimmed) it
/// is drawn nowhere outside the extent, its level rounded down: past the cut the code's normal points away
/// from the surface, and a border rounded or interpolated out there emitted those places again.

#include <pcl_sparse/format/byte_stream.h>
#include <pcl_sparse/format/range_coder.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/resampling/footprint_slack.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// The most angles a footprint in a model file may have (docs/FORMAT.md).
  constexpr std::uint32_t max_file_footprint_angles = 4096;

  /// The levels of a file's extents: extent = level * step, levels on \a bits bits.
  struct FootprintLevels
  {
    double step = 1.0;  ///< extent of one level (QUAN: extent_max / (2^bits - 1))
    int bits = 4;       ///< bits per level (2..8)
  };

  /// Which angles a writer keeps (ModelWriteOptions::max_footprint_angles, footprint_refine_steps).
  struct FootprintRefinement
  {
    /// Coarse angles: every stride-th, the stride doubled while more than this many remain and it divides
    /// the angle count; 0 keeps every angle.
    int max_coarse_angles = 2;
    /// An interval between coded angles is split while the extents inside it stray from the line between
    /// their levels by more than this many steps in all (summed over its angles: the area between the
    /// border drawn and the true one, so no single extent strays further) and some of them would round to
    /// another level than the line; 0 keeps the coarse angles only.
    double max_deviation_steps = 2.0;
  };

  /// The adaptive models of a range-coded FOOT section (one set per section, or per tile run); the writer
  /// and the reader build the same ones and code the same symbols in the same order.
  struct FootprintContexts
  {
    explicit FootprintContexts (int bits);

    /// Interval depths from this one on share the last models.
    static constexpr int depth_contexts = 4;
    /// Classes of how far apart an interval's end levels are: 0, 1, 2-3, more.
    static constexpr int end_contexts = 4;

    BitTreeModel angles{13};               ///< the angle count (<= 4096)
    BitTreeModel stride_log2{4};           ///< log2 of the coarse stride
    BitTreeModel first_level;              ///< the first coarse level
    BitTreeModel level_delta;              ///< the next coarse levels, as circular deltas
    std::vector<BitTreeModel> split;       ///< per depth and end class: whether the interval is split
    std::vector<BitTreeModel> residual;    ///< per depth and end class: the middle level minus the ends' mean, circular
  };

  /// Writes \a footprint's symbols in the varint layout (one byte each, the count as a varint).
  /// \param[in,out] out     receives the symbols
  /// \param[in] footprint   the footprint
  /// \param[in] levels      the extent levels (QUAN)
  /// \param[in] refinement  which angles to keep
  /// \param[in] slack  where each extent may be drawn instead (nullptr, or vectors of another length: at the
  ///                   extent itself); only which intervals split depends on it (also where an interval's
  ///                   line passes over a level inside the extent of a knife-edge angle,
  ///                   FootprintSlack::knife_edge), never the levels coded (those depend on the extents
  ///                   and PatchFootprint::trimmed only)
  /// \return the number of angles a reader gets (getFootprint)
  std::size_t
  putFootprint (ByteWriter& out, const PatchFootprint& footprint, const FootprintLevels& levels,
                const FootprintRefinement& refinement, const FootprintSlack* slack = nullptr);

  /// Writes \a footprint's symbols with the range coder, with \a contexts' models (the rest as above).
  /// \return the number of angles a reader gets (getFootprint)
  std::size_t
  putFootprint (RangeEncoder& out, FootprintContexts& contexts, const PatchFootprint& footprint,
                const FootprintLevels& levels, const FootprintRefinement& refinement,
                const FootprintSlack* slack = nullptr);

  /// Reads a footprint of the varint layout into \a footprint: the coarse extents if no interval was split,
  /// else every angle (interpolated between the coded ones).
  /// \throws pcl_sparse::Error (via \a in) naming patch \a patch for out-of-range symbols
  void
  getFootprint (ByteReader& in, const FootprintLevels& levels, std::size_t patch, PatchFootprint& footprint);

  /// Reads a range-coded footprint, as the varint one.
  void
  getFootprint (RangeDecoder& in, FootprintContexts& contexts, const FootprintLevels& levels, std::size_t patch,
                PatchFootprint& footprint);
} // namespace pcl_sparse
