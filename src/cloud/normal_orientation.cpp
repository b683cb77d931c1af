#include <pcl_sparse/cloud/normal_orientation.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <utility>

namespace pcl_sparse
{
  namespace
  {
    /// Below this |cos| between a normal and the line of sight, the sign toward the viewpoint is decided by
    /// the normal's estimation error (80 degrees and more from the line of sight).
    const double kGrazingCosine = 0.17;

    bool
    hasNormal (const std::vector<Eigen::Vector3d>& normals, int i)
    {
      return normals[i].squaredNorm () > 0.5;
    }

    /// Union-find with path halving, for Kruskal.
    int
    findRoot (std::vector<int>& up, int v)
    {
      while (up[v] != v)
        v = up[v] = up[up[v]];
      return v;
    }

    /// The minimum spanning forest (Kruskal: edges by weight, ties by their corners, so it is unique) as
    /// adjacency lists (CSR).
    void
    spanningForest (const PointNeighborhoods& hoods, const std::vector<std::uint8_t>& usable,
                    const std::vector<Eigen::Vector3d>& normals, std::vector<int>& offsets, std::vector<int>& adjacent)
    {
      const std::size_t n = hoods.size ();
      struct Edge
      {
        double weight;
        int a, b;
        bool operator< (const Edge& o) const { return std::tie (weight, a, b) < std::tie (o.weight, o.a, o.b); }
      };
      std::vector<Edge> edges;
      for (std::size_t i = 0; i < n; ++i)
        if (usable[i] && hasNormal (normals, static_cast<int> (i)))
          for (const int j : hoods.of (i))
            if (j > static_cast<int> (i) && usable[j] && hasNormal (normals, j))
              edges.push_back ({1.0 - std::abs (normals[i].dot (normals[j])), static_cast<int> (i), j});
      std::sort (edges.begin (), edges.end ());
      std::vector<int> up (n);
      std::iota (up.begin (), up.end (), 0);
      std::vector<std::pair<int, int>> directed;
      for (const Edge& e : edges)
      {
        const int ra = findRoot (up, e.a), rb = findRoot (up, e.b);
        if (ra == rb)
          continue;
        up[ra] = rb;
        directed.emplace_back (e.a, e.b);
        directed.emplace_back (e.b, e.a);
      }
      std::sort (directed.begin (), directed.end ());
      offsets.assign (n + 1, 0);
      adjacent.resize (directed.size ());
      for (std::size_t e = 0; e < directed.size (); ++e)
      {
        ++offsets[directed[e].first + 1];
        adjacent[e] = directed[e].second;
      }
      for (std::size_t i = 0; i < n; ++i)
        offsets[i + 1] += offsets[i];
    }

    /// Orients the tree \a members (breadth-first order from members[0]) from its root, as documented.
    void
    orientTree (const std::vector<Eigen::Vector3d>& positions, const std::vector<int>& members,
                const std::vector<int>& parent, std::vector<std::uint8_t>& on_path, std::vector<Eigen::Vector3d>& normals)
    {
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero ();
      for (const int i : members)
        centroid += positions[i];
      centroid /= static_cast<double> (members.size ());
      double radius2 = 0.0, best = -1.0, best_z = -1.0;
      int root = members[0], root_z = members[0];
      for (const int i : members)
      {
        radius2 += (positions[i] - centroid).squaredNorm ();
        const double outward = std::abs (normals[i].dot (positions[i] - centroid));
        if (outward > best)
          best = outward, root = i;
        if (std::abs (normals[i].z ()) > best_z)
          best_z = std::abs (normals[i].z ()), root_z = i;
      }
      const double rms = std::sqrt (radius2 / static_cast<double> (members.size ()));
      const bool flat = !(best > 0.05 * rms);
      const int start = flat ? root_z : root;
      const double sign = flat ? normals[start].z () : normals[start].dot (positions[start] - centroid);
      // Orient the start, then walk the tree from it (parents are given from members[0]: re-root by path).
      if (sign < 0.0)
        normals[start] = -normals[start];
      // Along the path from start up to members[0], each parent takes its child's orientation.
      for (int child = start; parent[child] >= 0; child = parent[child])
        if (normals[parent[child]].dot (normals[child]) < 0.0)
          normals[parent[child]] = -normals[parent[child]];
      // Then every other node from its parent, in breadth-first order (parents come first).
      for (int v = start; v >= 0; v = parent[v])
        on_path[v] = 1;
      for (const int v : members)
        if (!on_path[v] && normals[v].dot (normals[parent[v]]) < 0.0)
          normals[v] = -normals[v];
      for (int v = start; v >= 0; v = parent[v])
        on_path[v] = 0;
    }
  } // namespace

  void
  orientTowardViewpoints (const std::vector<Eigen::Vector3d>& positions, const Viewpoints& viewpoints,
                          const PointNeighborhoods& neighborhoods, const std::vector<std::uint8_t>& usable,
                          std::vector<Eigen::Vector3d>& normals)
  {
    const std::size_t n = positions.size ();
    std::vector<std::uint8_t> decided (n, 0);
    for (std::size_t i = 0; i < n; ++i)
    {
      const Eigen::Vector3d sight = viewpoints.of (i) - positions[i];
      const double along = normals[i].dot (sight);
      if (along < 0.0)
        normals[i] = -normals[i];
      decided[i] = std::abs (along) >= kGrazingCosine * sight.norm () ? 1 : 0;
    }
    // Grazing normals take the sign of their decided neighbours, spreading in passes (each pass reads only
    // the previous one's decisions, so the result does not depend on the order).
    std::vector<int> grazing;
    for (std::size_t i = 0; i < n; ++i)
      if (!decided[i] && usable[i] && hasNormal (normals, static_cast<int> (i)))
        grazing.push_back (static_cast<int> (i));
    std::vector<int> now;
    while (!grazing.empty ())
    {
      now.clear ();
      std::vector<int> later;
      for (const int i : grazing)
      {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero ();
        for (const int j : neighborhoods.of (i))
          if (decided[j] && usable[j])
            sum += normals[j];
        if (sum.squaredNorm () > 0.0)
        {
          if (normals[i].dot (sum) < 0.0)
            normals[i] = -normals[i];
          now.push_back (i);
        }
        else
          later.push_back (i);
      }
      if (now.empty ())
        break;  // the rest is out of reach: it keeps the viewpoint's sign
      for (const int i : now)
        decided[i] = 1;
      grazing.swap (later);
    }
  }

  void
  orientBySpanningTree (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                        const std::vector<std::uint8_t>& usable, std::vector<Eigen::Vector3d>& normals)
  {
    std::vector<int> offsets, adjacent;
    spanningForest (neighborhoods, usable, normals, offsets, adjacent);
    const std::size_t n = positions.size ();
    std::vector<int> parent (n, -1);
    std::vector<std::uint8_t> seen (n, 0), on_path (n, 0);
    std::vector<int> members;
    for (std::size_t s = 0; s < n; ++s)
    {
      if (seen[s] || !usable[s] || !hasNormal (normals, static_cast<int> (s)))
        continue;
      members.assign (1, static_cast<int> (s));
      seen[s] = 1;
      for (std::size_t q = 0; q < members.size (); ++q)
        for (int e = offsets[members[q]]; e < offsets[members[q] + 1]; ++e)
          if (!seen[adjacent[e]])
          {
            seen[adjacent[e]] = 1;
            parent[adjacent[e]] = members[q];
            members.push_back (adjacent[e]);
          }
      orientTree (positions, members, parent, on_path, normals);
    }
  }

  void
  orientByImageGrid (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3i>& image_triangles,
                     const PointNeighborhoods& neighborhoods, const std::vector<std::uint8_t>& usable,
                     std::vector<Eigen::Vector3d>& normals)
  {
    const std::size_t n = positions.size ();
    std::vector<Eigen::Vector3d> facing (n, Eigen::Vector3d::Zero ());
    for (const auto& t : image_triangles)
    {
      const Eigen::Vector3d area = (positions[t[1]] - positions[t[0]]).cross (positions[t[2]] - positions[t[0]]);
      for (int c = 0; c < 3; ++c)
        facing[t[c]] += area;
    }
    std::vector<int> loose;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!usable[i] || !hasNormal (normals, static_cast<int> (i)))
        continue;
      if (facing[i].squaredNorm () > 0.0)
      {
        if (normals[i].dot (facing[i]) < 0.0)
          normals[i] = -normals[i];
      }
      else
        loose.push_back (static_cast<int> (i));
    }
    orientLikeNeighbors (neighborhoods, usable, loose, normals);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero ();
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (usable[i])
        centroid += positions[i], ++count;
    centroid /= static_cast<double> (std::max<std::size_t> (count, 1));
    double outward = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (usable[i])
        outward += normals[i].dot (positions[i] - centroid);
    if (outward < 0.0)
      for (auto& normal : normals)
        normal = -normal;
  }

  void
  orientLikeNeighbors (const PointNeighborhoods& neighborhoods, const std::vector<std::uint8_t>& usable,
                       const std::vector<int>& points, std::vector<Eigen::Vector3d>& normals)
  {
    std::vector<std::uint8_t> listed (normals.size (), 0);
    for (const int i : points)
      listed[i] = 1;
    for (const int i : points)
    {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero ();
      for (const int j : neighborhoods.of (i))
        if (usable[j] && !listed[j])
          sum += normals[j];
      if (normals[i].dot (sum) < 0.0)
        normals[i] = -normals[i];
    }
  }
} // namespace pcl_sparse
