#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/geometry/geodesic.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace pcl_sparse
{
  std::vector<double>
  computeEdgeLengths (const TriangleMesh& mesh, const MeshTopology& topology, int num_threads)
  {
    if (topology.numVertices () != mesh.numVertices ())
      throw Error ("computeEdgeLengths: the topology does not belong to the mesh (vertex counts differ)");
    const int num_vertices = static_cast<int> (mesh.numVertices ());
    std::vector<double> lengths (topology.vertex_neighbors.size ());
    // The caller's thread count, not all: extra threads would spin-wait through the single-threaded rest.
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int v = 0; v < num_vertices; ++v)
      for (int i = topology.vertex_neighbor_offsets[v]; i < topology.vertex_neighbor_offsets[v + 1]; ++i)
      {
        const double l = (mesh.vertices[topology.vertex_neighbors[i]] - mesh.vertices[v]).norm ();
        lengths[i] = std::isfinite (l) ? l : std::numeric_limits<double>::infinity ();
      }
    return lengths;
  }

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
  DijkstraGeodesic::setEdgeLengths (const std::vector<double>& lengths)
  {
    if (lengths.empty ())
    {
      edge_lengths_ = nullptr;
      return;
    }
    if (lengths.size () != topology_->vertex_neighbors.size ())
      throw Error ("DijkstraGeodesic: " + std::to_string (lengths.size ()) + " edge lengths for " +
                   std::to_string (topology_->vertex_neighbors.size ()) + " 1-ring entries");
    edge_lengths_ = &lengths;
  }

  void
  DijkstraGeodesic::reset (int source)
  {
    // distance_ and parent_ are meaningful only where state_ says so: resetting the states is enough.
    for (int v : touched_)
      state_[v] = State::Untouched;
    touched_.clear ();
    accepted_.clear ();
    heap_.clear ();
    if (source < 0 || source >= static_cast<int> (state_.size ()))
      throw Error ("DijkstraGeodesic: source vertex " + std::to_string (source) + " out of range");
  }

  double
  DijkstraGeodesic::distance (int v) const
  {
    return state_[v] == State::Accepted || state_[v] == State::Refused || state_[v] == State::Deferred
             ? distance_[v]
             : std::numeric_limits<double>::infinity ();
  }

  std::size_t
  DijkstraGeodesic::compute (int source, double max_distance, const GeodesicVisitor& visitor)
  {
    if (!visitor)
      return walk (source, max_distance, [] (int, double, int) { return GeodesicVisit::Accept; });
    return walk (source, max_distance, visitor);
  }
} // namespace pcl_sparse
