#include <pcl_sparse/geometry/mesh_neighborhood.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_sparse
{
  namespace
  {
    /// Appends the ring after out[ring_begin, out.size ()) to \a out, stopping once \a out holds \a limit
    /// vertices; returns false if it added none.
    bool
    appendNextRing (const MeshTopology& topology, std::size_t ring_begin, VertexMarks& marks, std::vector<int>& out,
                    std::size_t limit = std::numeric_limits<std::size_t>::max ())
    {
      const std::size_t ring_end = out.size ();
      for (std::size_t i = ring_begin; i < ring_end; ++i)
        for (int u : topology.neighborsOf (out[i]))
          if (marks.mark (u))
          {
            out.push_back (u);
            if (out.size () >= limit)
              return true;
          }
      return out.size () > ring_end;
    }
  } // namespace

  int
  collectKRing (const MeshTopology& topology, int v, int rings, VertexMarks& marks, std::vector<int>& out,
                int max_neighbors)
  {
    marks.clear ();
    out.clear ();
    out.push_back (v);
    marks.mark (v);
    std::size_t ring_begin = 0;
    int collected = 0;
    const std::size_t limit = 1 + static_cast<std::size_t> (std::max (max_neighbors, 0));
    while (collected < rings && out.size () < limit)
    {
      const std::size_t next_begin = out.size ();
      if (!appendNextRing (topology, ring_begin, marks, out, limit))
        break;
      ring_begin = next_begin;
      ++collected;
    }
    return collected;
  }

  int
  collectAdaptiveRing (const TriangleMesh& mesh, const MeshTopology& topology, int v, const AdaptiveRingOptions& options,
                       VertexMarks& marks, std::vector<int>& out)
  {
    marks.clear ();
    out.clear ();
    out.push_back (v);
    marks.mark (v);
    const Eigen::Vector3d& center = mesh.vertices[v];
    const double radius_squared = options.radius * options.radius;
    double max_squared = 0.0;
    std::size_t ring_begin = 0;
    int collected = 0;
    const int max_rings = std::max (1, options.max_rings);
    const std::size_t limit = 1 + static_cast<std::size_t> (std::max (options.max_neighbors, options.min_neighbors));
    while (collected < max_rings && out.size () < limit)
    {
      const std::size_t next_begin = out.size ();
      if (!appendNextRing (topology, ring_begin, marks, out, limit))
        break;
      ring_begin = next_begin;
      ++collected;
      for (std::size_t i = next_begin; i < out.size (); ++i)
        max_squared = std::max (max_squared, (mesh.vertices[out[i]] - center).squaredNorm ());
      const bool enough_points = static_cast<int> (out.size ()) - 1 >= options.min_neighbors;
      if (max_squared > radius_squared && enough_points)
        break;
    }
    return collected;
  }

  std::vector<int>
  kRing (const MeshTopology& topology, int v, int rings)
  {
    VertexMarks marks (topology.numVertices ());
    std::vector<int> out;
    collectKRing (topology, v, rings, marks, out);
    return out;
  }
} // namespace pcl_sparse
