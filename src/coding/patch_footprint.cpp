#include <pcl_sparse/coding/patch_footprint.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>
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

    /// Raises sector maxima with the points of segment [a, b].
    void
    addSegment (const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<Eigen::Vector2d>& rays,
                std::vector<double>& sector_max)
    {
      const int angles = static_cast<int> (rays.size ());
      const double ra = a.norm (), rb = b.norm ();
      if (ra > 0.0)
        sector_max[sectorOf (a, angles)] = std::max (sector_max[sectorOf (a, angles)], ra);
      if (rb > 0.0)
        sector_max[sectorOf (b, angles)] = std::max (sector_max[sectorOf (b, angles)], rb);
      // Crossings of the sector rays: a point on ray k belongs to sectors k - 1 and k.
      for (int k = 0; k < angles; ++k)
      {
        const double ca = cross2 (rays[k], a), cb = cross2 (rays[k], b);
        if ((ca > 0.0 && cb > 0.0) || (ca < 0.0 && cb < 0.0) || ca == cb)
          continue;
        const double t = ca / (ca - cb);
        const Eigen::Vector2d p = a + t * (b - a);
        const double r = rays[k].dot (p);
        if (r <= 0.0)
          continue;
        sector_max[k] = std::max (sector_max[k], r);
        sector_max[(k + angles - 1) % angles] = std::max (sector_max[(k + angles - 1) % angles], r);
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
    std::unordered_map<int, int> local_index;
    local_index.reserve (patch.vertices.size () * 2);
    for (std::size_t i = 0; i < patch.vertices.size () && i < patch.local.size (); ++i)
    {
      local_index.emplace (patch.vertices[i], static_cast<int> (i));
      const Eigen::Vector2d p = patch.local[i].head<2> ();
      if (p.norm () > 0.0)
        sector_max[sectorOf (p, angles)] = std::max (sector_max[sectorOf (p, angles)], p.norm ());
    }
    for (int f : patch.triangles)
    {
      if (f < 0 || static_cast<std::size_t> (f) >= mesh.triangles.size ())
        continue;
      Eigen::Vector2d corner[3];
      bool ok = true;
      for (int c = 0; c < 3 && ok; ++c)
      {
        const auto it = local_index.find (mesh.triangles[f][c]);
        ok = it != local_index.end ();
        if (ok)
          corner[c] = patch.local[it->second].head<2> ();
      }
      if (!ok)
        continue;
      for (int c = 0; c < 3; ++c)
        addSegment (corner[c], corner[(c + 1) % 3], rays, sector_max);
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
