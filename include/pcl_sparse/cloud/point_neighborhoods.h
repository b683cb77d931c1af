#pragma once
/// \file point_neighborhoods.h
/// The accepted neighbours of every point of a scan (after the gap and shadow rules), stored compressed,
/// with each point's local spacing. Built from the kNN graph (knn_neighborhoods.h) or an image grid
/// (grid_neighborhoods.h); the normals, the noise, the outliers and the orientation read only this.

#include <pcl_sparse/mesh/mesh_topology.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  /// Neighbour lists in CSR form: the neighbours of point i are neighbors[offsets[i] .. offsets[i + 1]),
  /// never i itself. The relation need not be symmetric (kNN is not).
  ///   offsets   #P + 1
  ///   spacing   #P local spacing of each point (about the square root of the area per point); 0 where
  ///             the point has no neighbour
  struct PointNeighborhoods
  {
    std::vector<std::size_t> offsets{0};  ///< 64-bit: a few million points of k = 64 lists pass 2^31 entries
    std::vector<int> neighbors;
    std::vector<double> spacing;

    std::size_t size () const { return offsets.size () - 1; }

    IndexRange
    of (std::size_t i) const
    {
      return {neighbors.data () + offsets[i], neighbors.data () + offsets[i + 1]};
    }
  };

  /// \brief Fills \a neighborhoods' offsets and neighbours from fixed-size slots: point i's neighbours are
  /// the first counts[i] of slots[i * stride ...], in order (the spacing is left as it is). Only those are
  /// read, so the slots past them may be left uninitialised (uninitialisedNeighborSlots).
  /// \param[in] slots #points x stride neighbour indices
  /// \param[in] stride slots per point
  /// \param[in] counts #points: how many slots of each point are used
  /// \param[in,out] neighborhoods the lists
  /// \param[in] num_threads OpenMP threads for the copy (0 = default); the lists do not depend on it
  void
  packNeighborSlots (const int* slots, std::size_t stride, const std::vector<int>& counts,
                     PointNeighborhoods& neighborhoods, int num_threads);

  /// #points x stride neighbour slots, uninitialised: a scan of a few hundred thousand points with a 7 x 7
  /// window takes tens of megabytes of them, and filling them first cost a serial pass over every page.
  inline std::unique_ptr<int[]>
  uninitialisedNeighborSlots (std::size_t points, std::size_t stride)
  {
    return std::unique_ptr<int[]> (new int[points * stride]);
  }

  /// The reverse lists of \a neighborhoods over the points \a sources: point j's list holds the sources
  /// whose lists hold j, in the order of \a sources (spacing left empty).
  PointNeighborhoods
  reverseNeighborhoods (const PointNeighborhoods& neighborhoods, const std::vector<int>& sources);

  /// The neighbour lists made symmetric: j lists i whenever i lists j, each list ascending (a kNN graph is
  /// not symmetric, and the local triangulation and the spanning tree need both ends to see an edge).
  /// Spacing is copied.
  PointNeighborhoods
  symmetricNeighborhoods (const PointNeighborhoods& neighborhoods, int num_threads);
} // namespace pcl_sparse
