#include <pcl_sparse/patches/face_completion.h>

#include <pcl_sparse/geometry/quadric_fit.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace pcl_sparse
{
  namespace
  {
    /// As in growth (patch_growth.cpp): a face nearly perpendicular to the seed's plane could flip by rounding.
    constexpr double kMinProjectionCosine = 1e-6;

    /// A face projected on a patch's seed plane, counter-clockwise, with its bounding box.
    struct ProjectedFace
    {
      Eigen::Vector2d p[3];
      Eigen::Vector2d lo, hi;
    };

    double
    cross2 (const Eigen::Vector2d& a, const Eigen::Vector2d& b)
    {
      return a.x () * b.y () - a.y () * b.x ();
    }

    /// Whether one edge line of \a s leaves all of \a t on its outer side (within \a tolerance, a length).
    bool
    edgeSeparates (const ProjectedFace& s, const ProjectedFace& t, double tolerance)
    {
      for (int i = 0; i < 3; ++i)
      {
        const Eigen::Vector2d& a = s.p[i];
        const Eigen::Vector2d e = s.p[(i + 1) % 3] - a;
        const double length = e.norm ();
        if (!(length > 0.0))
          continue;
        bool outside = true;
        for (int k = 0; k < 3 && outside; ++k)
          outside = cross2 (e, t.p[k] - a) <= tolerance * length;
        if (outside)
          return true;
      }
      return false;
    }

    /// Whether the interiors of two counter-clockwise projected faces overlap (separating axis test over
    /// their edges, exact for convex polygons). Faces sharing an edge or a corner without overlapping pass.
    bool
    interiorsOverlap (const ProjectedFace& s, const ProjectedFace& t)
    {
      if ((s.hi.array () < t.lo.array ()).any () || (t.hi.array () < s.lo.array ()).any ())
        return false;
      const double size = std::max ((s.hi - s.lo).maxCoeff (), (t.hi - t.lo).maxCoeff ());
      const double tolerance = 1e-9 * size;
      return !edgeSeparates (s, t, tolerance) && !edgeSeparates (t, s, tolerance);
    }

    /// A patch's plane (the seed's tangent plane) and its triangles projected there, built on first use.
    struct PatchPlane
    {
      bool built = false;
      Eigen::Vector3d origin, t1, t2;
      std::vector<ProjectedFace> faces;

      PatchPlane () = default;
      PatchPlane (const TriangleMesh& mesh, const Patch& patch, const Eigen::Vector3d& seed_normal)
        : built (true), origin (mesh.vertices[patch.seed])
      {
        const Eigen::Matrix3d frame = frameAroundNormal (seed_normal);
        t1 = frame.col (0);
        t2 = frame.col (1);
        faces.reserve (patch.triangles.size ());
        for (int g : patch.triangles)
          faces.push_back (project (mesh, g));
      }

      ProjectedFace
      project (const TriangleMesh& mesh, int f) const
      {
        ProjectedFace q;
        for (int k = 0; k < 3; ++k)
        {
          const Eigen::Vector3d d = mesh.vertices[mesh.triangles[f][k]] - origin;
          q.p[k] = Eigen::Vector2d (t1.dot (d), t2.dot (d));
        }
        q.lo = q.p[0].cwiseMin (q.p[1]).cwiseMin (q.p[2]);
        q.hi = q.p[0].cwiseMax (q.p[1]).cwiseMax (q.p[2]);
        return q;
      }
    };

    /// The normal a patch grew around: the seed face's for coverage patches, else the seed's vertex normal.
    Eigen::Vector3d
    seedNormalOf (const Patch& patch, const PatchGrowthGeometry& geometry)
    {
      return patch.seed_face >= 0 ? geometry.face_normals[patch.seed_face] : geometry.vertex_normals[patch.seed];
    }

    /// Faces left in no patch: the patches at their corners (as grown) keep their footprints' full reach,
    /// which is what covers such a face (PatchCode footprint, clip_footprints_at_border).
    void
    markPatchesBesideUncoveredFaces (const TriangleMesh& mesh, const std::vector<int>& uncovered,
                                     const std::vector<int>& vertex_begin, const std::vector<int>& vertex_holders,
                                     std::vector<Patch>& patches)
    {
      for (int f : uncovered)
        for (int k = 0; k < 3; ++k)
          for (int i = vertex_begin[mesh.triangles[f][k]]; i < vertex_begin[mesh.triangles[f][k] + 1]; ++i)
            patches[vertex_holders[i]].beside_uncovered_face = true;
    }

    /// Offsets and lists of the patches holding each vertex (\a faces false) or face (true), ascending.
    void
    invertMembership (const std::vector<Patch>& patches, std::size_t size, bool faces, std::vector<int>& offsets,
                      std::vector<int>& lists)
    {
      offsets.assign (size + 1, 0);
      for (const Patch& p : patches)
        for (int v : faces ? p.triangles : p.vertices)
          ++offsets[v + 1];
      std::partial_sum (offsets.begin (), offsets.end (), offsets.begin ());
      lists.resize (offsets.back ());
      std::vector<int> cursor (offsets.begin (), offsets.end () - 1);
      for (std::size_t i = 0; i < patches.size (); ++i)
        for (int v : faces ? patches[i].triangles : patches[i].vertices)
          lists[cursor[v]++] = static_cast<int> (i);
    }

    /// Whether patch \a p holds \a key: \a p is in the ascending range [offsets[key], offsets[key + 1]) of
    /// \a lists (as grown), or \a key is in \a added (what completion gave \a p, ascending).
    bool
    holds (const std::vector<int>& offsets, const std::vector<int>& lists, int key, int p, const std::vector<int>& added)
    {
      return std::binary_search (lists.begin () + offsets[key], lists.begin () + offsets[key + 1], p) ||
             std::binary_search (added.begin (), added.end (), key);
    }

    void
    insertSorted (std::vector<int>& list, int value)
    {
      list.insert (std::upper_bound (list.begin (), list.end (), value), value);
    }
  } // namespace

  FaceCompletionResult
  completePatchFaces (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                      const PatchOptions& options, std::vector<Patch>& patches, const std::vector<std::uint8_t>& must_cover)
  {
    FaceCompletionResult result;
    const int num_faces = static_cast<int> (mesh.triangles.size ());
    const int num_patches = static_cast<int> (patches.size ());
    const double cos_cone = std::cos (options.cone_angle);
    const double cos_delta = std::cos (options.delta);
    const auto& flip_normals = geometry.geometric_normals.empty () ? geometry.face_normals : geometry.geometric_normals;

    std::vector<std::uint8_t> in_patch (num_faces, 0);
    for (const Patch& p : patches)
      for (int f : p.triangles)
        in_patch[f] = 1;

    // Patches holding each vertex and face as grown (so the candidates and corner counts do not depend on
    // the completion order), plus what completion added to each patch (few: sorted vectors).
    std::vector<int> vertex_begin, vertex_holders, face_begin, face_holders;
    invertMembership (patches, mesh.vertices.size (), false, vertex_begin, vertex_holders);
    invertMembership (patches, mesh.triangles.size (), true, face_begin, face_holders);
    std::vector<std::vector<int>> added_vertices (num_patches), added_faces (num_patches);
    auto holdsVertex = [&] (int p, int v) { return holds (vertex_begin, vertex_holders, v, p, added_vertices[p]); };
    auto holdsFace = [&] (int p, int g) { return holds (face_begin, face_holders, g, p, added_faces[p]); };
    // Smooth variation as growth measures it: within delta of the vertex normal of a corner the patch
    // holds (grow), or of a patch triangle across an edge (growFromFace).
    auto smoothIn = [&] (int p, int f) {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const Eigen::Vector3d& n = geometry.face_normals[f];
      for (int k = 0; k < 3; ++k)
        if (holdsVertex (p, t[k]) && n.dot (geometry.vertex_normals[t[k]]) > cos_delta)
          return true;
      for (int k = 0; k < 3; ++k)
      {
        const int g = topology.face_neighbors[f][k];
        if (g >= 0 && holdsFace (p, g) && n.dot (geometry.face_normals[g]) > cos_delta)
          return true;
      }
      return false;
    };

    std::vector<PatchPlane> planes (num_patches);
    auto planeOf = [&] (int p) -> PatchPlane& {
      if (!planes[p].built)
        planes[p] = PatchPlane (mesh, patches[p], seedNormalOf (patches[p], geometry));
      return planes[p];
    };

    std::vector<int> candidates;
    std::vector<std::pair<std::tuple<bool, int, double>, int>> ranked;
    for (int f = 0; f < num_faces; ++f)
    {
      if (in_patch[f] || !(geometry.face_areas[f] > 0.0))
        continue;
      const Eigen::Vector3i& t = mesh.triangles[f];
      if (!must_cover.empty () && !must_cover[t[0]] && !must_cover[t[1]] && !must_cover[t[2]])
        continue;
      ++result.faces_in_no_patch;
      candidates.clear ();
      for (int k = 0; k < 3; ++k)
        candidates.insert (candidates.end (), vertex_holders.begin () + vertex_begin[t[k]],
                           vertex_holders.begin () + vertex_begin[t[k] + 1]);
      std::sort (candidates.begin (), candidates.end ());
      candidates.erase (std::unique (candidates.begin (), candidates.end ()), candidates.end ());

      // Best first: smooth variation held, then most corners held, then the closest seed normal, then the
      // lowest index. Only within the cone and without a flip on the seed's plane.
      ranked.clear ();
      for (int p : candidates)
      {
        const Eigen::Vector3d ns = seedNormalOf (patches[p], geometry);
        const double c = geometry.face_normals[f].dot (ns);
        if (ns.isZero () || !(c > cos_cone && c > kMinProjectionCosine && flip_normals[f].dot (ns) > kMinProjectionCosine))
          continue;
        int corners = 0;
        for (int k = 0; k < 3; ++k)
          corners += holdsVertex (p, t[k]);
        ranked.push_back ({{!smoothIn (p, f), -corners, -c}, p});
      }
      std::sort (ranked.begin (), ranked.end ());
      bool done = false;
      for (const auto& entry : ranked)
      {
        const int p = entry.second;
        PatchPlane& plane = planeOf (p);
        const ProjectedFace q = plane.project (mesh, f);
        if (!(cross2 (q.p[1] - q.p[0], q.p[2] - q.p[0]) > 0.0))
          continue;
        if (std::any_of (plane.faces.begin (), plane.faces.end (),
                         [&] (const ProjectedFace& other) { return interiorsOverlap (q, other); }))
          continue;  // it would fold over the patch's own triangles: no longer a height field
        // As growth with the pairwise cone: no two patch triangles further apart than the cone, no fold.
        if (options.pairwise_cone &&
            (std::any_of (patches[p].triangles.begin (), patches[p].triangles.end (),
                          [&] (int g) { return !(geometry.face_normals[f].dot (geometry.face_normals[g]) > cos_cone); }) ||
             addingFaceFolds (mesh, topology, geometry, seedNormalOf (patches[p], geometry), f,
                              [&] (int v) { return holdsVertex (p, v); })))
          continue;
        plane.faces.push_back (q);
        Patch& patch = patches[p];
        patch.triangles.push_back (f);
        ++patch.completed_triangles;
        insertSorted (added_faces[p], f);
        for (int k = 0; k < 3; ++k)
          if (!holdsVertex (p, t[k]))
          {
            patch.vertices.push_back (t[k]);
            insertSorted (added_vertices[p], t[k]);
          }
        in_patch[f] = 1;
        ++result.completed;
        result.without_smooth_variation += std::get<0> (entry.first);
        done = true;
        break;
      }
      if (!done)
        result.uncovered.push_back (f);
    }
    markPatchesBesideUncoveredFaces (mesh, result.uncovered, vertex_begin, vertex_holders, patches);
    return result;
  }

  std::vector<int>
  facesInNoPatch (const TriangleMesh& mesh, const std::vector<Patch>& patches)
  {
    std::vector<std::uint8_t> in_patch (mesh.triangles.size (), 0);
    for (const Patch& p : patches)
      for (int f : p.triangles)
        in_patch[f] = 1;
    std::vector<int> faces;
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const double area =
          (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross (mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm ();
      if (!in_patch[f] && area > 0.0)
        faces.push_back (static_cast<int> (f));
    }
    return faces;
  }
} // namespace pcl_sparse
