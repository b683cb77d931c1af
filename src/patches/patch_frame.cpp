#include <pcl_sparse/patches/patch_frame.h>

#include <pcl_sparse/geometry/quadric_fit.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  double
  projectedSignedArea (const TriangleMesh& mesh, int f, const Eigen::Vector3d& normal)
  {
    const Eigen::Vector3i& t = mesh.triangles[f];
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    return 0.5 * (mesh.vertices[t[1]] - a).cross (mesh.vertices[t[2]] - a).dot (normal);
  }

  namespace
  {
    bool
    noTriangleFlips (const TriangleMesh& mesh, const Patch& patch, const Eigen::Vector3d& normal)
    {
      for (int f : patch.triangles)
        if (!(projectedSignedArea (mesh, f, normal) > 0.0))
          return false;
      return true;
    }
  } // namespace

  PatchFrameKind
  computePatchFrame (const TriangleMesh& mesh, const Eigen::Vector3d& seed_normal, double radius_guard, Patch& patch)
  {
    const Eigen::Vector3d n0 = seed_normal.isZero () || !seed_normal.allFinite ()
                                 ? Eigen::Vector3d::UnitZ ()
                                 : Eigen::Vector3d (seed_normal.normalized ());
    PatchFrameKind kind = PatchFrameKind::NormalOnly;
    Eigen::Matrix3d R = frameAroundNormal (n0);
    if (patch.vertices.size () >= 6)
    {
      std::vector<Eigen::Vector3d> points;
      points.reserve (patch.vertices.size ());
      for (int v : patch.vertices)
        points.push_back (mesh.vertices[v]);
      MongeJet jet;
      if (fitMongeJet (points, patch.origin, n0, jet) && jet.frame ().allFinite ())
      {
        if (jet.normal.dot (n0) > 0.0 && noTriangleFlips (mesh, patch, jet.normal))
        {
          R = jet.frame ();
          kind = PatchFrameKind::Jet;
        }
        else
        {
          // Keep the seed's plane (growth guarantees no flip there) and the jet's max direction in it.
          const Eigen::Vector3d t1 = jet.d1 - jet.d1.dot (n0) * n0;
          if (t1.norm () > 1e-6)
          {
            R.col (0) = t1.normalized ();
            R.col (1) = n0.cross (R.col (0));
            R.col (2) = n0;
          }
          kind = PatchFrameKind::SeedNormal;
        }
      }
    }
    patch.frame = R;
    const Eigen::Vector3d N = R.col (2);

    double radius = 0.0;
    for (int v : patch.vertices)
    {
      const Eigen::Vector3d d = mesh.vertices[v] - patch.origin;
      radius = std::max (radius, (d - d.dot (N) * N).norm ());
    }
    if (!(radius > 0.0) || !std::isfinite (radius))
      radius = radius_guard > 0.0 && std::isfinite (radius_guard) ? radius_guard : 1.0;
    patch.radius = radius;

    patch.local.resize (patch.vertices.size ());
    for (std::size_t i = 0; i < patch.vertices.size (); ++i)
      patch.local[i] = patch.toLocal (mesh.vertices[patch.vertices[i]]);
    return kind;
  }
} // namespace pcl_sparse
