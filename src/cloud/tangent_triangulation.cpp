#include <pcl_sparse/cloud/tangent_triangulation.h>

#include <pcl_sparse/common/splitmix64.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/geometry/quadric_fit.h>

#include "edge_set.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>

namespace pcl_sparse
{
  namespace
  {
    using Key = std::array<int, 3>;

    /// A vertex of the Voronoi cell and the label of the cell edge leaving it (-1: the bounding square).
    struct CellVertex
    {
      Eigen::Vector2d p;
      int label;
    };

    struct FanScratch
    {
      std::vector<std::tuple<double, int, Eigen::Vector2d>> candidates;  // |q|^2, point, projection
      std::vector<CellVertex> cell, clipped;
    };

    /// A fixed direction in [-1, 1]^2 per point index (splitmix64), for the symbolic perturbation.
    Eigen::Vector2d
    perturbation (int index)
    {
      const std::uint64_t z = splitmix64 (static_cast<std::uint64_t> (index));
      const double u = static_cast<double> (z & 0xffffffffull) / 4294967295.0;
      const double v = static_cast<double> (z >> 32) / 4294967295.0;
      return {2.0 * u - 1.0, 2.0 * v - 1.0};
    }

    /// Clips the convex cell by the half-plane of points closer to 0 than to q; the new edge gets \a label.
    void
    clipCell (const Eigen::Vector2d& q, int label, FanScratch& s)
    {
      const double c = 0.5 * q.squaredNorm ();
      s.clipped.clear ();
      const std::size_t m = s.cell.size ();
      for (std::size_t k = 0; k < m; ++k)
      {
        const CellVertex& P = s.cell[k];
        const CellVertex& Q = s.cell[(k + 1) % m];
        const double dP = q.dot (P.p) - c, dQ = q.dot (Q.p) - c;
        if (dP <= 0.0)
          s.clipped.push_back (P);
        if ((dP <= 0.0) != (dQ <= 0.0))
        {
          const Eigen::Vector2d X = P.p + (dP / (dP - dQ)) * (Q.p - P.p);
          s.clipped.push_back ({X, dP <= 0.0 ? label : P.label});
        }
      }
      s.cell.swap (s.clipped);
    }

    /// Point i's fan triangles (sorted corner indices) appended to \a out.
    void
    proposeFan (int i, const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& hoods,
                const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                double gap_factor, const ShadowRule& shadow, FanScratch& s, std::vector<Key>& out)
    {
      const Eigen::Matrix3d frame = frameAroundNormal (normals[i]);
      const double eps = 1e-7 * hoods.spacing[i];
      s.candidates.clear ();
      for (const int j : hoods.of (i))
        if (usable[j] && normals[j].dot (normals[i]) > 0.25)
        {
          const Eigen::Vector3d d = positions[j] - positions[i];
          const Eigen::Vector2d q = Eigen::Vector2d (d.dot (frame.col (0)), d.dot (frame.col (1))) +
                                    eps * (perturbation (j) - perturbation (i));
          if (q.squaredNorm () > 0.0)
            s.candidates.emplace_back (q.squaredNorm (), j, q);
        }
      if (s.candidates.size () < 2)
        return;
      std::sort (s.candidates.begin (), s.candidates.end (),
                 [] (const auto& x, const auto& y) { return std::tie (std::get<0> (x), std::get<1> (x)) < std::tie (std::get<0> (y), std::get<1> (y)); });
      const double R = 2.0 * std::sqrt (std::get<0> (s.candidates.back ()));
      s.cell = {{{-R, -R}, -1}, {{R, -R}, -1}, {{R, R}, -1}, {{-R, R}, -1}};
      for (const auto& [squared, j, q] : s.candidates)
      {
        double reach = 0.0;  // the cell's farthest vertex: farther bisectors cannot cut it
        for (const auto& v : s.cell)
          reach = std::max (reach, v.p.squaredNorm ());
        if (0.25 * squared > reach)
          break;
        clipCell (q, j, s);
      }
      // Consecutive labelled edges of positive length share a Voronoi vertex: a Delaunay triangle.
      const double tolerance = 1e-12 * R;
      int first = -2, previous = -2;
      const std::size_t m = s.cell.size ();
      auto emit = [&] (int a, int b) {
        if (a < 0 || b < 0 || a == b)
          return;
        const double limit = gap_factor * std::min (hoods.spacing[a], hoods.spacing[b]);
        if ((positions[a] - positions[b]).norm () > limit || shadow.shadowed (i, positions[a], positions[b]))
          return;
        Key key{i, a, b};
        std::sort (key.begin (), key.end ());
        out.push_back (key);
      };
      for (std::size_t k = 0; k < m; ++k)
      {
        if ((s.cell[(k + 1) % m].p - s.cell[k].p).norm () <= tolerance)
          continue;
        const int label = s.cell[k].label;
        if (first == -2)
          first = label;
        else
          emit (previous, label);
        previous = label;
      }
      if (first != -2 && previous != first)
        emit (previous, first);
    }
  } // namespace

  std::vector<Eigen::Vector3i>
  triangulateTangentFans (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                          const std::vector<Eigen::Vector3d>& normals, const std::vector<std::uint8_t>& usable,
                          double gap_factor, const ShadowRule& shadow, int num_threads)
  {
    const std::ptrdiff_t n = static_cast<std::ptrdiff_t> (positions.size ());
    std::vector<Key> proposals;
    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel num_threads(threads)
    {
      FanScratch scratch;
      std::vector<Key> mine;
#pragma omp for schedule(dynamic, 512) nowait
      for (std::ptrdiff_t i = 0; i < n; ++i)
        if (usable[i] && normals[i].squaredNorm () > 0.5)
          proposeFan (static_cast<int> (i), positions, neighborhoods, normals, usable, gap_factor, shadow, scratch, mine);
#pragma omp critical
      proposals.insert (proposals.end (), mine.begin (), mine.end ());
    }
    // The order of the proposals depends on the threads; sorted, it does not.
    std::sort (proposals.begin (), proposals.end ());

    struct Candidate
    {
      int votes;
      double longest;
      Eigen::Vector3i corners;
    };
    std::vector<Candidate> candidates;
    for (std::size_t s = 0; s < proposals.size ();)
    {
      std::size_t e = s;
      while (e < proposals.size () && proposals[e] == proposals[s])
        ++e;
      const Key& k = proposals[s];
      const int votes = static_cast<int> (e - s);
      s = e;
      Eigen::Vector3i t (k[0], k[1], k[2]);
      const Eigen::Vector3d &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
      if ((b - a).cross (c - a).dot (normals[t[0]] + normals[t[1]] + normals[t[2]]) < 0.0)
        std::swap (t[1], t[2]);
      const double longest = std::max ({(b - a).norm (), (c - b).norm (), (a - c).norm ()});
      candidates.push_back ({votes, longest, t});
    }
    std::sort (candidates.begin (), candidates.end (), [] (const Candidate& x, const Candidate& y) {
      if (x.votes != y.votes)
        return x.votes > y.votes;
      if (x.longest != y.longest)
        return x.longest < y.longest;
      return std::lexicographical_compare (x.corners.data (), x.corners.data () + 3, y.corners.data (), y.corners.data () + 3);
    });

    EdgeSet used (3 * candidates.size ());
    std::vector<Eigen::Vector3i> triangles;
    for (const auto& candidate : candidates)
    {
      const Eigen::Vector3i& t = candidate.corners;
      if (used.contains (t[0], t[1]) || used.contains (t[1], t[2]) || used.contains (t[2], t[0]))
        continue;
      used.insert (t[0], t[1]);
      used.insert (t[1], t[2]);
      used.insert (t[2], t[0]);
      triangles.push_back (t);
    }
    return triangles;
  }
} // namespace pcl_sparse
