#include <pcl_sparse/coding/patch_footprint.h>
#include <pcl_sparse/common/upper_median.h>

#include "patch_local_index.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  namespace
  {
    /// Sector of a direction: floor(angle / (2 pi / K)) in [0, K).
    int
    sectorOf (const Eigen::Vector2d& p, int angles)
    {
      double t = std::atan2 (p.y (), p.x ()) / (2.0 * M_PI);
      t -= std::floor (t);
      return std::min (static_cast<int> (t * angles), angles - 1);
    }

    double
    cross2 (const Eigen::Vector2d& a, const Eigen::Vector2d& b)
    {
      return a.x () * b.y () - a.y () * b.x ();
    }

    /// One projected vertex: position, radius and sector.
    struct Corner
    {
      Eigen::Vector2d p;
      double r;
      int sector;
    };

    /// The radius r > 0 where \a ray (a unit direction from the origin) crosses segment [a, b], if it does.
    bool
    rayCrossing (const Eigen::Vector2d& ray, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double& r)
    {
      const double ca = cross2 (ray, a), cb = cross2 (ray, b);
      if ((ca > 0.0 && cb > 0.0) || (ca < 0.0 && cb < 0.0) || ca == cb)
        return false;
      r = ray.dot (a + ca / (ca - cb) * (b - a));
      return r > 0.0;
    }

    /// Raises the maximum of sector \a k and of its predecessor with the crossing of ray k by [a, b].
    void
    addRayCrossing (const Corner& a, const Corner& b, int k, const std::vector<Eigen::Vector2d>& rays,
                    std::vector<double>& sector_max)
    {
      const int angles = static_cast<int> (rays.size ());
      double r = 0.0;
      if (!rayCrossing (rays[k], a.p, b.p, r))
        return;
      sector_max[k] = std::max (sector_max[k], r);
      sector_max[(k + angles - 1) % angles] = std::max (sector_max[(k + angles - 1) % angles], r);
    }

    /// Calls \a visit (k) for each ray k that segment [a, b] (no endpoint at the origin) can cross. The
    /// segment sweeps the shorter arc between its endpoints' directions unless it is collinear with the
    /// origin (then every ray): rays from.sector + 1 .. to.sector, counter-clockwise. With \a margin the
    /// rays bordering the endpoints' own sectors (from.sector, to.sector + 1) are visited too, so a ray
    /// through an endpoint is tried whatever the rounding of its sector.
    template <typename Visit>
    void
    forEachRayOnArc (const Corner& a, const Corner& b, int angles, bool margin, Visit&& visit)
    {
      const double cross = cross2 (a.p, b.p);
      if (std::abs (cross) <= 1e-12 * a.r * b.r)
      {
        for (int k = 0; k < angles; ++k)
          visit (k);
        return;
      }
      // Counter-clockwise from a to b if cross > 0.
      const Corner& from = cross > 0.0 ? a : b;
      const Corner& to = cross > 0.0 ? b : a;
      // Counted rather than run up to the last ray: with 3 angles an arc from sector s to sector s + 2 has
      // its margin ray (s + 3 = s) as its first, and only that one was visited.
      const int between = (to.sector - from.sector + angles) % angles;  // rays from.sector + 1 .. to.sector
      const int count = std::min (angles, margin ? between + 2 : between);
      const int first = margin ? from.sector : (from.sector + 1) % angles;
      for (int i = 0; i < count; ++i)
        visit ((first + i) % angles);
    }

    /// Raises sector maxima with the points of segment [a, b] (endpoints are counted by the caller): only
    /// the rays on its arc can cross it.
    void
    addSegment (const Corner& a, const Corner& b, const std::vector<Eigen::Vector2d>& rays,
                std::vector<double>& sector_max)
    {
      if (a.r == 0.0 || b.r == 0.0 || a.sector == b.sector)
        return;  // from the origin the segment is one direction; within one sector no ray is crossed
      forEachRayOnArc (a, b, static_cast<int> (rays.size ()), false,
                       [&] (int k) { addRayCrossing (a, b, k, rays, sector_max); });
    }

    /// Whether \a q lies in one of the projected triangles (corner indices into \a corners).
    bool
    insideSomeTriangle (const Eigen::Vector2d& q, const std::vector<std::array<int, 3>>& triangles,
                        const std::vector<Corner>& corners)
    {
      for (const auto& t : triangles)
      {
        const Eigen::Vector2d &a = corners[t[0]].p, &b = corners[t[1]].p, &c = corners[t[2]].p;
        const double d1 = cross2 (b - a, q - a), d2 = cross2 (c - b, q - b), d3 = cross2 (a - c, q - c);
        if ((d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0) || (d1 <= 0.0 && d2 <= 0.0 && d3 <= 0.0))
          return true;
      }
      return false;
    }

    /// An edge of the projected triangles used by only one of them: corners a < b, and that triangle.
    struct BorderEdge
    {
      int a, b;
      int triangle;  ///< index into the local triangles
    };

    /// The border of the union of the projected triangles, and the median length of all their edges.
    /// \a triangles: local corner indices.
    std::vector<BorderEdge>
    borderEdges (const std::vector<std::array<int, 3>>& triangles, const std::vector<Corner>& corners,
                 double& median_length)
    {
      // The edges (smaller corner, larger corner, triangle) in ascending order: a counting sort on the
      // smaller corner, then a sort of each bucket (a few edges). The same order as one std::sort of all
      // of them, which was about a third of the footprint's time (a fifth of it is left).
      const std::size_t num_edges = 3 * triangles.size ();
      std::vector<int> bucket_begin (corners.size () + 1, 0);
      for (const auto& t : triangles)
        for (int c = 0; c < 3; ++c)
          ++bucket_begin[std::min (t[c], t[(c + 1) % 3]) + 1];
      for (std::size_t v = 0; v < corners.size (); ++v)
        bucket_begin[v + 1] += bucket_begin[v];
      std::vector<int> next (bucket_begin.begin (), bucket_begin.end () - 1);
      std::vector<std::array<int, 3>> edges (num_edges);
      for (std::size_t i = 0; i < triangles.size (); ++i)
        for (int c = 0; c < 3; ++c)
        {
          const std::array<int, 3>& t = triangles[i];
          const int a = std::min (t[c], t[(c + 1) % 3]);
          edges[next[a]++] = {a, std::max (t[c], t[(c + 1) % 3]), static_cast<int> (i)};
        }
      for (std::size_t v = 0; v < corners.size (); ++v)
        std::sort (edges.begin () + bucket_begin[v], edges.begin () + bucket_begin[v + 1]);
      std::vector<double> lengths;
      lengths.reserve (edges.size ());
      for (const auto& e : edges)
        lengths.push_back ((corners[e[0]].p - corners[e[1]].p).norm ());
      median_length = upperMedian (lengths);
      std::vector<BorderEdge> border;
      for (std::size_t i = 0; i < edges.size ();)
      {
        std::size_t j = i;
        while (j < edges.size () && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1])
          ++j;
        if (j - i == 1)
          border.push_back ({edges[i][0], edges[i][1], edges[i][2]});
        i = j;
      }
      return border;
    }

    /// Whether the mesh goes on smoothly past border edge \a e of the patch: the face across it (through a
    /// manifold edge) exists and faces within the limit of the patch's normal, as the patch's own faces do.
    /// At open borders, sharp edges and where the surface curls away (a thin part's rounded edge) it does not.
    bool
    continuesSmoothly (const BorderEdge& e, const std::vector<int>& faces, const Patch& patch, const TriangleMesh& mesh,
                       const MeshTopology& topology, double min_cosine)
    {
      const int f = faces[e.triangle];
      const int va = patch.vertices[e.a], vb = patch.vertices[e.b];
      for (int k = 0; k < 3; ++k)
      {
        const int u = mesh.triangles[f][k], w = mesh.triangles[f][(k + 1) % 3];
        if (!((u == va && w == vb) || (u == vb && w == va)))
          continue;
        const int g = topology.face_neighbors[f][k];
        if (g < 0)
          return false;
        const Eigen::Vector3i& t = mesh.triangles[g];
        const Eigen::Vector3d n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross (mesh.vertices[t[2]] - mesh.vertices[t[0]]);
        const double length = n.norm ();
        return length > 0.0 && n.dot (patch.frame.col (2)) >= min_cosine * length;
      }
      return false;
    }

    /// Per ray, the radii where it crosses the border edges, ascending. With \a smooth_edge (per border
    /// edge), \a smooth_exit gets per ray whether its outermost crossing is on a smooth edge (false for a ray
    /// that crosses none, and where edges of both kinds cross it there).
    std::vector<std::vector<double>>
    borderCrossings (const std::vector<BorderEdge>& border, const std::vector<Corner>& corners,
                     const std::vector<Eigen::Vector2d>& rays, const std::vector<char>* smooth_edge = nullptr,
                     std::vector<char>* smooth_exit = nullptr)
    {
      std::vector<std::vector<double>> crossings (rays.size ());
      std::vector<double> outermost (rays.size (), 0.0);
      if (smooth_exit)
        smooth_exit->assign (rays.size (), 0);
      for (std::size_t i = 0; i < border.size (); ++i)
      {
        const Corner &a = corners[border[i].a], &b = corners[border[i].b];
        if (a.r == 0.0 || b.r == 0.0)
          continue;  // a segment from the origin crosses no ray at r > 0
        const char smooth = smooth_edge ? (*smooth_edge)[i] : 0;
        // Every ray the arc with its margin leaves out would fail the test.
        forEachRayOnArc (a, b, static_cast<int> (rays.size ()), true, [&] (int k) {
          double r = 0.0;
          if (!rayCrossing (rays[k], a.p, b.p, r))
            return;
          if (smooth_exit && (crossings[k].empty () || r > outermost[k]))
            (*smooth_exit)[k] = smooth;
          else if (smooth_exit && r == outermost[k])
            (*smooth_exit)[k] = (*smooth_exit)[k] && smooth;
          outermost[k] = std::max (outermost[k], r);
          crossings[k].push_back (r);
        });
      }
      for (auto& c : crossings)
        std::sort (c.begin (), c.end ());
      return crossings;
    }

    /// Per ray, the radius where it first leaves the union of the projected triangles for a gap wider than
    /// 3 median edge lengths before meeting them again (a hole, or a concave bay of the patch's border);
    /// +infinity where it meets no such gap. Narrower gaps (a missing triangle of a scan's triangulation)
    /// are crossed: clipping there would open holes between patches.
    std::vector<double>
    firstExits (const std::vector<std::array<int, 3>>& triangles, const std::vector<Corner>& corners,
                const std::vector<std::vector<double>>& crossings, double median_length,
                const std::vector<Eigen::Vector2d>& rays)
    {
      const double gap = 3.0 * median_length;
      std::vector<double> exits (rays.size (), std::numeric_limits<double>::infinity ());
      for (std::size_t k = 0; k < rays.size (); ++k)
      {
        const std::vector<double>& c = crossings[k];
        for (std::size_t i = 0; i + 1 < c.size (); ++i)
          if (c[i + 1] - c[i] > gap && !insideSomeTriangle (0.5 * (c[i] + c[i + 1]) * rays[k], triangles, corners))
          {
            exits[k] = c[i];
            break;
          }
      }
      return exits;
    }

    /// Lowers each conservative \a extent to the outermost crossing of its ray with the triangles' border
    /// (\a outer), then raises the two extents around each corner the linear interpolation would cut, just
    /// enough to hold it (never above the conservative extents, which hold every corner). Every point of
    /// every projected triangle stays inside: along a segment within one sector the radius is a convex
    /// function of the angle, so the interpolation holds the segment once it holds the segment's ends
    /// (corners, or crossings of the rays, which are at most the outermost crossing).
    void
    clipAtBorder (const std::vector<Corner>& corners, const std::vector<double>& outer, std::vector<double>& extent)
    {
      const int angles = static_cast<int> (extent.size ());
      const std::vector<double> conservative = extent;
      for (int k = 0; k < angles; ++k)
        extent[k] = std::min (extent[k], outer[k]);
      for (const Corner& c : corners)
      {
        if (!(c.r > 0.0))
          continue;
        double t = std::atan2 (c.p.y (), c.p.x ()) / (2.0 * M_PI);
        t -= std::floor (t);
        const int k = c.sector, j = (k + 1) % angles;
        const double w = std::min (1.0, std::max (0.0, t * angles - k));
        // The nearer ray first, so the other one moves as little as possible.
        const int near = w >= 0.5 ? j : k, far = w >= 0.5 ? k : j;
        const double near_weight = w >= 0.5 ? w : 1.0 - w, far_weight = 1.0 - near_weight;
        auto held = [&] () { return (1.0 - w) * extent[k] + w * extent[j]; };
        if (held () >= c.r)
          continue;
        extent[near] = std::min (conservative[near], extent[near] + (c.r - held ()) / near_weight);
        if (held () < c.r && far_weight > 0.0)
          extent[far] = std::min (conservative[far], extent[far] + (c.r - held ()) / far_weight);
      }
    }

    /// Raises each extent whose ray leaves the patch across a smooth edge towards the largest extent within
    /// \a reach angles on either side whose ray does too, by at most \a max_raise.
    void
    reachOverSmoothBorders (const std::vector<char>& smooth_exit, int reach, double max_raise, std::vector<double>& extent)
    {
      const int angles = static_cast<int> (extent.size ());
      const std::vector<double> clipped = extent;
      for (int k = 0; k < angles; ++k)
        if (smooth_exit[k])
          for (int d = -reach; d <= reach; ++d)
          {
            const int j = ((k + d) % angles + angles) % angles;
            if (smooth_exit[j])
              extent[k] = std::max (extent[k], std::min (clipped[j], clipped[k] + max_raise));
          }
    }
  } // namespace

  PatchFootprint
  computePatchFootprint (const Patch& patch, const TriangleMesh& mesh, int angles, bool clip_at_first_exit,
                         bool clip_at_border, double reach_degrees, const MeshTopology* topology,
                         double reach_max_tilt_degrees)
  {
    PatchFootprint footprint;
    if (angles < 1)
      return footprint;
    std::vector<Eigen::Vector2d> rays (angles);
    for (int k = 0; k < angles; ++k)
      rays[k] = Eigen::Vector2d (std::cos (2.0 * M_PI * k / angles), std::sin (2.0 * M_PI * k / angles));

    std::vector<double> sector_max (angles, 0.0);
    const std::size_t count = std::min (patch.vertices.size (), patch.local.size ());
    const PatchLocalIndex local_index (patch.vertices, count, mesh.vertices.size ());
    std::vector<Corner> corners (count);
    for (std::size_t i = 0; i < count; ++i)
    {
      Corner& c = corners[i];
      c.p = patch.local[i].head<2> ();
      c.r = c.p.norm ();
      c.sector = c.r > 0.0 ? sectorOf (c.p, angles) : 0;
      if (c.r > 0.0)
        sector_max[c.sector] = std::max (sector_max[c.sector], c.r);
    }
    std::vector<std::array<int, 3>> local_triangles;
    std::vector<int> local_faces;  // their faces in the mesh
    for (int f : patch.triangles)
    {
      if (f < 0 || static_cast<std::size_t> (f) >= mesh.triangles.size ())
        continue;
      int corner[3];
      bool ok = true;
      for (int c = 0; c < 3 && ok; ++c)
      {
        corner[c] = local_index (mesh.triangles[f][c]);
        ok = corner[c] >= 0;
      }
      if (!ok)
        continue;
      for (int c = 0; c < 3; ++c)
        addSegment (corners[corner[c]], corners[corner[(c + 1) % 3]], rays, sector_max);
      local_triangles.push_back ({corner[0], corner[1], corner[2]});
      local_faces.push_back (f);
    }
    std::vector<double> exits, outer;
    std::vector<char> smooth_exit;
    double median_length = 0.0;
    const int reach = static_cast<int> (std::lround (reach_degrees / 360.0 * angles));
    const bool reach_over_smooth = clip_at_border && topology && reach > 0;
    if ((clip_at_first_exit || clip_at_border) && !local_triangles.empty ())
    {
      const std::vector<BorderEdge> border = borderEdges (local_triangles, corners, median_length);
      std::vector<char> smooth_edge;
      if (reach_over_smooth)
      {
        const double min_cosine = std::cos (reach_max_tilt_degrees * M_PI / 180.0);
        for (const BorderEdge& e : border)
          smooth_edge.push_back (continuesSmoothly (e, local_faces, patch, mesh, *topology, min_cosine));
      }
      const auto crossings = borderCrossings (border, corners, rays, reach_over_smooth ? &smooth_edge : nullptr,
                                              reach_over_smooth ? &smooth_exit : nullptr);
      if (clip_at_first_exit)
        exits = firstExits (local_triangles, corners, crossings, median_length, rays);
      if (clip_at_border)
      {
        // A ray that crosses no border edge lies outside the triangles (from a seed on the patch's border
        // it points away from the patch): its outermost crossing is the seed itself, 0. Left at the
        // sector maxima, it kept a whole sector's reach outside the patch (a wedge beyond its border).
        outer.assign (angles, 0.0);
        for (int k = 0; k < angles; ++k)
          if (!crossings[k].empty ())
            outer[k] = crossings[k].back ();
      }
    }

    // The conservative extents: the larger of the two adjacent sector maxima.
    std::vector<double> extent (angles);
    for (int k = 0; k < angles; ++k)
      extent[k] = std::max (sector_max[k], sector_max[(k + angles - 1) % angles]);
    if (!outer.empty ())
      clipAtBorder (corners, outer, extent);
    if (!smooth_exit.empty ())
      reachOverSmoothBorders (smooth_exit, reach, 0.5 * median_length, extent);
    footprint.extent.resize (angles);
    for (int k = 0; k < angles; ++k)
    {
      double e = extent[k];
      if (!exits.empty ())
        e = std::min (e, exits[k]);
      // Round up so the float never cuts a vertex lying exactly on the boundary.
      footprint.extent[k] = static_cast<float> (e * (1.0 + 1e-6) + 1e-9);
    }
    return footprint;
  }
} // namespace pcl_sparse
