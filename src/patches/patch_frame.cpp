#include <pcl_sparse/patches/patch_frame.h>

#include <pcl_sparse/geometry/quadric_fit.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

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
    /// Smallest cosine between \a normal and a patch triangle's normal (projected area over area): the
    /// steepest triangle; -infinity when a triangle flips or projects to nothing.
    double
    steepestTriangleCosine (const TriangleMesh& mesh, const Patch& patch, const Eigen::Vector3d& normal)
    {
      double steepest = 1.0;
      for (int f : patch.triangles)
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        const Eigen::Vector3d& a = mesh.vertices[t[0]];
        const Eigen::Vector3d doubled = (mesh.vertices[t[1]] - a).cross (mesh.vertices[t[2]] - a);
        const double projected = doubled.dot (normal), area = doubled.norm ();
        if (!(projected > 0.0))
          return -std::numeric_limits<double>::infinity ();
        steepest = std::min (steepest, projected / area);
      }
      return steepest;
    }
  } // namespace

  PatchFrameKind
  computePatchFrame (const TriangleMesh& mesh, const Eigen::Vector3d& seed_normal, double radius_guard, Patch& patch,
                     double steep_angle)
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
        // The jet's normal must not make the steepest triangle steeper than the seed's plane does, beyond
        // steep_angle (72 degrees on meshes): on a strip of long thin triangles (two rows of collinear vertices) the jet is
        // underdetermined across the strip and its normal can lie in the strip's plane, 89.9 degrees from
        // every triangle, which no height field codes (blade: vertex errors of 0.8 % of the diagonal).
        const double jet_steepest = steepestTriangleCosine (mesh, patch, jet.normal);
        const double steep_cosine = steep_angle > 0.0 ? std::cos (steep_angle) : 0.0;
        if (jet.normal.dot (n0) > 0.0 && jet_steepest > 0.0 &&
            jet_steepest >= std::min (steep_cosine, steepestTriangleCosine (mesh, patch, n0)))
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
