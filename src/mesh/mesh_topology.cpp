#include <pcl_sparse/mesh/mesh_topology.h>

#include <algorithm>

namespace pcl_sparse
{
  namespace
  {
    /// Turns per-item counts into CSR offsets (exclusive prefix sum, one extra entry at the end).
    std::vector<int>
    offsetsFromCounts (const std::vector<int>& counts)
    {
      std::vector<int> offsets (counts.size () + 1, 0);
      for (std::size_t i = 0; i < counts.size (); ++i)
        offsets[i + 1] = offsets[i] + counts[i];
      return offsets;
    }
  } // namespace

  MeshTopology
  buildMeshTopology (const TriangleMesh& mesh)
  {
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    const int num_faces = static_cast<int> (mesh.triangles.size ());
    MeshTopology topo;

    // vertex -> faces; each face counted once per distinct vertex, faces ascending by construction.
    std::vector<int> counts (num_vertices, 0);
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k)
        if (k == 0 || (t[k] != t[0] && (k == 1 || t[2] != t[1])))
          ++counts[t[k]];
    topo.vertex_face_offsets = offsetsFromCounts (counts);
    topo.vertex_faces.resize (topo.vertex_face_offsets.back ());
    {
      std::vector<int> cursor (topo.vertex_face_offsets.begin (), topo.vertex_face_offsets.end () - 1);
      for (int f = 0; f < num_faces; ++f)
      {
        const auto& t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k)
          if (k == 0 || (t[k] != t[0] && (k == 1 || t[2] != t[1])))
            topo.vertex_faces[cursor[t[k]]++] = f;
      }
    }

    // Edges: each undirected edge (a, b), a < b, is collected at its smaller end a by scanning the faces
    // around a. Linear in the mesh size, and the edge order (by a, then b) is unique.
    topo.face_edges.assign (num_faces, Eigen::Vector3i::Constant (-1));
    struct Corner
    {
      int other;
      int face;
      int slot;
    };
    std::vector<Corner> local;
    for (int a = 0; a < num_vertices; ++a)
    {
      local.clear ();
      for (int f : topo.facesOf (a))
      {
        const auto& t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k)
        {
          const int p = t[k], q = t[(k + 1) % 3];
          if (p != q && std::min (p, q) == a)
            local.push_back ({std::max (p, q), f, k});
        }
      }
      std::sort (local.begin (), local.end (), [] (const Corner& x, const Corner& y) {
        return x.other != y.other ? x.other < y.other : (x.face != y.face ? x.face < y.face : x.slot < y.slot);
      });
      for (std::size_t i = 0; i < local.size ();)
      {
        std::size_t j = i;
        while (j < local.size () && local[j].other == local[i].other)
          ++j;
        const int e = static_cast<int> (topo.edges.size ());
        topo.edges.emplace_back (a, local[i].other);
        topo.edge_face_count.push_back (static_cast<int> (j - i));
        for (std::size_t c = i; c < j; ++c)
          topo.face_edges[local[c].face][local[c].slot] = e;
        i = j;
      }
    }

    // face -> face across manifold edges only.
    std::vector<Eigen::Vector2i> edge_faces (topo.edges.size (), Eigen::Vector2i (-1, -1));
    for (int f = 0; f < num_faces; ++f)
      for (int k = 0; k < 3; ++k)
      {
        const int e = topo.face_edges[f][k];
        if (e < 0 || topo.edge_face_count[e] != 2)
          continue;
        (edge_faces[e][0] < 0 ? edge_faces[e][0] : edge_faces[e][1]) = f;
      }
    topo.face_neighbors.assign (num_faces, Eigen::Vector3i::Constant (-1));
    for (int f = 0; f < num_faces; ++f)
      for (int k = 0; k < 3; ++k)
      {
        const int e = topo.face_edges[f][k];
        if (e >= 0 && topo.edge_face_count[e] == 2)
          topo.face_neighbors[f][k] = edge_faces[e][0] == f ? edge_faces[e][1] : edge_faces[e][0];
      }

    // vertex -> vertices from the edge list; edges are sorted by (a, b) so each list comes out ascending
    // after placing the b > v entries (from v's own edges) behind the a < v entries.
    std::fill (counts.begin (), counts.end (), 0);
    for (const auto& e : topo.edges)
    {
      ++counts[e[0]];
      ++counts[e[1]];
    }
    topo.vertex_neighbor_offsets = offsetsFromCounts (counts);
    topo.vertex_neighbors.resize (topo.vertex_neighbor_offsets.back ());
    {
      std::vector<int> cursor (topo.vertex_neighbor_offsets.begin (), topo.vertex_neighbor_offsets.end () - 1);
      // Smaller neighbours first: edges (a, v) with a < v come in increasing a.
      for (const auto& e : topo.edges)
        topo.vertex_neighbors[cursor[e[1]]++] = e[0];
      for (const auto& e : topo.edges)
        topo.vertex_neighbors[cursor[e[0]]++] = e[1];
    }
    return topo;
  }
} // namespace pcl_sparse
