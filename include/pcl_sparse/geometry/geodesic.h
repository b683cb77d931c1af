#pragma once
/// \file geodesic.h
/// Geodesic distances from a seed vertex as shortest paths along mesh edges (Dijkstra), bounded by a
/// radius and by a callback that may refuse vertices: the walk behind patch growth (docs/METHOD.md step 5).
///
/// Dijkstra over edges overestimates the true geodesic distance, depending on direction: up to 8.2 % on a
/// grid with both diagonals ("union jack"), up to 15.5 % (2 / sqrt 3) on an equilateral triangulation; the
/// authors use fast marching. test_geometry_geodesic.cpp checks both bounds.
///
/// This is the only edge walk of the library: PatchGrower::grow (patch_growth.h) is a visitor of it (Stop
/// for the authors' stop-at-first-failure growth, Defer for the non-stopping variant) over the cached
/// edge lengths of computeEdgeLengths.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  /// What the visitor decides about a vertex reached by the walk.
  enum class GeodesicVisit
  {
    Accept,  ///< keep it and expand the walk through its edges
    Refuse,  ///< drop it: it is not expanded (it may not be reached again); the walk goes on elsewhere
    Stop,    ///< drop it and end the whole walk now (the authors' patch growth stops at the first failure)
    Defer    ///< drop it for now, but offer it again whenever a neighbour is accepted later: at the distance
             ///< through that neighbour if shorter, else at its former distance. For visitors whose answer
             ///< depends on which vertices are already accepted (patch growth). Offers after a re-offer are
             ///< no longer in increasing distance: a late accepted vertex relaxes its neighbours from its
             ///< own, smaller, distance.
  };

  /// Length of every 1-ring entry of a topology: |p_u - p_v| for u the i-th neighbour of v, +infinity
  /// where it is not finite (NaN coordinates). Such edges are walked only by an unbounded walk
  /// (max_distance +infinity), which offers what lies behind them last; the lengths DijkstraGeodesic
  /// computes itself follow the same rule. Parallel over vertices, deterministic.
  /// \param[in] mesh      the mesh
  /// \param[in] topology     its topology
  /// \param[in] num_threads  OpenMP threads (0: all)
  /// \return one length per entry of topology.vertex_neighbors (CSR, same layout)
  std::vector<double>
  computeEdgeLengths (const TriangleMesh& mesh, const MeshTopology& topology, int num_threads = 0);

  /// Called once per reached vertex, when its distance is final, in increasing distance (ties by vertex
  /// index); again for deferred vertices (GeodesicVisit::Defer). \a parent is the accepted vertex it
  /// was reached from (-1 for the source).
  using GeodesicVisitor = std::function<GeodesicVisit (int vertex, double distance, int parent)>;

  /// Dijkstra over the edges of a mesh with reusable state: the arrays are sized once for the mesh and
  /// only the entries a walk touched are reset by the next walk, so a walk costs O(R log R) for a region
  /// of R vertices, independent of the mesh size. Not thread-safe: use one object per thread.
  class DijkstraGeodesic
  {
  public:
    using Ptr = std::shared_ptr<DijkstraGeodesic>;
    using ConstPtr = std::shared_ptr<const DijkstraGeodesic>;

    /// Sizes the walker for a mesh.
    /// \param[in] mesh      the mesh; must outlive this object
    /// \param[in] topology  its topology; must outlive this object
    DijkstraGeodesic (const TriangleMesh& mesh, const MeshTopology& topology);

    /// Walks with precomputed edge lengths instead of computing |p_u - p_v| on every relaxation; same
    /// distances bit for bit.
    /// \param[in] lengths  computeEdgeLengths of the mesh (cached once per mesh, shared by all walkers);
    ///                     must outlive this object; an empty vector restores the computed lengths
    void setEdgeLengths (const std::vector<double>& lengths);

    /// Walks from a source vertex, offering every vertex within a distance to a visitor, in increasing
    /// distance. The source itself is offered first, at distance 0.
    /// \param[in] source        start vertex
    /// \param[in] max_distance  largest distance offered (inclusive); +infinity for the whole component
    /// \param[in] visitor       decides about each offered vertex; empty: every vertex is accepted
    /// \return the number of accepted vertices
    std::size_t
    compute (int source, double max_distance, const GeodesicVisitor& visitor = GeodesicVisitor ());

    /// compute () with any callable `GeodesicVisit (int vertex, double distance, int parent)`, inlined
    /// instead of called through std::function: for hot loops (patch growth runs one walk per seed).
    /// \param[in] source        start vertex
    /// \param[in] max_distance  largest distance offered (inclusive)
    /// \param[in] visitor       the callable
    /// \return the number of accepted vertices
    template <typename Visitor>
    std::size_t
    walk (int source, double max_distance, Visitor&& visitor);

    /// Accepted vertices of the last walk in the order they were accepted (increasing distance).
    const std::vector<int>& acceptedVertices () const { return accepted_; }

    /// Distance of vertex \a v in the last walk.
    /// \param[in] v  a vertex index
    /// \return its distance if it was accepted, refused or deferred there, +infinity otherwise
    double distance (int v) const;

    /// The vertex \a v was reached from in the last walk.
    /// \param[in] v  a vertex index
    /// \return its parent; -1 for the source or if \a v was not accepted
    int parent (int v) const { return state_[v] == State::Accepted ? parent_[v] : -1; }

    /// Whether vertex \a v was accepted in the last walk.
    bool isAccepted (int v) const { return state_[v] == State::Accepted; }

  private:
    enum class State : std::uint8_t
    {
      Untouched,
      Queued,
      Accepted,
      Refused,
      Deferred
    };

    void reset (int source);
    double edgeLength (int v, int i, int u) const;

    const TriangleMesh* mesh_;
    const MeshTopology* topology_;
    const std::vector<double>* edge_lengths_ = nullptr;
    std::vector<double> distance_;
    std::vector<int> parent_;
    std::vector<State> state_;
    std::vector<int> touched_;
    std::vector<int> accepted_;
    std::vector<std::pair<double, int>> heap_;
  };

  inline double
  DijkstraGeodesic::edgeLength (int v, int i, int u) const
  {
    if (edge_lengths_)
      return (*edge_lengths_)[i];
    const double l = (mesh_->vertices[u] - mesh_->vertices[v]).norm ();
    return std::isfinite (l) ? l : std::numeric_limits<double>::infinity ();
  }

  template <typename Visitor>
  std::size_t
  DijkstraGeodesic::walk (int source, double max_distance, Visitor&& visitor)
  {
    reset (source);
    // Min-heap on (distance, vertex): equal distances come out by index, so the order is deterministic.
    const auto later = std::greater<std::pair<double, int>> ();
    distance_[source] = 0.0;
    parent_[source] = -1;
    state_[source] = State::Queued;
    touched_.push_back (source);
    heap_.emplace_back (0.0, source);
    while (!heap_.empty ())
    {
      std::pop_heap (heap_.begin (), heap_.end (), later);
      const auto [d, v] = heap_.back ();
      heap_.pop_back ();
      if (state_[v] != State::Queued || d != distance_[v])
        continue;  // stale entry: v was settled or improved since this entry was pushed
      const GeodesicVisit decision = visitor (v, d, parent_[v]);
      if (decision == GeodesicVisit::Stop)
      {
        state_[v] = State::Refused;
        break;
      }
      if (decision == GeodesicVisit::Refuse || decision == GeodesicVisit::Defer)
      {
        state_[v] = decision == GeodesicVisit::Refuse ? State::Refused : State::Deferred;
        continue;
      }
      state_[v] = State::Accepted;
      accepted_.push_back (v);
      const int first = topology_->vertex_neighbor_offsets[v], last = topology_->vertex_neighbor_offsets[v + 1];
      for (int i = first; i < last; ++i)
      {
        const int u = topology_->vertex_neighbors[i];
        const State su = state_[u];
        if (su == State::Accepted || su == State::Refused)
          continue;
        // Only the state says whether distance_[u] and parent_[u] belong to this walk (they are not reset).
        const double du = d + edgeLength (v, i, u);
        if (du <= max_distance && (su == State::Untouched || du < distance_[u]))
        {
          if (su == State::Untouched)
            touched_.push_back (u);
          distance_[u] = du;
          parent_[u] = v;
        }
        else if (su != State::Deferred)
          continue;  // no shorter path; a deferred vertex is offered again at its former distance
        state_[u] = State::Queued;
        heap_.emplace_back (distance_[u], u);
        std::push_heap (heap_.begin (), heap_.end (), later);
      }
    }
    return accepted_.size ();
  }
} // namespace pcl_sparse
