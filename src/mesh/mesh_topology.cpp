#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <algorithm>

namespace pcl_sparse
{
  namespace
  {
    /// Below this many vertices the topology is built on one thread.
    constexpr int kParallelVertices = 4096;

    /// A face's edge at a vertex: its other end, and where it is in the face.
    struct Corner
    {
      int other;
      int face;
      int slot;  ///< the edge's index in the face
    };

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
  buildMeshTopology (const TriangleMesh& mesh, int num_threads)
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

    // Edges, face neighbours and 1-rings, vertex by vertex from the faces around it; each undirected edge
    // (a, b), a < b, belongs to its smaller end a, so the edges come by a, then b. In parallel: the sizes
    // first, then each vertex's lists straight into place (the same lists for any thread count).
    const int threads = resolveThreadCount (num_threads);
    const bool parallel = num_vertices > kParallelVertices;
    std::vector<int> edge_counts (num_vertices, 0);
    std::fill (counts.begin (), counts.end (), 0);  // now the 1-rings' sizes
#pragma omp parallel num_threads(threads) if(parallel)
    {
      std::vector<int> seen (num_vertices, -1);  // seen[w] == a: w counted for a
#pragma omp for schedule(dynamic, 1024)
      for (int a = 0; a < num_vertices; ++a)
        for (int f : topo.facesOf (a))
          for (int k = 0; k < 3; ++k)
          {
            const int p = mesh.triangles[f][k], q = mesh.triangles[f][(k + 1) % 3];
            const int other = p == a ? q : p;
            if (p == q || (p != a && q != a) || seen[other] == a)
              continue;
            seen[other] = a;
            ++counts[a];
            edge_counts[a] += other > a ? 1 : 0;
          }
    }
    const std::vector<int> edge_offsets = offsetsFromCounts (edge_counts);
    topo.vertex_neighbor_offsets = offsetsFromCounts (counts);
    topo.edges.resize (edge_offsets.back ());
    topo.edge_face_count.resize (edge_offsets.back ());
    topo.vertex_neighbors.resize (topo.vertex_neighbor_offsets.back ());
    // Every slot of face_edges and face_neighbors is written below: resize leaves Eigen's vectors as they
    // are, and the threads, not one, touch their pages first.
    topo.face_edges.resize (num_faces);
    topo.face_neighbors.resize (num_faces);
#pragma omp parallel num_threads(threads) if(parallel)
    {
      std::vector<Corner> local;
#pragma omp for schedule(dynamic, 1024)
      for (int a = 0; a < num_vertices; ++a)
      {
        local.clear ();
        for (int f : topo.facesOf (a))
          for (int k = 0; k < 3; ++k)
          {
            const int p = mesh.triangles[f][k], q = mesh.triangles[f][(k + 1) % 3];
            if (p == q && p == a)
              topo.face_edges[f][k] = topo.face_neighbors[f][k] = -1;  // no edge
            else if (p != q && (p == a || q == a))
              local.push_back ({p == a ? q : p, f, k});
          }
        std::sort (local.begin (), local.end (), [] (const Corner& x, const Corner& y) {
          return x.other != y.other ? x.other < y.other : (x.face != y.face ? x.face < y.face : x.slot < y.slot);
        });
        int* ring = topo.vertex_neighbors.data () + topo.vertex_neighbor_offsets[a];
        int e = edge_offsets[a];
        for (std::size_t i = 0; i < local.size ();)
        {
          std::size_t j = i;
          while (j < local.size () && local[j].other == local[i].other)
            ++j;
          *ring++ = local[i].other;
          if (local[i].other > a)
          {
            // Each (face, slot) is written here only, at the edge's smaller end. Across manifold edges only;
            // a face using the edge twice is its own neighbour.
            topo.edges[e] = Eigen::Vector2i (a, local[i].other);
            topo.edge_face_count[e] = static_cast<int> (j - i);
            for (std::size_t c = i; c < j; ++c)
            {
              topo.face_edges[local[c].face][local[c].slot] = e;
              topo.face_neighbors[local[c].face][local[c].slot] = j - i == 2 ? local[c == i ? j - 1 : i].face : -1;
            }
            ++e;
          }
          i = j;
        }
      }
    }
    return topo;
  }
} // namespace pcl_sparse
