#pragma once
/// \file mesh_neighborhood.h
/// Ring neighbourhoods of a mesh vertex: k rings and adaptive rings (docs/METHOD.md step 3).
///
/// The walks reuse a VertexMarks scratch (a visit stamp per vertex), so collecting a neighbourhood costs
/// O(size of the neighbourhood), never O(#V): no per-call clears, no per-call allocation once the output
/// vector has grown. One scratch per thread.

// Adaptive radii are fractions of the bounding-box diagonal: boundingBoxDiagonal comes with them.
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// "Visited" flags for all vertices of a mesh that are cleared in O(1): a vertex is marked when its
  /// stamp equals the current one, and clear () just advances the current stamp.
  class VertexMarks
  {
  public:
    VertexMarks () = default;
    /// Marks for \a num_vertices vertices, all clear.
    explicit VertexMarks (std::size_t num_vertices) { resize (num_vertices); }

    /// Sizes the scratch for a mesh with \a num_vertices vertices and clears all marks.
    void
    resize (std::size_t num_vertices)
    {
      stamps_.assign (num_vertices, 0u);
      current_ = 1u;
    }

    /// Number of vertices the marks are sized for.
    std::size_t size () const { return stamps_.size (); }

    /// Unmarks every vertex in O(1) (O(#V) once every 2^32 calls, when the stamp wraps).
    void
    clear ()
    {
      if (++current_ == 0u)
      {
        std::fill (stamps_.begin (), stamps_.end (), 0u);
        current_ = 1u;
      }
    }

    /// Whether vertex \a v is marked.
    bool isMarked (int v) const { return stamps_[v] == current_; }

    /// Marks a vertex.
    /// \param[in] v  vertex index
    /// \return true if it was not marked before
    bool
    mark (int v)
    {
      if (stamps_[v] == current_)
        return false;
      stamps_[v] = current_;
      return true;
    }

  private:
    std::vector<std::uint32_t> stamps_;
    std::uint32_t current_ = 1u;
  };

  /// The most neighbours a ring neighbourhood holds by default. A vertex of valence N (a fan-triangulated
  /// N-gon) is in the 1-ring of N vertices, whose neighbourhoods would then each hold all N: quadratic
  /// time. 16 rings of a regular mesh hold 816; Harris 3D's neighbourhoods on the shared meshes at most 271
  /// (koala-loop1-200k).
  constexpr int default_max_ring_neighbors = 1024;

  /// Collects the k-ring of a vertex: the vertex itself, then its 1-ring, then the vertices at edge
  /// distance 2, and so on, each ring in breadth-first order (deterministic: the topology's lists are
  /// sorted).
  /// \param[in]     topology  the mesh's topology
  /// \param[in]     v         the centre vertex
  /// \param[in]     rings     k, the number of rings
  /// \param[in,out] marks     scratch sized for the mesh; cleared on entry, left marking exactly \a out
  /// \param[out]    out       the neighbourhood, out[0] == v
  /// \param[in]     max_neighbors  never more neighbours than this: the ring that reaches it is cut there,
  ///                               in the topology's order (see AdaptiveRingOptions::max_neighbors)
  /// \return the number of rings actually collected (fewer than \a rings when the component of v is
  ///         exhausted earlier)
  int
  collectKRing (const MeshTopology& topology, int v, int rings, VertexMarks& marks, std::vector<int>& out,
                int max_neighbors = default_max_ring_neighbors);

  /// Options of the adaptive ring neighbourhood.
  struct AdaptiveRingOptions
  {
    /// Stop adding rings once the neighbourhood radius (largest distance from v to a collected vertex)
    /// exceeds this absolute length. Harris 3D uses 0.01 x bounding-box diagonal (Sipiran & Bustos).
    double radius = 0.0;
    /// Keep adding rings while fewer than this many neighbours (v excluded) are collected, even past
    /// \a radius: a height quadric needs 6 points. 0 disables the rule.
    int min_neighbors = 6;
    /// Never collect more than this many rings (guards against long thin needles and huge radii).
    int max_rings = 16;
    /// Never collect more than this many neighbours: the ring that reaches it is cut there, in the
    /// topology's order (default_max_ring_neighbors says why).
    int max_neighbors = default_max_ring_neighbors;
  };

  /// Collects rings around a vertex (as collectKRing) until the neighbourhood radius exceeds
  /// options.radius and at least options.min_neighbors neighbours are collected, or options.max_rings
  /// is reached, or options.max_neighbors are collected, or the component of v is exhausted. At least one
  /// ring (or its first options.max_neighbors vertices) is always collected.
  /// \param[in]     mesh      the mesh (for distances)
  /// \param[in]     topology  its topology
  /// \param[in]     v         the centre vertex
  /// \param[in]     options   radius, minimum neighbour count, ring limit
  /// \param[in,out] marks     scratch sized for the mesh; cleared on entry, left marking exactly \a out
  /// \param[out]    out       the neighbourhood, out[0] == v
  /// \return the number of rings collected
  int
  collectAdaptiveRing (const TriangleMesh& mesh, const MeshTopology& topology, int v, const AdaptiveRingOptions& options,
                       VertexMarks& marks, std::vector<int>& out);

  /// collectKRing allocating its own scratch (O(#V) per call): for tests and one-off queries.
  /// \param[in] topology  the mesh's topology
  /// \param[in] v         the centre vertex
  /// \param[in] rings     k, the number of rings
  /// \return the k-ring, v first
  std::vector<int>
  kRing (const MeshTopology& topology, int v, int rings);
} // namespace pcl_sparse
