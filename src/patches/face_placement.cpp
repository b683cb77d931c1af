#include <pcl_sparse/patches/face_placement.h>

#include <pcl_sparse/common/huge_pages.h>
#include <pcl_sparse/geometry/quadric_fit.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace pcl_sparse
{
  namespace
  {
    /// As in growth (patch_growth.cpp): a face nearly perpendicular to the seed's plane could flip by rounding.
    constexpr double kMinProjectionCosine = 1e-6;

    /// Placements a plane's run has room for before it moves (a patch takes a few faces at most, mostly).
    constexpr std::size_t kPlaneSlack = 16;

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

    /// A patch's plane (the seed's tangent plane) and its triangles projected there, built on first use. The
    /// projected triangles are a run of a ProjectedFacePool's storage with room for a few placements.
    struct PatchPlane
    {
      bool built = false;
      Eigen::Vector3d origin, t1, t2;
      ProjectedFace* faces = nullptr;
      std::size_t size = 0, capacity = 0;

      const ProjectedFace* begin () const { return faces; }
      const ProjectedFace* end () const { return faces + size; }

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

    /// Storage for the planes' projected triangles, handed out in runs from chunks that double in size up to
    /// about 5 MB and are never moved. With one vector per plane, reallocated at its first placement,
    /// office1.pcd's completion and merging (10.5k planes, 750k triangles) spent more time in page faults and
    /// copies than in projecting: its encoding took 2.29 s best of 5, 2.22 with room for placements in each
    /// vector, 2.12 with the pool (2 threads, same model).
    class ProjectedFacePool
    {
    public:
      /// Room for \a n faces, uninitialised.
      ProjectedFace*
      allocate (std::size_t n)
      {
        if (chunks_.empty () || used_ + n > chunk_size_)
        {
          chunk_size_ = std::max (n, chunks_.empty () ? kFirstChunk : std::min (2 * chunk_size_, kLargestChunk));
          chunks_.emplace_back (new ProjectedFace[chunk_size_]);
          adviseHugePages (chunks_.back ().get (), chunk_size_ * sizeof (ProjectedFace));
          used_ = 0;
        }
        ProjectedFace* run = chunks_.back ().get () + used_;
        used_ += n;
        return run;
      }

    private:
      static constexpr std::size_t kFirstChunk = 4096;
      static constexpr std::size_t kLargestChunk = 65536;
      std::vector<std::unique_ptr<ProjectedFace[]>> chunks_;
      std::size_t chunk_size_ = 0, used_ = 0;
    };

    /// The normal a patch grew around: the seed face's for coverage patches, else the seed's vertex normal.
    Eigen::Vector3d
    seedNormalOf (const Patch& patch, const PatchGrowthGeometry& geometry)
    {
      return patch.seed_face >= 0 ? geometry.face_normals[patch.seed_face] : geometry.vertex_normals[patch.seed];
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

    void
    insertSorted (std::vector<int>& list, int value)
    {
      list.insert (std::upper_bound (list.begin (), list.end (), value), value);
    }

    void
    eraseSorted (std::vector<int>& list, int value)
    {
      const auto it = std::lower_bound (list.begin (), list.end (), value);
      if (it != list.end () && *it == value)
        list.erase (it);
    }
  } // namespace

  struct FacePlacer::Impl
  {
    /// One placement: face \a face went to \a patch, whose last \a num_vertices vertices it brought.
    struct Record
    {
      int patch, face, num_vertices;
    };

    const TriangleMesh& mesh;
    const MeshTopology& topology;
    const PatchGrowthGeometry& geometry;
    const PatchOptions& options;
    std::vector<Patch>& patches;
    const std::vector<Eigen::Vector3d>& flip_normals;
    const double cos_cone, cos_delta;
    // Patches holding each vertex and face as built, plus what placements added to each patch (few: sorted
    // vectors) and, per vertex, the patches placements gave it.
    std::vector<int> vertex_begin, vertex_holders, face_begin, face_holders;
    std::vector<std::vector<int>> added_vertices, added_faces;
    std::unordered_map<int, std::vector<int>> added_vertex_holders;
    std::vector<std::uint8_t> removed;
    std::vector<PatchPlane> planes;
    ProjectedFacePool pool;
    std::vector<Record> log;
    // Scratch of place ().
    std::vector<int> candidates;
    std::vector<std::pair<std::tuple<bool, int, double>, int>> ranked;

    Impl (const TriangleMesh& mesh_, const MeshTopology& topology_, const PatchGrowthGeometry& geometry_,
          const PatchOptions& options_, std::vector<Patch>& patches_)
      : mesh (mesh_), topology (topology_), geometry (geometry_), options (options_), patches (patches_),
        flip_normals (geometry_.geometric_normals.empty () ? geometry_.face_normals : geometry_.geometric_normals),
        cos_cone (std::cos (options_.cone_angle)), cos_delta (std::cos (options_.delta)),
        added_vertices (patches_.size ()), added_faces (patches_.size ()), removed (patches_.size (), 0),
        planes (patches_.size ())
    {
      invertMembership (patches, mesh.vertices.size (), false, vertex_begin, vertex_holders);
      invertMembership (patches, mesh.triangles.size (), true, face_begin, face_holders);
    }

    static bool
    holds (const std::vector<int>& offsets, const std::vector<int>& lists, int key, int p, const std::vector<int>& added)
    {
      return std::binary_search (lists.begin () + offsets[key], lists.begin () + offsets[key + 1], p) ||
             std::binary_search (added.begin (), added.end (), key);
    }

    bool holdsVertex (int p, int v) const { return holds (vertex_begin, vertex_holders, v, p, added_vertices[p]); }
    bool holdsFace (int p, int g) const { return holds (face_begin, face_holders, g, p, added_faces[p]); }

    /// Smooth variation as growth measures it: within delta of the vertex normal of a corner the patch
    /// holds (grow), or of a patch triangle across an edge (growFromFace).
    bool
    smoothIn (int p, int f) const
    {
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
    }

    PatchPlane&
    planeOf (int p)
    {
      PatchPlane& plane = planes[p];
      if (plane.built)
        return plane;
      const Patch& patch = patches[p];
      const Eigen::Matrix3d frame = frameAroundNormal (seedNormalOf (patch, geometry));
      plane.built = true;
      plane.origin = mesh.vertices[patch.seed];
      plane.t1 = frame.col (0);
      plane.t2 = frame.col (1);
      plane.size = patch.triangles.size ();
      plane.capacity = plane.size + kPlaneSlack;
      plane.faces = pool.allocate (plane.capacity);
      for (std::size_t i = 0; i < plane.size; ++i)
        plane.faces[i] = plane.project (mesh, patch.triangles[i]);
      return plane;
    }

    /// Whether patch \a p can take face \a f, projected \a q on its plane (the file comment's conditions
    /// besides the cone and the flip, which ranking checked).
    bool
    canTake (int p, int f, const ProjectedFace& q)
    {
      if (!(cross2 (q.p[1] - q.p[0], q.p[2] - q.p[0]) > 0.0))
        return false;
      const PatchPlane& plane = planes[p];
      if (std::any_of (plane.begin (), plane.end (),
                       [&] (const ProjectedFace& other) { return interiorsOverlap (q, other); }))
        return false;  // it would fold over the patch's own triangles: no longer a height field
      // As growth with the pairwise cone: no two patch triangles further apart than the cone, no fold.
      if (!options.pairwise_cone)
        return true;
      const std::vector<int>& triangles = patches[p].triangles;
      return std::all_of (triangles.begin (), triangles.end (),
                          [&] (int g) { return geometry.face_normals[f].dot (geometry.face_normals[g]) > cos_cone; }) &&
             !addingFaceFolds (mesh, topology, geometry, seedNormalOf (patches[p], geometry), f,
                               [&] (int v) { return holdsVertex (p, v); });
    }

    void
    add (int p, int f, const ProjectedFace& q)
    {
      PatchPlane& plane = planes[p];
      if (plane.size == plane.capacity)  // a new run twice as long: the old one is left unused
      {
        ProjectedFace* faces = pool.allocate (2 * plane.capacity);
        std::copy (plane.begin (), plane.end (), faces);
        plane.faces = faces;
        plane.capacity *= 2;
      }
      plane.faces[plane.size++] = q;
      Patch& patch = patches[p];
      patch.triangles.push_back (f);
      ++patch.completed_triangles;
      insertSorted (added_faces[p], f);
      int num_vertices = 0;
      for (int k = 0; k < 3; ++k)
      {
        const int v = mesh.triangles[f][k];
        if (holdsVertex (p, v))
          continue;
        patch.vertices.push_back (v);
        insertSorted (added_vertices[p], v);
        added_vertex_holders[v].push_back (p);
        ++num_vertices;
      }
      log.push_back ({p, f, num_vertices});
    }

    void
    undo (const Record& r)
    {
      Patch& patch = patches[r.patch];
      for (int i = 0; i < r.num_vertices; ++i)
      {
        const int v = patch.vertices.back ();
        patch.vertices.pop_back ();
        eraseSorted (added_vertices[r.patch], v);
        std::vector<int>& holders = added_vertex_holders[v];
        holders.erase (std::find (holders.begin (), holders.end (), r.patch));
        if (holders.empty ())
          added_vertex_holders.erase (v);
      }
      patch.triangles.pop_back ();
      --patch.completed_triangles;
      eraseSorted (added_faces[r.patch], r.face);
      --planes[r.patch].size;
    }

    Placement
    place (int f, bool with_added)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      candidates.clear ();
      for (int k = 0; k < 3; ++k)
      {
        candidates.insert (candidates.end (), vertex_holders.begin () + vertex_begin[t[k]],
                           vertex_holders.begin () + vertex_begin[t[k] + 1]);
        const auto added = with_added ? added_vertex_holders.find (t[k]) : added_vertex_holders.end ();
        if (added != added_vertex_holders.end ())
          candidates.insert (candidates.end (), added->second.begin (), added->second.end ());
      }
      std::sort (candidates.begin (), candidates.end ());
      candidates.erase (std::unique (candidates.begin (), candidates.end ()), candidates.end ());

      // Best first: smooth variation held, then most corners held, then the closest seed normal, then the
      // lowest index. Only within the cone and without a flip on the seed's plane.
      ranked.clear ();
      for (int p : candidates)
      {
        if (removed[p] || holdsFace (p, f))
          continue;
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
      for (const auto& entry : ranked)
      {
        const int p = entry.second;
        const ProjectedFace q = planeOf (p).project (mesh, f);
        if (!canTake (p, f, q))
          continue;
        add (p, f, q);
        return {p, !std::get<0> (entry.first), log.back ().num_vertices};
      }
      return {};
    }
  };

  FacePlacer::FacePlacer (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                          const PatchOptions& options, std::vector<Patch>& patches)
    : impl_ (new Impl (mesh, topology, geometry, options, patches))
  {
  }

  FacePlacer::~FacePlacer () = default;

  FacePlacer::Placement
  FacePlacer::place (int f, bool with_added)
  {
    return impl_->place (f, with_added);
  }

  void
  FacePlacer::setRemoved (int p, bool removed)
  {
    impl_->removed[p] = removed ? 1 : 0;
  }

  std::size_t
  FacePlacer::mark () const
  {
    return impl_->log.size ();
  }

  void
  FacePlacer::rollback (std::size_t mark)
  {
    while (impl_->log.size () > mark)
    {
      impl_->undo (impl_->log.back ());
      impl_->log.pop_back ();
    }
  }

  std::vector<int>
  FacePlacer::holdersOf (int v) const
  {
    return std::vector<int> (impl_->vertex_holders.begin () + impl_->vertex_begin[v],
                             impl_->vertex_holders.begin () + impl_->vertex_begin[v + 1]);
  }
} // namespace pcl_sparse
