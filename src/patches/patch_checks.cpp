#include <pcl_sparse/patches/patch_checks.h>

#include <pcl_sparse/patches/patch_frame.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pcl_sparse
{
  namespace
  {
    /// Whether every one of \a triangles is reached from \a seed_face through adjacent ones (across manifold
    /// edges) whose normals differ by less than delta (\a cos_delta).
    bool
    reachedBySmoothSteps (const std::vector<int>& triangles, int seed_face, const MeshTopology& topology,
                          const PatchGrowthGeometry& geometry, double cos_delta)
    {
      std::vector<int> tris (triangles), stack = {seed_face};
      std::sort (tris.begin (), tris.end ());
      std::vector<char> reached (tris.size (), 0);
      reached[std::lower_bound (tris.begin (), tris.end (), seed_face) - tris.begin ()] = 1;
      std::size_t count = 1;
      while (!stack.empty ())
      {
        const int f = stack.back ();
        stack.pop_back ();
        for (int k = 0; k < 3; ++k)
        {
          const int g = topology.face_neighbors[f][k];
          if (g < 0)
            continue;
          const auto it = std::lower_bound (tris.begin (), tris.end (), g);
          if (it == tris.end () || *it != g || reached[it - tris.begin ()])
            continue;
          if (!(geometry.face_normals[f].dot (geometry.face_normals[g]) > cos_delta))
            continue;
          reached[it - tris.begin ()] = 1;
          ++count;
          stack.push_back (g);
        }
      }
      return count == tris.size ();
    }
  } // namespace

  PatchInvariantChecker::PatchInvariantChecker (const TriangleMesh& mesh, const PatchOptions& options,
                                                const std::vector<Eigen::Vector3d>& point_normals)
    : mesh_ (mesh), options_ (options)
  {
    topology_ = buildMeshTopology (mesh);
    is_split_ = splitNonManifoldVertices (mesh, topology_, split_);
    if (is_split_)
      topology_ = buildMeshTopology (split_.mesh);
    grown_mesh_ = is_split_ ? &split_.mesh : &mesh_;
    geometry_ = computePatchGrowthGeometry (*grown_mesh_, topology_,
                                            is_split_ ? valuesOnSplit (split_, point_normals) : point_normals);
  }

  std::string
  PatchInvariantChecker::check (const Patch& patch) const
  {
    std::ostringstream why;
    const int num_vertices = static_cast<int> (mesh_.vertices.size ());
    if (patch.vertices.empty () || patch.vertices[0] != patch.seed)
      return "seed is not the first vertex";
    if (patch.local.size () != patch.vertices.size ())
      return "local and vertices differ in size";
    std::vector<int> sorted = patch.vertices;
    std::sort (sorted.begin (), sorted.end ());
    if (sorted.front () < 0 || sorted.back () >= num_vertices)
      return "vertex index out of range";
    if (std::adjacent_find (sorted.begin (), sorted.end ()) != sorted.end ())
      return "repeated vertex";
    if (!(patch.radius > 0.0) || !std::isfinite (patch.radius))
      return "radius not positive";
    const Eigen::Matrix3d& R = patch.frame;
    if (!(R.transpose () * R).isApprox (Eigen::Matrix3d::Identity (), 1e-9) || !(R.determinant () > 0.0))
      return "frame not a rotation";
    const Eigen::Vector3d N = R.col (2);
    // The seed's normal as the growth saw it: a split seed may be any copy, take the first triangle's.
    Eigen::Vector3d ns = geometry_.vertex_normals[patch.seed];
    if (!patch.triangles.empty ())
    {
      const Eigen::Vector3i& t = grown_mesh_->triangles[patch.triangles[0]];
      for (int k = 0; k < 3; ++k)
        if (mesh_.triangles[patch.triangles[0]][k] == patch.seed)
          ns = geometry_.vertex_normals[t[k]];
    }
    if (patch.seed_face >= 0)
    {
      if (std::find (patch.triangles.begin (), patch.triangles.end (), patch.seed_face) == patch.triangles.end ())
        return "seed face not in the patch";
      ns = geometry_.face_normals[patch.seed_face];
    }
    if (!ns.isZero () && !(N.dot (ns) > 0.0))
      return "frame normal opposes the seed normal";
    for (std::size_t i = 0; i < patch.vertices.size (); ++i)
    {
      const Eigen::Vector3d expected = R.transpose () * (mesh_.vertices[patch.vertices[i]] - patch.origin) / patch.radius;
      if (!(patch.local[i] - expected).isZero (1e-9 * (1.0 + expected.norm ())))
        return "local coordinates wrong";
      if (std::hypot (expected.x (), expected.y ()) > 1.0 + 1e-9)
        return "vertex outside the unit disk";
    }
    const double cos_delta = std::cos (options_.delta), cos_cone = std::cos (options_.cone_angle);
    double area = 0.0, projected = 0.0;
    const std::size_t grown = patch.triangles.size () - std::min (patch.triangles.size (), patch.completed_triangles);
    for (std::size_t i = 0; i < patch.triangles.size (); ++i)
    {
      const int f = patch.triangles[i];
      const Eigen::Vector3i &t = mesh_.triangles[f], &tg = grown_mesh_->triangles[f];
      for (int k = 0; k < 3; ++k)
        if (!std::binary_search (sorted.begin (), sorted.end (), t[k]))
          return "triangle " + std::to_string (f) + " has a corner outside the patch";
      const Eigen::Vector3d& nt = geometry_.face_normals[f];
      const double a = geometry_.face_areas[f];
      if (!(a > 0.0))
        return "degenerate triangle " + std::to_string (f);
      if (!(projectedSignedArea (mesh_, f, N) > 0.0))
        return "triangle " + std::to_string (f) + " flips on the frame's tangent plane";
      if (!(nt.dot (ns) > 0.0))
        return "triangle " + std::to_string (f) + " flips on the seed's tangent plane";
      if (!(nt.dot (ns) > cos_cone))
        return "triangle " + std::to_string (f) + " outside the normal cone";
      // Face-grown: smooth variation is checked below, between adjacent faces. Face completion: none.
      bool smooth = patch.seed_face >= 0 || i >= grown;
      for (int k = 0; k < 3; ++k)
        smooth = smooth || nt.dot (geometry_.vertex_normals[tg[k]]) > cos_delta;
      if (!smooth)
        return "triangle " + std::to_string (f) + " fails smooth variation";
      if (i >= grown)
        continue;  // nor the area bound
      area += a;
      projected += a * nt.dot (ns);
    }
    // Face-grown: every triangle (of growth) is reached from the seed face by smooth steps.
    if (patch.seed_face >= 0 &&
        !reachedBySmoothSteps (std::vector<int> (patch.triangles.begin (), patch.triangles.begin () + grown),
                               patch.seed_face, topology_, geometry_, cos_delta))
      return "face-grown patch: a triangle is not reached from the seed face by smooth steps";
    if (options_.pairwise_cone)
    {
      // No face with its three corners among the patch's vertices faces away from n_s.
      for (int v : patch.vertices)
        for (int f : topology_.facesOf (v))
        {
          const Eigen::Vector3i& t = mesh_.triangles[f];
          bool all = true;
          for (int k = 0; k < 3; ++k)
            all = all && std::binary_search (sorted.begin (), sorted.end (), t[k]);
          if (all && geometry_.face_areas[f] > 0.0 && geometry_.face_normals[f].dot (ns) < 0.0)
            return "the vertices fold: face " + std::to_string (f) + " has its corners in the patch and faces away";
        }
      // Only a pair with a triangle further than half the cone from n_s can fail.
      const double cos_half = std::cos (0.5 * options_.cone_angle);
      for (int f : patch.triangles)
        if (geometry_.face_normals[f].dot (ns) < cos_half)
          for (int g : patch.triangles)
            if (!(geometry_.face_normals[f].dot (geometry_.face_normals[g]) > cos_cone))
              return "triangles " + std::to_string (f) + " and " + std::to_string (g) + " differ by more than the cone angle";
    }
    if (!(area <= options_.rho * geometry_.total_area * (1.0 + 1e-12) || area <= options_.eta * projected * (1.0 + 1e-12)))
    {
      why << "area condition fails: A_p / A = " << area / geometry_.total_area << ", A_p / A_proj = " << area / projected;
      return why.str ();
    }
    return std::string ();
  }

  std::vector<int>
  PatchInvariantChecker::uncoveredVertices (const std::vector<Patch>& patches) const
  {
    std::vector<char> in_patch (mesh_.vertices.size (), 0), referenced (mesh_.vertices.size (), 0);
    for (const auto& t : mesh_.triangles)
      for (int k = 0; k < 3; ++k)
        referenced[t[k]] = 1;
    for (const Patch& p : patches)
      for (int v : p.vertices)
        in_patch[v] = 1;
    std::vector<int> uncovered;
    for (std::size_t v = 0; v < in_patch.size (); ++v)
      if (referenced[v] && !in_patch[v])
        uncovered.push_back (static_cast<int> (v));
    return uncovered;
  }
} // namespace pcl_sparse
