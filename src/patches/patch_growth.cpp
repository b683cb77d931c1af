#include <pcl_sparse/patches/patch_growth.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/thread_count.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace pcl_sparse
{
  namespace
  {
    /// A triangle nearly perpendicular to the seed's tangent plane projects to a sliver whose orientation
    /// rounding could flip: such triangles are refused (n_t . n_s must exceed this).
    constexpr double kMinProjectionCosine = 1e-6;

    /// Min-heap order on (distance, vertex): ties by vertex index, so growth is deterministic.
    struct HeapGreater
    {
      bool operator() (const std::pair<double, int>& a, const std::pair<double, int>& b) const
      {
        return a.first != b.first ? a.first > b.first : a.second > b.second;
      }
    };
  } // namespace

  PatchGrowthGeometry
  computePatchGrowthGeometry (const TriangleMesh& mesh, const MeshTopology& topology,
                              const std::vector<Eigen::Vector3d>& point_normals, int num_threads)
  {
    PatchGrowthGeometry g;
    // The caller's thread count, not all: with -threads 1 an idle second thread spin-waited in the OpenMP
    // pool through the rest of the encode (a quarter of the CPU time of a small mesh).
    const int threads = resolveThreadCount (num_threads);
    const int num_faces = static_cast<int> (mesh.triangles.size ());
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    if (!point_normals.empty () && point_normals.size () != mesh.vertices.size ())
      throw Error ("computePatchGrowthGeometry: " + std::to_string (point_normals.size ()) + " point normals for " +
                   std::to_string (mesh.vertices.size ()) + " vertices");
    const bool given = !point_normals.empty ();
    g.face_normals.resize (num_faces);
    g.face_areas.resize (num_faces);
    g.geometric_normals.resize (given ? num_faces : 0);
    std::vector<Eigen::Vector3d> crosses (num_faces);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int f = 0; f < num_faces; ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const Eigen::Vector3d& a = mesh.vertices[t[0]];
      Eigen::Vector3d c = (mesh.vertices[t[1]] - a).cross (mesh.vertices[t[2]] - a);
      if (!c.allFinite ())
        c.setZero ();
      crosses[f] = c;
      const double n = c.norm ();
      g.face_areas[f] = 0.5 * n;
      g.face_normals[f] = n > 0.0 ? Eigen::Vector3d (c / n) : Eigen::Vector3d::Zero ();
      if (given)
        g.geometric_normals[f] = g.face_normals[f];
      if (given && n > 0.0)
      {
        const Eigen::Vector3d sum = point_normals[t[0]] + point_normals[t[1]] + point_normals[t[2]];
        const double s = sum.norm ();
        if (s > 0.5)  // corners roughly agree (three unit normals; zero ones count as missing)
          g.face_normals[f] = sum / s;
      }
    }
    g.vertex_normals.resize (num_vertices);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int v = 0; v < num_vertices; ++v)
    {
      if (given && point_normals[v].squaredNorm () > 0.25)
      {
        g.vertex_normals[v] = point_normals[v].normalized ();
        continue;
      }
      Eigen::Vector3d sum = Eigen::Vector3d::Zero ();
      for (int f : topology.facesOf (v))
        sum += crosses[f];
      const double n = sum.norm ();
      g.vertex_normals[v] = n > 0.0 ? Eigen::Vector3d (sum / n) : Eigen::Vector3d::Zero ();
    }
    g.edge_lengths = computeEdgeLengths (mesh, topology, num_threads);
    // Sequential sum: the total must not depend on the thread count.
    for (double a : g.face_areas)
      g.total_area += a;
    return g;
  }

  PatchGrower::PatchGrower (const TriangleMesh& mesh, const MeshTopology& topology,
                            const PatchGrowthGeometry& geometry, const PatchOptions& options)
    : mesh_ (mesh)
    , topology_ (topology)
    , geometry_ (geometry)
    , cos_delta_ (std::cos (options.delta))
    , cos_cone_ (std::cos (options.cone_angle))
    , cos_half_cone_ (std::cos (0.5 * options.cone_angle))
    , pairwise_cone_ (options.pairwise_cone)
    , eta_ (options.eta)
    , rho_area_ (options.rho * geometry.total_area)
    , stop_at_first_refusal_ (options.stop_at_first_refusal)
    , max_vertices_ (static_cast<std::size_t> (std::max (0, options.max_patch_vertices)))
    , min_vertices_ (static_cast<std::size_t> (std::max (0, options.min_growth_vertices)))
    , walk_ (mesh, topology)
    , state_ (mesh.vertices.size (), Untouched)
  {
    walk_.setEdgeLengths (geometry.edge_lengths);
  }

  bool
  PatchGrower::areaConditionHolds (double area, double projected_area, std::size_t size) const
  {
    return size < min_vertices_ || area <= rho_area_ || area <= eta_ * projected_area;
  }

  void
  PatchGrower::reset ()
  {
    for (int v : touched_)
      state_[v] = Untouched;
    touched_.clear ();
    heap_.clear ();
  }

  double
  PatchGrower::coneCosine (int f, const Eigen::Vector3d& ns) const
  {
    if (!(geometry_.face_areas[f] > 0.0))
      return -1.0;
    const double c = geometry_.face_normals[f].dot (ns);
    if (!geometry_.geometric_normals.empty () && !(geometry_.geometric_normals[f].dot (ns) > kMinProjectionCosine))
      return -1.0;
    return c > cos_cone_ && c > kMinProjectionCosine ? c : -1.0;
  }

  bool
  PatchGrower::smoothAt (int f, int w) const
  {
    return geometry_.face_normals[f].dot (geometry_.vertex_normals[w]) > cos_delta_;
  }

  bool
  PatchGrower::pairwiseConeHolds (int f, double c) const
  {
    // Only pairs whose angles to n_s add up to more than the cone can fail, so a triangle within half
    // the cone of n_s is compared with the wide patch triangles only (usually none).
    const auto& others = c >= cos_half_cone_ ? wide_normals_ : patch_normals_;
    for (const auto& m : others)
      if (!(geometry_.face_normals[f].dot (m) > cos_cone_))
        return false;
    return true;
  }

  void
  PatchGrower::addPatchNormal (int f, double c)
  {
    patch_normals_.push_back (geometry_.face_normals[f]);
    if (c < cos_half_cone_)
      wide_normals_.push_back (geometry_.face_normals[f]);
  }

  void
  PatchGrower::collectFaces (int u, const Eigen::Vector3d& ns, double& new_area, double& new_projected)
  {
    // The faces u would complete are patch triangles (and add area); the candidate justifying faces
    // pass the cone and are smooth at an accepted corner other than u.
    completed_.clear ();
    candidates_.clear ();
    folds_ = false;
    const auto& areas = geometry_.face_areas;
    for (int f : topology_.facesOf (u))
    {
      const double c = coneCosine (f, ns);
      if (c < 0.0)
      {
        folds_ = folds_ || (pairwise_cone_ && completesFoldedFace (f, u, ns));
        continue;
      }
      const Eigen::Vector3i& t = mesh_.triangles[f];
      bool complete = true, smooth = false;
      for (int k = 0; k < 3; ++k)
      {
        const int w = t[k];
        if (w == u)
          continue;
        if (walk_.isAccepted (w))
          smooth = smooth || smoothAt (f, w);
        else
          complete = false;
      }
      if (complete)
      {
        if (!(smooth || smoothAt (f, u)))
          continue;
        if (pairwise_cone_ && !pairwiseConeHolds (f, c))
          continue;
        if (pairwise_cone_)
          addPatchNormal (f, c);  // provisional: compared with the next completed faces; undone on refusal
        completed_.push_back (f);
        new_area += areas[f];
        new_projected += areas[f] * c;
        if (smooth)
          candidates_.emplace_back (f, -1.0);  // justifies u, already counted in the area
      }
      else if (smooth)
        candidates_.emplace_back (f, c);
    }
  }

  bool
  PatchGrower::completesFoldedFace (int f, int u, const Eigen::Vector3d& ns) const
  {
    if (!(geometry_.face_areas[f] > 0.0) || !(geometry_.face_normals[f].dot (ns) < 0.0))
      return false;
    const Eigen::Vector3i& t = mesh_.triangles[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] != u && !walk_.isAccepted (t[k]))
        return false;
    return true;
  }

  bool
  PatchGrower::isJustified (double area, double projected_area, std::size_t size) const
  {
    // A justifying face's area counts in A_p even while it is not complete.
    if (!areaConditionHolds (area, projected_area, size))
      return false;
    const auto& areas = geometry_.face_areas;
    for (const auto& [f, c] : candidates_)
    {
      const bool ok = c < 0.0 || (areaConditionHolds (area + areas[f], projected_area + areas[f] * c, size) &&
                                  (!pairwise_cone_ || pairwiseConeHolds (f, c)));
      if (ok)
        return true;
    }
    return false;
  }

  double
  PatchGrower::grow (int seed, Patch& patch)
  {
    reset ();
    patch.seed = seed;
    patch.seed_face = -1;
    patch.origin = mesh_.vertices[seed];
    patch.vertices.assign (1, seed);
    patch.triangles.clear ();
    patch.local.clear ();

    const Eigen::Vector3d& ns = geometry_.vertex_normals[seed];
    if (ns.isZero () || !patch.origin.allFinite ())
      return 0.0;
    const Eigen::Vector3d s = patch.origin;
    patch_normals_.clear ();
    wide_normals_.clear ();

    double area = 0.0, projected = 0.0, growth_radius = 0.0;
    // The walk offers u when its edge distance from the seed is final; a refused u is deferred, not
    // dropped, in the non-stopping growth: a neighbour accepted later may give it a justifying face.
    const GeodesicVisit refusal = stop_at_first_refusal_ ? GeodesicVisit::Stop : GeodesicVisit::Defer;
    auto visit = [&] (int u, double, int) {
      if (u == seed)
        return GeodesicVisit::Accept;
      if (max_vertices_ > 0 && patch.vertices.size () >= max_vertices_)
        return GeodesicVisit::Stop;
      double new_area = 0.0, new_projected = 0.0;
      collectFaces (u, ns, new_area, new_projected);
      const double area_after = area + new_area, projected_after = projected + new_projected;
      if (folds_ || !isJustified (area_after, projected_after, patch.vertices.size ()))
      {
        if (pairwise_cone_)  // undo the provisional normals of this vertex's completed faces
          for (int f : completed_)
          {
            patch_normals_.pop_back ();
            if (geometry_.face_normals[f].dot (ns) < cos_half_cone_)
              wide_normals_.pop_back ();
          }
        return refusal;
      }
      area = area_after;
      projected = projected_after;
      patch.vertices.push_back (u);
      patch.triangles.insert (patch.triangles.end (), completed_.begin (), completed_.end ());
      const Eigen::Vector3d r = mesh_.vertices[u] - s;
      growth_radius = std::max (growth_radius, (r - r.dot (ns) * ns).norm ());
      return GeodesicVisit::Accept;
    };
    walk_.walk (seed, std::numeric_limits<double>::infinity (), visit);
    return growth_radius;
  }

  double
  PatchGrower::growFromFace (int seed, int seed_face, Patch& patch)
  {
    reset ();
    for (int f : touched_faces_)
      face_state_[f] = Untouched;
    touched_faces_.clear ();
    if (face_state_.empty ())
    {
      face_state_.assign (mesh_.triangles.size (), Untouched);
      face_distance_.assign (mesh_.triangles.size (), 0.0);
    }
    patch.seed = seed;
    patch.seed_face = seed_face;
    patch.origin = mesh_.vertices[seed];
    patch.vertices.assign (1, seed);
    patch.triangles.clear ();
    patch.local.clear ();
    const auto& normals = geometry_.face_normals;
    const auto& areas = geometry_.face_areas;
    const Eigen::Vector3d ns = normals[seed_face];
    if (!(areas[seed_face] > 0.0) || !patch.origin.allFinite ())
      return 0.0;
    state_[seed] = Accepted;  // vertex membership, reset by the next growth
    touched_.push_back (seed);

    auto centroid = [&] (int f) {
      const Eigen::Vector3i& t = mesh_.triangles[f];
      return Eigen::Vector3d ((mesh_.vertices[t[0]] + mesh_.vertices[t[1]] + mesh_.vertices[t[2]]) / 3.0);
    };
    patch_normals_.clear ();
    wide_normals_.clear ();
    double area = 0.0, projected = 0.0, growth_radius = 0.0;
    auto accept = [&] (int f, double c) {
      face_state_[f] = Accepted;
      patch.triangles.push_back (f);
      area += areas[f];
      projected += areas[f] * c;
      addPatchNormal (f, c);
      for (int k = 0; k < 3; ++k)
      {
        const int u = mesh_.triangles[f][k];
        if (state_[u] != Accepted)
        {
          state_[u] = Accepted;
          touched_.push_back (u);
          patch.vertices.push_back (u);
          const Eigen::Vector3d r = mesh_.vertices[u] - patch.origin;
          growth_radius = std::max (growth_radius, (r - r.dot (ns) * ns).norm ());
        }
      }
      const Eigen::Vector3d cf = centroid (f);
      for (int k = 0; k < 3; ++k)
      {
        const int g = topology_.face_neighbors[f][k];
        if (g < 0 || face_state_[g] == Accepted)
          continue;
        const double d = face_distance_[f] + (centroid (g) - cf).norm ();
        if (face_state_[g] == Untouched || d < face_distance_[g] || face_state_[g] == Refused)
        {
          if (face_state_[g] == Untouched)
            touched_faces_.push_back (g);
          face_distance_[g] = face_state_[g] == Refused ? std::min (d, face_distance_[g]) : d;
          face_state_[g] = Queued;
          heap_.emplace_back (face_distance_[g], g);
          std::push_heap (heap_.begin (), heap_.end (), HeapGreater ());
        }
      }
    };

    touched_faces_.push_back (seed_face);
    face_distance_[seed_face] = 0.0;
    accept (seed_face, 1.0);
    while (!heap_.empty () && (max_vertices_ == 0 || patch.vertices.size () < max_vertices_))
    {
      std::pop_heap (heap_.begin (), heap_.end (), HeapGreater ());
      const auto [d, g] = heap_.back ();
      heap_.pop_back ();
      if (face_state_[g] != Queued || d > face_distance_[g])
        continue;
      bool ok = false;
      const double c = coneCosine (g, ns);
      if (c > 0.0 && areaConditionHolds (area + areas[g], projected + areas[g] * c, patch.vertices.size ()))
      {
        for (int k = 0; k < 3 && !ok; ++k)
        {
          const int h = topology_.face_neighbors[g][k];
          ok = h >= 0 && face_state_[h] == Accepted && normals[g].dot (normals[h]) > cos_delta_;
        }
        ok = ok && (!pairwise_cone_ || (pairwiseConeHolds (g, c) &&
                                        !addingFaceFolds (mesh_, topology_, geometry_, ns, g,
                                                          [&] (int v) { return state_[v] == Accepted; })));
      }
      if (!ok)
      {
        if (stop_at_first_refusal_)
          break;
        face_state_[g] = Refused;
        continue;
      }
      accept (g, c);
    }
    return growth_radius;
  }
} // namespace pcl_sparse
