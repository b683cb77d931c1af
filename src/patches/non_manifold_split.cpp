#include <pcl_sparse/patches/non_manifold_split.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    int
    findRoot (std::vector<int>& parent, int i)
    {
      while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
      return i;
    }
  } // namespace

  bool
  splitNonManifoldVertices (const TriangleMesh& mesh, const MeshTopology& topology, NonManifoldSplit& split)
  {
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    std::vector<int> parent, group_vertex;
    // (face, corner) -> new vertex index, only for corners that move to a copy.
    std::vector<std::pair<int, int>> moved_corners;
    std::vector<int> moved_vertex;
    std::vector<int> original;
    int next = num_vertices;
    for (int v = 0; v < num_vertices; ++v)
    {
      const IndexRange faces = topology.facesOf (v);
      const int n = static_cast<int> (faces.size ());
      if (n <= 1)
        continue;
      parent.resize (n);
      std::iota (parent.begin (), parent.end (), 0);
      auto slotOf = [&] (int face) {  // -1 for a face using v twice or of zero area
        const Eigen::Vector3i& t = mesh.triangles[face];
        const Eigen::Vector3d& a = mesh.vertices[t[0]];
        const Eigen::Vector3d cross = (mesh.vertices[t[1]] - a).cross (mesh.vertices[t[2]] - a);
        if (!(cross.squaredNorm () > 0.0) || !cross.allFinite ())
          return -1;
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
      // Groups in order of their lowest face; the first keeps v.
      group_vertex.assign (n, -1);
      int groups = 0;
      for (int i = 0; i < n; ++i)
      {
        const int r = findRoot (parent, i);
        if (group_vertex[r] < 0)
        {
          group_vertex[r] = groups == 0 ? v : next++;
          if (groups > 0)
            original.push_back (v);
          ++groups;
        }
        if (group_vertex[r] != v)
        {
          moved_corners.emplace_back (faces.first[i], v);
          moved_vertex.push_back (group_vertex[r]);
        }
      }
    }
    if (original.empty ())
      return false;

    split.mesh = mesh;
    split.original.resize (next);
    std::iota (split.original.begin (), split.original.begin () + num_vertices, 0);
    for (std::size_t i = 0; i < original.size (); ++i)
    {
      split.original[num_vertices + i] = original[i];
      split.mesh.vertices.push_back (mesh.vertices[original[i]]);
    }
    for (std::size_t i = 0; i < moved_corners.size (); ++i)
    {
      Eigen::Vector3i& t = split.mesh.triangles[moved_corners[i].first];
      for (int k = 0; k < 3; ++k)
        if (t[k] == moved_corners[i].second)
          t[k] = moved_vertex[i];
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
