#include <pcl_sparse/coding/patch_footprint.h>

#include <algorithm>
#include <cmath>
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

    /// Raises the maximum of sector \a k and of its predecessor with the crossing of ray k by [a, b].
    void
    addRayCrossing (const Corner& a, const Corner& b, int k, const std::vector<Eigen::Vector2d>& rays,
                    std::vector<double>& sector_max)
    {
      const int angles = static_cast<int> (rays.size ());
      const double ca = cross2 (rays[k], a.p), cb = cross2 (rays[k], b.p);
      if ((ca > 0.0 && cb > 0.0) || (ca < 0.0 && cb < 0.0) || ca == cb)
        return;
      const double t = ca / (ca - cb);
      const double r = rays[k].dot (a.p + t * (b.p - a.p));
      if (r <= 0.0)
        return;
      sector_max[k] = std::max (sector_max[k], r);
      sector_max[(k + angles - 1) % angles] = std::max (sector_max[(k + angles - 1) % angles], r);
    }

    /// Raises sector maxima with the points of segment [a, b] (endpoints are counted by the caller).
    /// The segment sweeps the shorter arc between its endpoints' directions unless it passes through the
    /// origin; only the rays on that arc can cross it.
    void
    addSegment (const Corner& a, const Corner& b, const std::vector<Eigen::Vector2d>& rays,
                std::vector<double>& sector_max)
    {
      const int angles = static_cast<int> (rays.size ());
      if (a.r == 0.0 || b.r == 0.0 || a.sector == b.sector)
        return;  // from the origin the segment is one direction; within one sector no ray is crossed
      const double cross = cross2 (a.p, b.p);
      if (std::abs (cross) <= 1e-12 * a.r * b.r)
      {
        // Collinear with the origin: either one direction or through the origin; test every ray.
        for (int k = 0; k < angles; ++k)
          addRayCrossing (a, b, k, rays, sector_max);
        return;
      }
      // Counter-clockwise from a to b if cross > 0: rays a.sector + 1 .. b.sector are crossed.
      const Corner& from = cross > 0.0 ? a : b;
      const Corner& to = cross > 0.0 ? b : a;
      for (int k = (from.sector + 1) % angles;; k = (k + 1) % angles)
      {
        addRayCrossing (a, b, k, rays, sector_max);
        if (k == to.sector)
          break;
      }
    }
  } // namespace

  PatchFootprint
  computePatchFootprint (const Patch& patch, const TriangleMesh& mesh, int angles)
  {
    PatchFootprint footprint;
    if (angles < 1)
      return footprint;
    std::vector<Eigen::Vector2d> rays (angles);
    for (int k = 0; k < angles; ++k)
      rays[k] = Eigen::Vector2d (std::cos (2.0 * M_PI * k / angles), std::sin (2.0 * M_PI * k / angles));

    std::vector<double> sector_max (angles, 0.0);
    // Mesh vertex id -> local index, as a sorted array (patches are small: cheaper than a hash map).
    const std::size_t count = std::min (patch.vertices.size (), patch.local.size ());
    std::vector<std::pair<int, int>> lookup (count);
    std::vector<Corner> corners (count);
    for (std::size_t i = 0; i < count; ++i)
    {
      lookup[i] = {patch.vertices[i], static_cast<int> (i)};
      Corner& c = corners[i];
      c.p = patch.local[i].head<2> ();
      c.r = c.p.norm ();
      c.sector = c.r > 0.0 ? sectorOf (c.p, angles) : 0;
      if (c.r > 0.0)
        sector_max[c.sector] = std::max (sector_max[c.sector], c.r);
    }
    std::sort (lookup.begin (), lookup.end ());
    for (int f : patch.triangles)
    {
      if (f < 0 || static_cast<std::size_t> (f) >= mesh.triangles.size ())
        continue;
      int corner[3];
      bool ok = true;
      for (int c = 0; c < 3 && ok; ++c)
      {
        const int v = mesh.triangles[f][c];
        const auto it = std::lower_bound (lookup.begin (), lookup.end (), std::make_pair (v, -1));
        ok = it != lookup.end () && it->first == v;
        if (ok)
          corner[c] = it->second;
      }
      if (!ok)
        continue;
      for (int c = 0; c < 3; ++c)
        addSegment (corners[corner[c]], corners[corner[(c + 1) % 3]], rays, sector_max);
    }

    footprint.extent.resize (angles);
    for (int k = 0; k < angles; ++k)
    {
      const double e = std::max (sector_max[k], sector_max[(k + angles - 1) % angles]);
      // Round up so the float never cuts a vertex lying exactly on the boundary.
      footprint.extent[k] = static_cast<float> (e * (1.0 + 1e-6) + 1e-9);
    }
    return footprint;
  }
} // namespace pcl_sparse
