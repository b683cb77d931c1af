#pragma once

/// Mesh vertex id -> index in a patch's vertex list, for the coder's per-patch loops over the patch's
/// triangles (footprints, surface samples). A per-thread array over the mesh's vertices, set for the
/// patch's vertices only and reset by the destructor: O(patch) per patch and one load per corner, where
/// a sorted (id, index) array cost a sort and a binary search per corner (a tenth of the coding stage).
/// One at a time per thread (the array is shared by the thread's instances: a second one on the same thread
/// throws std::logic_error). The array keeps the size of the largest mesh the thread has seen (4 bytes a
/// vertex).

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace pcl_sparse
{
  class PatchLocalIndex
  {
  public:
    /// \param[in] vertices      the patch's mesh vertex ids; only the first \a count are indexed
    /// \param[in] count         how many of them
    /// \param[in] num_vertices  the mesh's vertex count (larger ids are never looked up)
    PatchLocalIndex (const std::vector<int>& vertices, std::size_t count, std::size_t num_vertices)
      : vertices_ (vertices), count_ (count), map_ (scratch ())
    {
      if (inUse ())
        throw std::logic_error ("PatchLocalIndex: two at a time on one thread");
      if (map_.size () < num_vertices)
        map_.resize (num_vertices, -1);
      inUse () = true;  // after the only step that may throw (the destructor of a throwing constructor never runs)
      // Backwards, so that a repeated id keeps its first index (what the binary search found).
      for (std::size_t i = count_; i-- > 0;)
        if (inRange (vertices_[i]))
          map_[vertices_[i]] = static_cast<int> (i);
    }

    ~PatchLocalIndex ()
    {
      for (std::size_t i = 0; i < count_; ++i)
        if (inRange (vertices_[i]))
          map_[vertices_[i]] = -1;
      inUse () = false;
    }

    PatchLocalIndex (const PatchLocalIndex&) = delete;
    PatchLocalIndex& operator= (const PatchLocalIndex&) = delete;

    /// The index of mesh vertex \a v in the patch, -1 if it is not one of its (first count) vertices.
    int operator() (int v) const { return inRange (v) ? map_[v] : -1; }

  private:
    bool inRange (int v) const { return v >= 0 && static_cast<std::size_t> (v) < map_.size (); }

    static bool&
    inUse ()
    {
      thread_local bool in_use = false;
      return in_use;
    }

    static std::vector<int>&
    scratch ()
    {
      thread_local std::vector<int> map;
      return map;
    }

    const std::vector<int>& vertices_;
    std::size_t count_;
    std::vector<int>& map_;
  };
} // namespace pcl_sparse
