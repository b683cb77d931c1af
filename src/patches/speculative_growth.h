#pragma once

#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_growth.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace pcl_sparse
{
  /// Grows the sampling loop's next candidates on helper threads while the loop decides on the current one.
  ///
  /// The loop (feature_aware_patch_sampling.cpp) is sequential: whether a candidate grows depends on the
  /// patches kept before it. But a grown patch depends only on its seed (PatchGrower::grow), so helpers
  /// can grow the next candidates that are still valid, and the loop takes their patches when it gets
  /// there: the output is the sequential loop's, for any number of threads. The loop never waits idle: when
  /// a helper is still growing the candidate it needs, it grows a later one itself meanwhile, and it grows a
  /// candidate no helper has claimed itself. (An earlier version grew batches in parallel with a barrier
  /// after each, and was 3-6x slower than one thread on a loaded machine.) A helper whose candidate became
  /// invalid before the loop got there has wasted its work, nothing else.
  ///
  /// Each helper holds its own PatchGrower (about 14 bytes per vertex).
  class SpeculativeGrowth
  {
  public:
    /// \a order: the loop's candidates; \a never_grown: per vertex, 1 where the loop never grows a patch
    /// (not referenced by a face, outside the seed region); \a invalid: the loop's invalid flags (it writes
    /// them with relaxed stores while the helpers read them). \a helpers threads are started (0: none, and
    /// grow () grows every patch itself).
    SpeculativeGrowth (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                       const PatchOptions& options, const std::vector<int>& order,
                       const std::vector<std::uint8_t>& never_grown, const std::atomic<std::uint8_t>* invalid,
                       int helpers);
    /// Stops and joins the helpers.
    ~SpeculativeGrowth ();

    SpeculativeGrowth (const SpeculativeGrowth&) = delete;
    SpeculativeGrowth& operator= (const SpeculativeGrowth&) = delete;

    /// The patch of candidate order[\a position] in \a patch, and its growth radius (as \a grower.grow
    /// returns it); \a grower is the loop's. Positions must be asked for in increasing order.
    double grow (std::size_t position, PatchGrower& grower, Patch& patch);

    /// Candidates whose patch a helper grew and the loop took, for tests and benchmarks.
    std::size_t numTaken () const { return taken_; }

  private:
    /// A slot holds the patch of one position of a window ahead of the loop; its tag is
    /// (position + 1) * 4 + state, 0 for a slot never used.
    enum SlotState : std::uint64_t { Claimed = 1, Done = 2, Owned = 3 };
    struct Slot
    {
      std::atomic<std::uint64_t> tag{0};
      Patch patch;
      double radius = 0.0;
    };

    static std::uint64_t tagOf (std::size_t position, SlotState state) { return (position + 1) * 4 + state; }

    /// Claims the first position after the loop's, within the window, whose candidate is valid and not
    /// claimed, and grows its patch into its slot with \a grower; \a next: where this thread looks first.
    /// False if there was none.
    bool growAhead (PatchGrower& grower, std::size_t& next);
    void runHelper ();

    const TriangleMesh& mesh_;
    const MeshTopology& topology_;
    const PatchGrowthGeometry& geometry_;
    const PatchOptions& options_;
    const std::vector<int>& order_;
    const std::vector<std::uint8_t>& never_grown_;
    const std::atomic<std::uint8_t>* invalid_;
    std::unique_ptr<Slot[]> slots_;
    std::atomic<std::size_t> cursor_{0};  ///< the position the loop is at
    std::atomic<bool> stop_{false};
    std::size_t loop_next_ = 0;  ///< where the loop looks first when it grows ahead
    std::size_t taken_ = 0;
    std::vector<std::thread> helpers_;
  };
} // namespace pcl_sparse
