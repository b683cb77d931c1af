#include <pcl_sparse/cloud/normal_orientation.h>

#include <pcl_sparse/mesh/mesh_components.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
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

    /// Flips the normals of \a points toward direction (i); where a normal is within 10 degrees of
    /// perpendicular to it, the sign is the estimation error's, so a usable such point takes the sign of its
    /// decided neighbours (sum of their normals) instead, spreading in passes (each pass reads only the
    /// previous one's decisions: the result does not depend on the order); where none reaches, the first
    /// unreached point keeps direction's sign and spreads it the same way.
    /// A pass looks only at the grazing points next to the previous pass's decisions (through reverse
    /// neighbour lists), so the spreading costs O(their neighbourhoods) in all: passes over every grazing
    /// point cost O(passes x points), quadratic on ground seen at a grazing angle from a low sensor (found by
    /// a review: 4.7 s more for 400k points).
    /// With few grazing points the work is O(points and their neighbourhoods), not O(#P): the spanning tree
    /// orients every flat tree with it, and per-call arrays over the whole cloud made a cloud of many short
    /// wires quadratic (320k points in 32k wires: 9.3 s).
    /// \a decided, \a waiting: #P zeros, left zero.
    template <typename Direction>
    void
    orientAlong (const std::vector<int>& points, Direction direction, const PointNeighborhoods& hoods,
                 const std::vector<std::uint8_t>& usable, std::vector<std::uint8_t>& decided,
                 std::vector<std::uint8_t>& waiting, std::vector<Eigen::Vector3d>& normals)
    {
      std::vector<int> grazing;
      for (const int i : points)
      {
        const Eigen::Vector3d d = direction (i);
        const double along = normals[i].dot (d);
        if (along < 0.0)
          normals[i] = -normals[i];
        if (std::abs (along) >= kGrazingCosine * d.norm ())
          decided[i] = 1;
        else if (usable[i] && hasNormal (normals, i))
          grazing.push_back (i);
      }
      if (!grazing.empty ())
      {
        // Who lists j, among the grazing points: reverse lists over the whole cloud when the grazing points
        // are many (a low sensor over ground: 2M points 0.5 s, against 1.9 s sorting pairs), else the sorted
        // (j, k) pairs of the call (a flat tree of a few points in a large cloud). A pass's decisions do not
        // depend on the order of its candidates, so both give the same normals.
        const bool whole_cloud = grazing.size () * 16 >= hoods.size ();
        const PointNeighborhoods reverse = whole_cloud ? reverseNeighborhoods (hoods, grazing) : PointNeighborhoods ();
        std::vector<std::pair<int, int>> listed_by;
        if (!whole_cloud)
        {
          for (const int k : grazing)
            for (const int j : hoods.of (k))
              listed_by.emplace_back (j, k);
          std::sort (listed_by.begin (), listed_by.end ());
        }
        for (const int i : grazing)
          waiting[i] = 1;
        std::vector<int> candidates = grazing, now;
        // The waiting grazing points that list i become candidates of the next pass, once each.
        auto consider = [&] (int k) {
          if (waiting[k] == 1)
          {
            waiting[k] = 2;
            candidates.push_back (k);
          }
        };
        auto listersOf = [&] (int i) {
          if (whole_cloud)
          {
            for (const int k : reverse.of (i))
              consider (k);
            return;
          }
          auto it = std::lower_bound (listed_by.begin (), listed_by.end (), std::make_pair (i, std::numeric_limits<int>::min ()));
          for (; it != listed_by.end () && it->first == i; ++it)
            consider (it->second);
        };
        // The first pass looks at every grazing point; later ones at those next to new decisions. Grazing
        // points no decision reaches (a viewpoint in the plane of the surface leaves every point grazing)
        // are made consistent among themselves: the first of them keeps its sign and spreads it, so
        // neighbouring normals agree instead of keeping their estimation's random signs (found by a review).
        std::size_t next_seed = 0;
        while (!candidates.empty () || next_seed < grazing.size ())
        {
          if (candidates.empty ())
          {
            while (next_seed < grazing.size () && !waiting[grazing[next_seed]])
              ++next_seed;
            if (next_seed == grazing.size ())
              break;
            const int seed = grazing[next_seed];
            decided[seed] = 1;
            waiting[seed] = 0;
            listersOf (seed);
            for (const int i : candidates)
              waiting[i] = 1;
            continue;
          }
          now.clear ();
          for (const int i : candidates)
          {
            Eigen::Vector3d sum = Eigen::Vector3d::Zero ();
            for (const int j : hoods.of (i))
              if (decided[j] && usable[j])
                sum += normals[j];
            if (sum.squaredNorm () > 0.0)
            {
              if (normals[i].dot (sum) < 0.0)
                normals[i] = -normals[i];
              now.push_back (i);
            }
          }
          for (const int i : now)
          {
            decided[i] = 1;
            waiting[i] = 0;
          }
          candidates.clear ();
          for (const int i : now)
            listersOf (i);
          for (const int i : candidates)
            waiting[i] = 1;
        }
      }
      for (const int i : points)
        decided[i] = 0;
      for (const int i : grazing)
        waiting[i] = 0;
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
      DisjointSets trees (n);  // which edges Kruskal keeps does not depend on how the sets are joined
      std::vector<std::pair<int, int>> directed;
      for (const Edge& e : edges)
      {
        if (trees.find (e.a) == trees.find (e.b))
          continue;
        trees.join (e.a, e.b);
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
                const std::vector<int>& parent, const PointNeighborhoods& hoods, const std::vector<std::uint8_t>& usable,
                std::vector<std::uint8_t>& scratch, std::vector<std::uint8_t>& waiting, std::vector<Eigen::Vector3d>& normals)
    {
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero ();
      for (const int i : members)
        centroid += positions[i];
      centroid /= static_cast<double> (members.size ());
      Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero ();
      double best = -1.0;
      int root = members[0];
      for (const int i : members)
      {
        const Eigen::Vector3d d = positions[i] - centroid;
        covariance.noalias () += d * d.transpose ();
        const double outward = std::abs (normals[i].dot (d));
        if (outward > best)
          best = outward, root = i;
      }
      // Flat (a wall, a terrain): the thinnest direction of the tree has under a tenth of the widest one's
      // extent. Then "outward" means nothing, and propagation across creases and vegetation goes astray:
      // the tree is seen as from a viewpoint far along its thinnest axis (up, for a terrain).
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread (covariance);
      if (!(spread.eigenvalues ()[0] > 0.01 * spread.eigenvalues ()[2]))
      {
        Eigen::Vector3d axis = spread.eigenvectors ().col (0);
        int largest;
        axis.cwiseAbs ().maxCoeff (&largest);
        if (std::abs (axis.z ()) > 1e-3 ? axis.z () < 0.0 : axis[largest] < 0.0)
          axis = -axis;
        orientAlong (members, [&] (int) { return axis; }, hoods, usable, scratch, waiting, normals);
        return;
      }
      const int start = root;
      const double sign = normals[start].dot (positions[start] - centroid);
      // Orient the start, then walk the tree from it (parents are given from members[0]: re-root by path).
      if (sign < 0.0)
        normals[start] = -normals[start];
      // Along the path from start up to members[0], each parent takes its child's orientation.
      for (int child = start; parent[child] >= 0; child = parent[child])
        if (normals[parent[child]].dot (normals[child]) < 0.0)
          normals[parent[child]] = -normals[parent[child]];
      // Then every other node from its parent, in breadth-first order (parents come first).
      for (int v = start; v >= 0; v = parent[v])
        scratch[v] = 1;  // on the path
      for (const int v : members)
        if (!scratch[v] && normals[v].dot (normals[parent[v]]) < 0.0)
          normals[v] = -normals[v];
      for (int v = start; v >= 0; v = parent[v])
        scratch[v] = 0;
    }
  } // namespace

  void
  orientTowardViewpoints (const std::vector<Eigen::Vector3d>& positions, const Viewpoints& viewpoints,
                          const PointNeighborhoods& neighborhoods, const std::vector<std::uint8_t>& usable,
                          std::vector<Eigen::Vector3d>& normals)
  {
    std::vector<int> all (positions.size ());
    std::iota (all.begin (), all.end (), 0);
    std::vector<std::uint8_t> scratch (positions.size (), 0), waiting (positions.size (), 0);
    orientAlong (all, [&] (int i) { return Eigen::Vector3d (viewpoints.of (i) - positions[i]); }, neighborhoods, usable,
                 scratch, waiting, normals);
  }

  void
  orientBySpanningTree (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                        const std::vector<std::uint8_t>& usable, std::vector<Eigen::Vector3d>& normals)
  {
    std::vector<int> offsets, adjacent;
    spanningForest (neighborhoods, usable, normals, offsets, adjacent);
    const std::size_t n = positions.size ();
    std::vector<int> parent (n, -1);
    std::vector<std::uint8_t> seen (n, 0), scratch (n, 0), waiting (n, 0);
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
      if (members.size () < 3)  // no shape to speak of
      {
        for (const int v : members)
          if (normals[v].z () < 0.0)
            normals[v] = -normals[v];
        continue;
      }
      orientTree (positions, members, parent, neighborhoods, usable, scratch, waiting, normals);
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
