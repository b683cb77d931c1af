#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/patches/non_manifold_split.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    /// Vertices per block of the parallel pass (the split does not depend on it).
    constexpr int kBlockVertices = 4096;

    /// A corner of a face at \a vertex that moves to the block's copy number \a copy.
    struct MovedCorner
    {
      int face;
      int vertex;
      int copy;
    };

    /// The copies a block of consecutive vertices makes, in vertex order, and the corners moving to them.
    struct SplitBlock
    {
      std::vector<int> original;  ///< the vertex of each copy
      std::vector<MovedCorner> moved;
    };

    int
    findRoot (std::vector<int>& parent, int i)
    {
      while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
      return i;
    }
  } // namespace

  bool
  splitNonManifoldVertices (const TriangleMesh& mesh, const MeshTopology& topology, NonManifoldSplit& split,
                            int num_threads)
  {
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    const int num_faces = static_cast<int> (mesh.triangles.size ());
    const int threads = resolveThreadCount (num_threads);
    // Faces of zero or non-finite area, once for all three corners.
    std::vector<std::uint8_t> degenerate (num_faces);
#pragma omp parallel for num_threads(threads) schedule(static) if(num_faces > kBlockVertices)
    for (int f = 0; f < num_faces; ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const Eigen::Vector3d& a = mesh.vertices[t[0]];
      const Eigen::Vector3d cross = (mesh.vertices[t[1]] - a).cross (mesh.vertices[t[2]] - a);
      degenerate[f] = !(cross.squaredNorm () > 0.0) || !cross.allFinite ();
    }

    // Umbrellas vertex by vertex, in blocks of vertices in parallel; a block numbers its copies from 0, and
    // the blocks are joined in vertex order (the same copies for any thread count).
    const int num_blocks = (num_vertices + kBlockVertices - 1) / kBlockVertices;
    std::vector<SplitBlock> blocks (num_blocks);
#pragma omp parallel num_threads(threads) if(num_blocks > 1)
    {
      std::vector<int> parent, group_vertex;
#pragma omp for schedule(dynamic, 1)
      for (int b = 0; b < num_blocks; ++b)
      {
        SplitBlock& block = blocks[b];
        const int last = std::min (num_vertices, (b + 1) * kBlockVertices);
        for (int v = b * kBlockVertices; v < last; ++v)
        {
          const IndexRange faces = topology.facesOf (v);
          const int n = static_cast<int> (faces.size ());
          if (n <= 1)
            continue;
          parent.resize (n);
          std::iota (parent.begin (), parent.end (), 0);
          auto slotOf = [&] (int face) {  // -1 for a face using v twice or of zero area
            if (degenerate[face])
              return -1;
            const Eigen::Vector3i& t = mesh.triangles[face];
            int count = 0, slot = -1;
            for (int k = 0; k < 3; ++k)
              if (t[k] == v)
              {
                ++count;
                slot = k;
              }
            return count == 1 ? slot : -1;
          };
          for (int i = 0; i < n; ++i)
          {
            const int f = faces.first[i];
            const int k = slotOf (f);
            if (k < 0)
            {
              parent[findRoot (parent, i)] = findRoot (parent, 0);  // degenerate: first umbrella
              continue;
            }
            // The two edges of f at v: slot k joins corners k, k + 1; slot k + 2 joins corners k + 2, k.
            for (int e : {k, (k + 2) % 3})
            {
              const int g = topology.face_neighbors[f][e];
              if (g < 0)
                continue;
              const int j = static_cast<int> (std::lower_bound (faces.first, faces.last, g) - faces.first);
              if (j < n && faces.first[j] == g)
                parent[findRoot (parent, i)] = findRoot (parent, j);
            }
          }
          // Groups in order of their lowest face; the first keeps v, the others become the block's copies.
          group_vertex.assign (n, -1);
          int groups = 0;
          for (int i = 0; i < n; ++i)
          {
            const int r = findRoot (parent, i);
            if (group_vertex[r] < 0)
            {
              group_vertex[r] = groups == 0 ? v : num_vertices + static_cast<int> (block.original.size ());
              if (groups > 0)
                block.original.push_back (v);
              ++groups;
            }
            if (group_vertex[r] != v)
              block.moved.push_back ({faces.first[i], v, group_vertex[r] - num_vertices});
          }
        }
      }
    }

    std::size_t copies = 0;
    for (const SplitBlock& block : blocks)
      copies += block.original.size ();
    if (copies == 0)
      return false;
    split.mesh = mesh;
    split.original.resize (num_vertices + copies);
    std::iota (split.original.begin (), split.original.begin () + num_vertices, 0);
    int next = num_vertices;  // the block's first copy
    for (const SplitBlock& block : blocks)
    {
      for (const MovedCorner& corner : block.moved)
      {
        Eigen::Vector3i& t = split.mesh.triangles[corner.face];
        for (int k = 0; k < 3; ++k)
          if (t[k] == corner.vertex)
            t[k] = next + corner.copy;
      }
      for (const int v : block.original)
      {
        split.original[next++] = v;
        split.mesh.vertices.push_back (mesh.vertices[v]);
      }
    }
    return true;
  }

  std::vector<Eigen::Vector3d>
  valuesOnSplit (const NonManifoldSplit& split, const std::vector<Eigen::Vector3d>& values)
  {
    if (values.empty ())
      return values;
    std::vector<Eigen::Vector3d> on_split (split.original.size ());
    for (std::size_t v = 0; v < on_split.size (); ++v)
      on_split[v] = values[split.original[v]];
    return on_split;
  }
} // namespace pcl_sparse
