#include "speculative_growth.h"

#include <chrono>
#include <utility>

namespace pcl_sparse
{
  namespace
  {
    /// Positions ahead of the loop a helper may claim. Helpers claim the first valid ones, so they stay
    /// near the loop; the window only bounds the slots (a position's slot is position % kWindow).
    constexpr std::size_t kWindow = 256;
    /// A helper with nothing to claim yields this many times before it sleeps between looks.
    constexpr int kIdleYields = 64;
  } // namespace

  SpeculativeGrowth::SpeculativeGrowth (const TriangleMesh& mesh, const MeshTopology& topology,
                                        const PatchGrowthGeometry& geometry, const PatchOptions& options,
                                        const std::vector<int>& order, const std::vector<std::uint8_t>& never_grown,
                                        const std::atomic<std::uint8_t>* invalid, int helpers)
    : mesh_ (mesh)
    , topology_ (topology)
    , geometry_ (geometry)
    , options_ (options)
    , order_ (order)
    , never_grown_ (never_grown)
    , invalid_ (invalid)
  {
    if (helpers <= 0)
      return;
    slots_.reset (new Slot[kWindow]);
    try
    {
      for (int h = 0; h < helpers; ++h)
        helpers_.emplace_back (&SpeculativeGrowth::runHelper, this);
    }
    catch (...)
    {
      stop_ = true;
      for (auto& t : helpers_)
        t.join ();
      throw;
    }
  }

  SpeculativeGrowth::~SpeculativeGrowth ()
  {
    stop_ = true;
    for (auto& t : helpers_)
      t.join ();
  }

  bool
  SpeculativeGrowth::growAhead (PatchGrower& grower, std::size_t& next)
  {
    const std::size_t cursor = cursor_.load (std::memory_order_acquire);
    next = std::max (next, cursor + 1);
    const std::size_t end = std::min (order_.size (), cursor + kWindow);
    while (next < end)
    {
      const std::size_t j = next++;
      const int v = order_[j];
      if (never_grown_[v] || invalid_[v].load (std::memory_order_relaxed))
        continue;
      Slot& slot = slots_[j % kWindow];
      std::uint64_t tag = slot.tag.load (std::memory_order_acquire);
      // Claimed already, or the slot's earlier position is still being grown by a helper left behind.
      if (tag >= tagOf (j, Claimed) || (tag & 3) == Claimed)
        continue;
      if (!slot.tag.compare_exchange_strong (tag, tagOf (j, Claimed), std::memory_order_acq_rel))
        continue;
      try
      {
        slot.radius = grower.grow (v, slot.patch);
      }
      catch (...)
      {
        // The loop grows it again itself (and meets the error there, if it is one).
        slot.tag.store (tagOf (j, Owned), std::memory_order_release);
        throw;
      }
      slot.tag.store (tagOf (j, Done), std::memory_order_release);
      return true;
    }
    return false;
  }

  void
  SpeculativeGrowth::runHelper ()
  {
    try
    {
      PatchGrower grower (mesh_, topology_, geometry_, options_);
      std::size_t next = 0;
      int idle = 0;
      while (!stop_.load (std::memory_order_relaxed))
      {
        if (growAhead (grower, next))
          idle = 0;
        else if (++idle < kIdleYields)
          std::this_thread::yield ();
        else
          std::this_thread::sleep_for (std::chrono::microseconds (50));
      }
    }
    catch (...)
    {
      // Out of memory, most likely: the helper stops, and the loop grows what is left itself.
    }
  }

  double
  SpeculativeGrowth::grow (std::size_t position, PatchGrower& grower, Patch& patch)
  {
    const int v = order_[position];
    if (helpers_.empty ())
      return grower.grow (v, patch);
    cursor_.store (position, std::memory_order_release);
    Slot& slot = slots_[position % kWindow];
    for (;;)
    {
      std::uint64_t tag = slot.tag.load (std::memory_order_acquire);
      if (tag == tagOf (position, Done))
      {
        ++taken_;
        std::swap (patch, slot.patch);
        return slot.radius;
      }
      if (tag == tagOf (position, Claimed))
      {
        // A helper is growing it: grow a later candidate meanwhile rather than wait.
        if (!growAhead (grower, loop_next_))
          std::this_thread::yield ();
        continue;
      }
      // No helper has it: claim it, so that none starts it, and grow it here. A slot still held by a
      // helper left behind on an earlier position cannot be claimed; no helper can take it either.
      if ((tag & 3) == Claimed || tag == tagOf (position, Owned) ||
          slot.tag.compare_exchange_strong (tag, tagOf (position, Owned), std::memory_order_acq_rel))
        return grower.grow (v, patch);
    }
  }
} // namespace pcl_sparse
