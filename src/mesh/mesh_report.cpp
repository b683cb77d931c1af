#include <pcl_sparse/mesh/mesh_report.h>

#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/mesh/mesh_components.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    /// Number of fans the faces around \a v form when glued across the manifold edges at \a v.
    int
    countFans (const TriangleMesh& mesh, const MeshTopology& topo, int v, std::vector<int>& local_parent)
    {
      const IndexRange faces = topo.facesOf (v);
      const int n = static_cast<int> (faces.size ());
      local_parent.resize (n);
      std::iota (local_parent.begin (), local_parent.end (), 0);
      auto find = [&local_parent] (int x) {
        while (local_parent[x] != x)
          x = local_parent[x] = local_parent[local_parent[x]];
        return x;
      };
      int fans = n;
      for (int i = 0; i < n; ++i)
      {
        const int f = faces.begin ()[i];
        const auto& t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k)
        {
          const int e = topo.face_edges[f][k];
          const int g = topo.face_neighbors[f][k];
          if (e < 0 || g < 0 || (t[k] != v && t[(k + 1) % 3] != v))
            continue;
          const int j = static_cast<int> (std::lower_bound (faces.begin (), faces.end (), g) - faces.begin ());
          if (j >= n || faces.begin ()[j] != g)
            continue;
          const int a = find (i), b = find (j);
          if (a != b)
          {
            local_parent[std::max (a, b)] = std::min (a, b);
            --fans;
          }
        }
      }
      return fans;
    }

    /// Tries to give every face an orientation sign so that neighbours traverse their shared edge in
    /// opposite directions; false if some component cannot be oriented (Moebius band, Klein bottle).
    /// Requires a manifold mesh (no repeated indices, every walked edge shared by exactly two faces).
    bool
    isOrientable (const TriangleMesh& mesh, const MeshTopology& topo)
    {
      const int num_faces = static_cast<int> (mesh.triangles.size ());
      std::vector<signed char> sign (num_faces, 0);
      std::vector<int> stack;
      for (int seed = 0; seed < num_faces; ++seed)
      {
        if (sign[seed] != 0)
          continue;
        sign[seed] = 1;
        stack.push_back (seed);
        while (!stack.empty ())
        {
          const int f = stack.back ();
          stack.pop_back ();
          const auto& t = mesh.triangles[f];
          for (int k = 0; k < 3; ++k)
          {
            const int g = topo.face_neighbors[f][k];
            if (g < 0)
              continue;
            const int e = topo.face_edges[f][k];
            const auto& u = mesh.triangles[g];
            int j = 0;
            while (j < 3 && topo.face_edges[g][j] != e)
              ++j;
            if (j == 3)
              return false;
            // g agrees with f when it walks the shared edge the other way round.
            const bool agrees = u[j] == t[(k + 1) % 3];
            const signed char wanted = agrees ? sign[f] : static_cast<signed char> (-sign[f]);
            if (sign[g] == 0)
            {
              sign[g] = wanted;
              stack.push_back (g);
            }
            else if (sign[g] != wanted)
              return false;
          }
        }
      }
      return true;
    }
  } // namespace

  bool
  isDegenerateFace (const TriangleMesh& mesh, int f)
  {
    const auto& t = mesh.triangles[f];
    if (hasRepeatedIndex (t))
      return true;
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    if (!a.allFinite () || !b.allFinite () || !c.allFinite ())
      return false;
    const double longest2 = std::max ({(b - a).squaredNorm (), (c - b).squaredNorm (), (a - c).squaredNorm ()});
    return (b - a).cross (c - a).norm () <= 1e-12 * longest2;
  }

  std::size_t
  countNonManifoldEdges (const TriangleMesh& mesh, const std::vector<int>& first_copy)
  {
    // The face sides bucketed by their smaller end (a counting sort, linear), then each vertex's few larger
    // ends sorted: a sort of all 3 #F sides took 0.14 s on a 400k-face mesh, this a fraction of it.
    const std::size_t num_vertices = mesh.vertices.size ();
    std::vector<int> offsets (num_vertices + 1, 0);
    const auto forEachSide = [&] (auto&& visit) {
      for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
        if (const Eigen::Vector3i& t = mesh.triangles[f];
            !hasRepeatedIndex (t) && (first_copy.empty () || first_copy[f] == static_cast<int> (f)))
          for (int k = 0; k < 3; ++k)
            visit (std::min (t[k], t[(k + 1) % 3]), std::max (t[k], t[(k + 1) % 3]));
    };
    forEachSide ([&] (int low, int) { ++offsets[low + 1]; });
    std::partial_sum (offsets.begin (), offsets.end (), offsets.begin ());
    std::vector<int> high (offsets.back ());
    std::vector<int> fill (offsets.begin (), offsets.end () - 1);
    forEachSide ([&] (int low, int other) { high[fill[low]++] = other; });
    std::size_t nonmanifold = 0;
    for (std::size_t v = 0; v < num_vertices; ++v)
    {
      const auto first = high.begin () + offsets[v], last = high.begin () + offsets[v + 1];
      std::sort (first, last);
      for (auto i = first, j = first; i != last; i = j)
      {
        while (j != last && *j == *i)
          ++j;
        nonmanifold += j - i > 2;
      }
    }
    return nonmanifold;
  }

  std::vector<int>
  findDuplicateFaces (const TriangleMesh& mesh)
  {
    const int num_faces = static_cast<int> (mesh.triangles.size ());
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    std::vector<std::array<int, 3>> sorted (num_faces);
    for (int f = 0; f < num_faces; ++f)
    {
      const auto& t = mesh.triangles[f];
      sorted[f] = {t[0], t[1], t[2]};
      std::sort (sorted[f].begin (), sorted[f].end ());
    }
    // Bucket the faces by their smallest vertex (counting sort), then sort each small bucket.
    std::vector<int> offsets (num_vertices + 1, 0);
    for (const auto& s : sorted)
      ++offsets[s[0] + 1];
    std::partial_sum (offsets.begin (), offsets.end (), offsets.begin ());
    std::vector<int> order (num_faces);
    {
      std::vector<int> cursor (offsets.begin (), offsets.end () - 1);
      for (int f = 0; f < num_faces; ++f)
        order[cursor[sorted[f][0]]++] = f;
    }
    std::vector<int> first (num_faces);
    for (int v = 0; v < num_vertices; ++v)
    {
      const auto begin = order.begin () + offsets[v], end = order.begin () + offsets[v + 1];
      // All faces of the bucket share sorted[.][0]; compare the other two corners, then the face index.
      std::sort (begin, end, [&sorted] (int x, int y) {
        const auto &a = sorted[x], &b = sorted[y];
        return a[1] != b[1] ? a[1] < b[1] : (a[2] != b[2] ? a[2] < b[2] : x < y);
      });
      for (auto it = begin; it != end; ++it)
      {
        const bool same = it != begin && sorted[*(it - 1)][1] == sorted[*it][1] && sorted[*(it - 1)][2] == sorted[*it][2];
        first[*it] = same ? first[*(it - 1)] : *it;
      }
    }
    return first;
  }

  namespace
  {
    /// Vertices: unreferenced and non-finite ones, bounding box. Returns the number of referenced vertices.
    std::size_t
    countVertices (const TriangleMesh& mesh, const MeshTopology& topo, MeshReport& report)
    {
      std::size_t referenced = 0;
      for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
      {
        if (topo.facesOf (static_cast<int> (v)).size () == 0)
          ++report.unreferenced_vertices;
        else
          ++referenced;
        if (!mesh.vertices[v].allFinite ())
          ++report.non_finite_vertices;
      }
      report.bbox_diagonal = boundingBoxDiagonal (mesh.vertices);  // the file's every vertex
      return referenced;
    }

    /// Faces: degenerate and duplicate. Returns the number of faces with a repeated vertex index.
    std::size_t
    countFaceDefects (const TriangleMesh& mesh, MeshReport& report)
    {
      const int num_faces = static_cast<int> (mesh.triangles.size ());
      std::size_t repeated_index = 0, degenerate_faces = 0;
      for (int f = 0; f < num_faces; ++f)
      {
        repeated_index += hasRepeatedIndex (mesh.triangles[f]);
        degenerate_faces += isDegenerateFace (mesh, f);
      }
      report.degenerate_faces = degenerate_faces;
      const std::vector<int> first_copy = findDuplicateFaces (mesh);
      for (int f = 0; f < num_faces; ++f)
        if (first_copy[f] != f)
          ++report.duplicate_faces;
      return repeated_index;
    }

    /// Edges: boundary, non-manifold, mean length over the finite ones.
    void
    measureEdges (const TriangleMesh& mesh, const MeshTopology& topo, MeshReport& report)
    {
      double length_sum = 0.0;
      std::size_t length_count = 0;
      for (std::size_t e = 0; e < topo.numEdges (); ++e)
      {
        const int count = topo.edge_face_count[e];
        report.boundary_edges += count == 1;
        report.nonmanifold_edges += count > 2;
        const double length = (mesh.vertices[topo.edges[e][0]] - mesh.vertices[topo.edges[e][1]]).norm ();
        if (std::isfinite (length))
        {
          length_sum += length;
          ++length_count;
        }
      }
      if (length_count > 0)
        report.mean_edge_length = length_sum / static_cast<double> (length_count);
    }

    /// Face components (through shared vertices, indexed by their root vertex) with their Euler
    /// characteristic chi_c = V_c - E_c + F_c and boundary loop count b_c.
    struct Components
    {
      std::vector<char> is_root;
      std::vector<long> chi;
      std::vector<long> loops;
    };

    /// Components over faces and boundary loops (through boundary edges); counts both into \a report.
    Components
    findComponents (const TriangleMesh& mesh, const MeshTopology& topo, MeshReport& report)
    {
      const int num_vertices = static_cast<int> (mesh.vertices.size ());
      DisjointSets components (num_vertices);
      for (const auto& t : mesh.triangles)
      {
        components.join (t[0], t[1]);
        components.join (t[1], t[2]);
      }
      DisjointSets loops (num_vertices);
      for (std::size_t e = 0; e < topo.numEdges (); ++e)
        if (topo.isBoundaryEdge (static_cast<int> (e)))
          loops.join (topo.edges[e][0], topo.edges[e][1]);

      Components c{std::vector<char> (num_vertices, 0), std::vector<long> (num_vertices, 0),
                   std::vector<long> (num_vertices, 0)};
      std::vector<char> loop_seen (num_vertices, 0);
      for (int v = 0; v < num_vertices; ++v)
        if (topo.facesOf (v).size () > 0)
        {
          const int root = components.find (v);
          ++c.chi[root];
          if (!c.is_root[root])
          {
            c.is_root[root] = 1;
            ++report.components;
          }
        }
      for (std::size_t e = 0; e < topo.numEdges (); ++e)
      {
        const int a = topo.edges[e][0];
        --c.chi[components.find (a)];
        if (topo.isBoundaryEdge (static_cast<int> (e)))
        {
          const int loop = loops.find (a);
          if (!loop_seen[loop])
          {
            loop_seen[loop] = 1;
            ++report.boundary_loops;
            ++c.loops[components.find (a)];
          }
        }
      }
      for (const auto& t : mesh.triangles)
        ++c.chi[components.find (t[0])];
      return c;
    }

    /// Sum over components of (2 - chi_c - b_c) / 2.
    int
    genusOf (const Components& c)
    {
      long twice_genus = 0;
      for (std::size_t root = 0; root < c.is_root.size (); ++root)
        if (c.is_root[root])
          twice_genus += 2 - c.chi[root] - c.loops[root];
      return static_cast<int> (twice_genus / 2);
    }
  } // namespace

  MeshReport
  computeMeshReport (const TriangleMesh& mesh, const MeshTopology& topo)
  {
    MeshReport report;
    report.vertices = mesh.vertices.size ();
    report.faces = mesh.triangles.size ();
    report.edges = topo.numEdges ();
    const std::size_t referenced = countVertices (mesh, topo, report);
    const std::size_t repeated_index = countFaceDefects (mesh, report);
    measureEdges (mesh, topo, report);

    // Vertices whose faces do not form a single fan. Serial on purpose: the whole report takes about
    // 0.1 s on 200k vertices, and OpenMP only slowed it down on a busy machine.
    std::vector<int> local_parent;
    for (int v = 0; v < static_cast<int> (mesh.vertices.size ()); ++v)
      if (countFans (mesh, topo, v, local_parent) > 1)
        ++report.nonmanifold_vertices;

    const Components components = findComponents (mesh, topo, report);
    report.euler_characteristic =
        static_cast<long> (referenced) - static_cast<long> (report.edges) + static_cast<long> (report.faces);
    report.manifold = report.faces > 0 && report.nonmanifold_edges == 0 && report.nonmanifold_vertices == 0 &&
                      repeated_index == 0;
    report.orientable = report.manifold && isOrientable (mesh, topo);
    report.closed = report.manifold && report.boundary_edges == 0;
    if (report.orientable)
      report.genus = genusOf (components);
    return report;
  }
} // namespace pcl_sparse
