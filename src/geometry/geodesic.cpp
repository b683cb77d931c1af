#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/geodesic.h>

#include <algorithm>
#include <limits>
#include <string>

namespace pcl_sparse
{
  DijkstraGeodesic::DijkstraGeodesic (const TriangleMesh& mesh, const MeshTopology& topology)
    : mesh_ (&mesh), topology_ (&topology)
  {
    if (topology.numVertices () != mesh.numVertices ())
      throw Error ("DijkstraGeodesic: the topology does not belong to the mesh (vertex counts differ)");
    const std::size_t n = mesh.numVertices ();
    distance_.assign (n, std::numeric_limits<double>::infinity ());
    parent_.assign (n, -1);
    state_.assign (n, State::Untouched);
  }

  void
  DijkstraGeodesic::reset ()
  {
    for (int v : touched_)
    {
      distance_[v] = std::numeric_limits<double>::infinity ();
      parent_[v] = -1;
      state_[v] = State::Untouched;
    }
    touched_.clear ();
    accepted_.clear ();
    heap_.clear ();
  }

  double
  DijkstraGeodesic::distance (int v) const
  {
    return state_[v] == State::Accepted || state_[v] == State::Refused ? distance_[v]
                                                                         : std::numeric_limits<double>::infinity ();
  }

  std::size_t
  DijkstraGeodesic::compute (int source, double max_distance, const GeodesicVisitor& visitor)
  {
    reset ();
    if (source < 0 || source >= static_cast<int> (distance_.size ()))
      throw Error ("DijkstraGeodesic: source vertex " + std::to_string (source) + " out of range");
    // Min-heap on (distance, vertex): equal distances come out by index, so the order is deterministic.
    const auto later = std::greater<std::pair<double, int>> ();
    distance_[source] = 0.0;
    state_[source] = State::Queued;
    touched_.push_back (source);
    heap_.emplace_back (0.0, source);
    const auto& vertices = mesh_->vertices;
    while (!heap_.empty ())
    {
      std::pop_heap (heap_.begin (), heap_.end (), later);
      const auto [d, v] = heap_.back ();
      heap_.pop_back ();
      if (state_[v] != State::Queued || d != distance_[v])
        continue;  // stale entry: v was settled or improved since this entry was pushed
      const GeodesicVisit decision = visitor ? visitor (v, d, parent_[v]) : GeodesicVisit::Accept;
      if (decision == GeodesicVisit::Stop)
      {
        state_[v] = State::Refused;
        break;
      }
      if (decision == GeodesicVisit::Refuse)
      {
        state_[v] = State::Refused;
        continue;
      }
      state_[v] = State::Accepted;
      accepted_.push_back (v);
      for (int u : topology_->neighborsOf (v))
      {
        if (state_[u] == State::Accepted || state_[u] == State::Refused)
          continue;
        const double du = d + (vertices[u] - vertices[v]).norm ();
        if (!(du <= max_distance) || du >= distance_[u])
          continue;
        if (state_[u] == State::Untouched)
          touched_.push_back (u);
        distance_[u] = du;
        parent_[u] = v;
        state_[u] = State::Queued;
        heap_.emplace_back (du, u);
        std::push_heap (heap_.begin (), heap_.end (), later);
      }
    }
    // Vertices still queued were never offered: report them as unreached.
    for (int v : touched_)
      if (state_[v] == State::Queued)
        parent_[v] = -1;
    return accepted_.size ();
  }
} // namespace pcl_sparse
