#pragma once
/// \file geodesic.h
/// Geodesic distances from a seed vertex as shortest paths along mesh edges (Dijkstra), bounded by a
/// radius and by a callback that may refuse vertices: the walk behind patch growth (METHOD.md step 5).
///
/// Dijkstra over edges overestimates the true geodesic distance, depending on direction: up to 8.2 % on a
/// grid with both diagonals ("union jack"), up to 15.5 % (2 / sqrt 3) on an equilateral triangulation; the
/// authors use fast marching. test_geometry_geodesic.cpp checks both bounds.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <cstdint>
#include <functional>
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
    Stop     ///< drop it and end the whole walk now (the authors' patch growth stops at the first failure)
  };

  /// Called once per reached vertex, when its distance is final, in increasing distance (ties by vertex
  /// index). \a parent is the accepted vertex it was reached from (-1 for the source).
  using GeodesicVisitor = std::function<GeodesicVisit (int vertex, double distance, int parent)>;

  /// Dijkstra over the edges of a mesh with reusable state: the arrays are sized once for the mesh and
  /// only the entries a walk touched are reset by the next walk, so a walk costs O(R log R) for a region
  /// of R vertices, independent of the mesh size. Not thread-safe: use one object per thread.
  class DijkstraGeodesic
  {
  public:
    using Ptr = std::shared_ptr<DijkstraGeodesic>;
    using ConstPtr = std::shared_ptr<const DijkstraGeodesic>;

    /// \a mesh and \a topology must outlive this object.
    DijkstraGeodesic (const TriangleMesh& mesh, const MeshTopology& topology);

    /// Walks from \a source, offering every vertex within \a max_distance (inclusive) to \a visitor (all
    /// are accepted when it is empty). The source itself is offered first, at distance 0.
    ///   returns  the number of accepted vertices
    std::size_t
    compute (int source, double max_distance, const GeodesicVisitor& visitor = GeodesicVisitor ());

    /// Accepted vertices of the last walk in the order they were accepted (increasing distance).
    const std::vector<int>& acceptedVertices () const { return accepted_; }

    /// Distance of \a v in the last walk if it was accepted or refused there, +infinity otherwise.
    double distance (int v) const;

    /// Vertex \a v was reached from in the last walk (-1 for the source or if \a v was not accepted).
    int parent (int v) const { return state_[v] == State::Accepted ? parent_[v] : -1; }

    bool isAccepted (int v) const { return state_[v] == State::Accepted; }

  private:
    enum class State : std::uint8_t
    {
      Untouched,
      Queued,
      Accepted,
      Refused
    };

    void reset ();

    const TriangleMesh* mesh_;
    const MeshTopology* topology_;
    std::vector<double> distance_;
    std::vector<int> parent_;
    std::vector<State> state_;
    std::vector<int> touched_;
    std::vector<int> accepted_;
    std::vector<std::pair<double, int>> heap_;
  };
} // namespace pcl_sparse
