#include <pcl_sparse/geometry/mesh_neighborhood.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// Appends the ring after out[ring_begin, out.size ()) to \a out; returns false if it is empty.
    bool
    appendNextRing (const MeshTopology& topology, std::size_t ring_begin, VertexMarks& marks, std::vector<int>& out)
    {
      const std::size_t ring_end = out.size ();
      for (std::size_t i = ring_begin; i < ring_end; ++i)
        for (int u : topology.neighborsOf (out[i]))
          if (marks.mark (u))
            out.push_back (u);
      return out.size () > ring_end;
    }
  } // namespace

  int
  collectKRing (const MeshTopology& topology, int v, int rings, VertexMarks& marks, std::vector<int>& out)
  {
    marks.clear ();
    out.clear ();
    out.push_back (v);
    marks.mark (v);
    std::size_t ring_begin = 0;
    int collected = 0;
    while (collected < rings)
    {
      const std::size_t next_begin = out.size ();
      if (!appendNextRing (topology, ring_begin, marks, out))
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
    while (collected < max_rings)
    {
      const std::size_t next_begin = out.size ();
      if (!appendNextRing (topology, ring_begin, marks, out))
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
