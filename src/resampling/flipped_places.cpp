#include <pcl_sparse/resampling/flipped_places.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/parallel_failure.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/geometry/nearest_face_normal.h>
#include <pcl_sparse/geometry/point_triangle_distance.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/patch_geometry.h>
#include <pcl_sparse/resampling/patch_ownership.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace pcl_sparse
{
  void
  FlippedPlaceOptions::validate () const
  {
    auto fail = [] (const std::string& field, double value, const std::string& range) {
      throwOutOfRange ("FlippedPlaceOptions", field, value, range);
    };
    if (!(max_normal_angle > 90.0 && max_normal_angle <= 180.0))
      fail ("max_normal_angle", max_normal_angle, "90 < max_normal_angle <= 180 degrees");
    if (radial_steps < 1)
      fail ("radial_steps", radial_steps, "radial_steps >= 1");
    if (max_rounds < 1)
      fail ("max_rounds", max_rounds, "max_rounds >= 1");
  }

  namespace
  {
    /// Squared distance in the plane from \a p to the triangle \a a \a b \a c (0 inside).
    double
    planarTriangleSquaredDistance (const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                   const Eigen::Vector2d& c)
    {
      auto cross = [] (const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x () * v.y () - u.y () * v.x (); };
      const double s0 = cross (b - a, p - a), s1 = cross (c - b, p - b), s2 = cross (a - c, p - c);
      if ((s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) || (s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0))
        return 0.0;
      auto segment = [&] (const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
        const Eigen::Vector2d d = v - u;
        const double length = d.squaredNorm ();
        const double t = length > 0.0 ? std::clamp ((p - u).dot (d) / length, 0.0, 1.0) : 0.0;
        return (u + t * d - p).squaredNorm ();
      };
      return std::min ({segment (a, b), segment (b, c), segment (c, a)});
    }

    /// A triangle in the plane tested against many points (a grid's cells): a point further than the reach
    /// outside one of its edge lines is further than that from the triangle, found with one dot product;
    /// only the others are measured exactly.
    struct PlanarTriangle
    {
      Eigen::Vector2d corners[3];
      Eigen::Vector2d outward[3];  ///< unit normal of the edge from corner k to k + 1, pointing out
      bool has_area = false;       ///< false: no outward side, every point measured

      PlanarTriangle (const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) : corners{a, b, c}
      {
        const double area = (b - a).x () * (c - a).y () - (b - a).y () * (c - a).x ();
        has_area = area != 0.0;
        for (int k = 0; k < 3; ++k)
        {
          const Eigen::Vector2d edge = corners[(k + 1) % 3] - corners[k];
          const double length = edge.norm ();
          has_area = has_area && length > 0.0;
          // (y, -x) points right of the edge: out of a counter-clockwise triangle.
          outward[k] = Eigen::Vector2d (edge.y (), -edge.x ()) * (length > 0.0 ? (area > 0.0 ? 1.0 : -1.0) / length : 0.0);
        }
      }

      /// Whether \a p lies within \a reach (its square: \a reach_squared) of the triangle. The corners are
      /// tried before the exact distance: a triangle smaller than the reach (most faces) is near a point
      /// near one of them.
      bool
      near (const Eigen::Vector2d& p, double reach, double reach_squared) const
      {
        if (has_area)
          for (int k = 0; k < 3; ++k)
            if (outward[k].dot (p - corners[k]) > reach)
              return false;
        for (int k = 0; k < 3; ++k)
          if ((p - corners[k]).squaredNorm () <= reach_squared)
            return true;
        return planarTriangleSquaredDistance (p, corners[0], corners[1], corners[2]) <= reach_squared;
      }
    };

    /// Where on patch \a p's plane a place can lie near an input face tilted far from the patch's normal: a
    /// grid over the square of its footprint listing, per cell, the faces tilted over `tilt` from N whose
    /// projection comes within `near` of the cell and whose heights within `near` of the slab of the
    /// patch's. A place's normal is within its slope angle of N, so it can only be more than the limit from
    /// the nearest face's normal where that face is tilted over the limit minus the slope; and that face
    /// is nearest only if it lies within the place's distance from the surface, taken as at most `near`
    /// (0.2 r: of the 275 places found on cheese-cgal, horse and sword searching 0.25 r, 225 lay within
    /// 0.01 r of the mesh and one beyond 0.2 r, at 0.21 r).
    struct TiltedFaceGrid
    {
      static constexpr int cells = 16;
      /// How far (local units) a place may lie from the surface for its nearest face to be found here.
      static constexpr double near = 0.2;
      double start = 0.0, cell = 1.0;
      /// A face near a cell: its normal (to compare first, from contiguous memory), a ball around it in the
      /// patch's local units (a place further than `near` from the ball is from the face: no exact distance
      /// needed) and its index.
      struct Face
      {
        Eigen::Vector3f normal;
        Eigen::Vector3f centre;
        float radius;
        int index;
      };
      std::vector<std::vector<Face>> faces;  ///< cells x cells, row by row

      /// The faces near the place (x, y).
      const std::vector<Face>&
      facesNear (double x, double y) const
      {
        const int i = std::clamp (static_cast<int> ((x - start) / cell), 0, cells - 1);
        const int j = std::clamp (static_cast<int> ((y - start) / cell), 0, cells - 1);
        return faces[static_cast<std::size_t> (j) * cells + i];
      }

      /// Whether a face listed near a place (\a local (x, y, h) in the patch's units, \a world) lies within
      /// \a near_distance (world: `near` local units) of it and has a normal whose cosine with \a normal is
      /// below \a flipped_cosine. Cheap tests first: the normals, then the face's ball, then the exact distance.
      bool
      tiltedFaceNear (const TriangleMesh& mesh, const Eigen::Vector3d& local, const Eigen::Vector3d& world,
                      const Eigen::Vector3d& normal, float flipped_cosine, double near_distance) const
      {
        const Eigen::Vector3f normal_f = normal.cast<float> (), local_f = local.cast<float> ();
        const std::vector<Face>& listed = facesNear (local.x (), local.y ());
        return std::any_of (listed.begin (), listed.end (), [&] (const Face& f) {
          if (!(normal_f.dot (f.normal) < flipped_cosine))
            return false;
          // Local units are about 1: 1e-4 covers the floats' rounding, so no face the exact test keeps is skipped.
          const float ball = static_cast<float> (near) + f.radius + 1e-4f;
          if ((local_f - f.centre).squaredNorm () > ball * ball)
            return false;
          const Eigen::Vector3i& t = mesh.triangles[static_cast<std::size_t> (f.index)];
          return pointTriangleDistance (world, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]) <= near_distance;
        });
      }
    };

    /// Fills \a grid with patch \a p's faces tilted over \a tilt from its normal (its cells' lists keep their memory
    /// from the thread's last patch; \a found: scratch space); \a any tells whether some cell lists a face.
    void
    tiltedFaces (const TriangleMesh& mesh, const NearestFaceNormal& surface, const PatchEvaluator& evaluator,
                 std::size_t p, double tilt, std::vector<TriangleTree::Nearest>& found, TiltedFaceGrid& grid, bool& any)
    {
      const PatchCode& code = evaluator.model ().patches[p];
      const double extent = evaluator.maxExtent (p);
      const double height = std::min (code.heightBound (*evaluator.model ().basis), 1.0);
      const double near = TiltedFaceGrid::near;
      grid.start = -extent;
      grid.cell = 2.0 * extent / TiltedFaceGrid::cells;
      const double reach = near + grid.cell * M_SQRT1_2, reach_squared = reach * reach;
      grid.faces.resize (TiltedFaceGrid::cells * TiltedFaceGrid::cells);
      for (std::vector<TiltedFaceGrid::Face>& listed : grid.faces)
        listed.clear ();
      any = false;
      surface.tree ().within (code.origin, code.radius * (std::sqrt (extent * extent + height * height) + near), found);
      const Eigen::Vector3d n = code.frame.col (2);
      const double tilt_cosine = std::cos (tilt);
      for (const TriangleTree::Nearest& face : found)
      {
        const std::size_t f = static_cast<std::size_t> (face.triangle);
        const double cosine = n.dot (surface.faceNormals ()[f]);
        if (!(cosine < tilt_cosine))
          continue;
        Eigen::Vector3d corners[3];
        Eigen::AlignedBox3d box;
        for (int corner = 0; corner < 3; ++corner)
          box.extend (corners[corner] = code.toLocal (mesh.vertices[static_cast<std::size_t> (mesh.triangles[f][corner])]));
        if (box.min ().z () > height + near || box.max ().z () < -height - near)
          continue;
        const int i0 = std::max (0, static_cast<int> (std::floor ((box.min ().x () - near - grid.start) / grid.cell)));
        const int i1 = std::min (TiltedFaceGrid::cells - 1, static_cast<int> (std::floor ((box.max ().x () + near - grid.start) / grid.cell)));
        const int j0 = std::max (0, static_cast<int> (std::floor ((box.min ().y () - near - grid.start) / grid.cell)));
        const int j1 = std::min (TiltedFaceGrid::cells - 1, static_cast<int> (std::floor ((box.max ().y () + near - grid.start) / grid.cell)));
        const PlanarTriangle projected (corners[0].head<2> (), corners[1].head<2> (), corners[2].head<2> ());
        const Eigen::Vector3d face_centre = (corners[0] + corners[1] + corners[2]) / 3.0;
        const double radius = std::sqrt (std::max ({(corners[0] - face_centre).squaredNorm (), (corners[1] - face_centre).squaredNorm (),
                                                    (corners[2] - face_centre).squaredNorm ()}));
        const TiltedFaceGrid::Face listed{surface.faceNormals ()[f].cast<float> (), face_centre.cast<float> (),
                                          static_cast<float> (radius), static_cast<int> (f)};
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i)
          {
            const Eigen::Vector2d centre (grid.start + (i + 0.5) * grid.cell, grid.start + (j + 0.5) * grid.cell);
            if (!projected.near (centre, reach, reach_squared))
              continue;
            grid.faces[static_cast<std::size_t> (j) * TiltedFaceGrid::cells + i].push_back (listed);
            any = true;
          }
      }
    }

    /// A place tested on a ray: where, and the code there.
    struct RayPlace
    {
      int ray;
      double fraction, inside;  ///< of the ray's extent: this place's, and the place's tested just inside it
      double x, y, centrality, turn;
      HeightSample h;
    };

    /// Patch \a p's footprint cut just inside its places that point the wrong way, or an empty vector when
    /// it has none; \a flagged receives their number.
    std::vector<float>
    cutFootprint (const TriangleMesh& mesh, const NearestFaceNormal& surface, const PatchEvaluator& evaluator,
                  const PatchOwnership& ownership, std::size_t p, const FlippedPlaceOptions& options,
                  std::size_t& flagged, std::vector<TriangleTree::Nearest>& scratch, TiltedFaceGrid& tilted)
    {
      flagged = 0;
      // A place is a valid one, no steeper than resampling's largest slope, so its normal is within that slope
      // of N: it can only be past the limit from a face tilted over the limit minus that slope. Where no face
      // in reach is (most patches of smooth meshes), none of the places is computed; elsewhere those faces are
      // filed by the cells of the footprint's square (tiltedFaces), and only the places in a cell listing one are.
      const double limit = options.max_normal_angle * M_PI / 180.0;
      const double tilt = std::max (0.0, limit - std::atan (std::sqrt (ownership.maxSlopeSquared ())));
      bool any;
      tiltedFaces (mesh, surface, evaluator, p, tilt, scratch, tilted, any);
      if (!any)
        return {};
      const PatchCode& code = evaluator.model ().patches[p];
      const std::vector<float>& extent = code.footprint.extent;
      const int k = static_cast<int> (extent.size ());
      const int steps = options.radial_steps;
      // The valid places on the rays near a tilted face, each ray from the seed outwards.
      std::vector<RayPlace> places;
      // The last step is split twice more: a flipped sliver along the rim (a flat patch reaching over a face
      // tilted 120 degrees, cheese-cgal) lies between the last two places, the border's often held by another.
      // Whether a place is one resampling may emit, inside the footprint and valid there (its centrality and
      // code filled in).
      auto settle = [&] (RayPlace& place) {
        place.centrality = evaluator.centrality (p, place.x, place.y, place.turn);
        if (!(place.centrality <= 1.0))
          return false;
        place.h = evaluator.sample (p, place.x, place.y, false);
        return isValidPlace (place.h, ownership.options (), ownership.maxSlopeSquared ());
      };
      std::vector<double> fractions;
      for (int i = 1; i < steps; ++i)
        fractions.push_back (static_cast<double> (i) / steps);
      fractions.push_back (1.0 - 0.5 / steps);
      fractions.push_back (1.0 - 0.25 / steps);
      fractions.push_back (1.0);
      for (int ray = 0; ray < 2 * k; ++ray)
      {
        const int before = ray / 2, after = (before + 1) % k;
        const double angle = M_PI * ray / k, c = std::cos (angle), s = std::sin (angle);
        const double e = ray % 2 == 1 ? 0.5 * (extent[before] + extent[after]) : extent[before];
        for (std::size_t i = 0; i < fractions.size (); ++i)
        {
          const double f = fractions[i];
          RayPlace place{ray, f, i == 0 ? 0.0 : fractions[i - 1], e * f * c, e * f * s, 0.0, 0.0, HeightSample ()};
          if (tilted.facesNear (place.x, place.y).empty () || !settle (place))
            continue;
          places.push_back (place);
        }
      }
      if (places.empty ())
        return {};
      const double flipped_cosine = std::cos (limit);
      const double near_distance = TiltedFaceGrid::near * code.radius;
      // A float normal is off by about 1e-7: the float test lets through every face the double one would.
      const float flipped_cosine_f = static_cast<float> (flipped_cosine) + 1e-5f;
      std::vector<float> cut = extent;
      int done_ray = -1;  // the ray whose innermost flipped place was found
      // Whether a face tilted over the limit from the place's normal lies near it (cheap, from the grid).
      auto nearTiltedFace = [&] (const RayPlace& place, const Eigen::Vector3d& world, const Eigen::Vector3d& normal) {
        return tilted.tiltedFaceNear (mesh, Eigen::Vector3d (place.x, place.y, place.h.value), world, normal, flipped_cosine_f,
                                      near_distance);
      };
      // Whether the place's normal is over the limit from the surface's at its nearest point.
      auto flippedNormal = [&] (const Eigen::Vector3d& world, const Eigen::Vector3d& normal) {
        double cosine;
        surface.nearest (world, normal, cosine, scratch);
        return cosine < flipped_cosine;
      };
      for (const RayPlace& place : places)
      {
        if (place.ray == done_ray)
          continue;  // the places further out are cut off with the inner one
        const Eigen::Vector3d normal = patchNormal (code, place.h);
        const Eigen::Vector3d world = patchPoint (code, place.x, place.y, place.h);
        if (!nearTiltedFace (place, world, normal))
          continue;
        RayPlace flipped = place;
        if (ownership.owns (p, world, place.centrality, place.turn))
        {
          if (!flippedNormal (world, normal))
            continue;
        }
        else
        {
          // Held by another patch or cleared here, the place may still end a flipped stretch this patch
          // emits between it and the place inside (cheese-cgal's file cloud: 0.66-0.75 of a ray tested at
          // 0.625 and 0.75): the place halfway is tested too.
          RayPlace half = place;
          half.fraction = 0.5 * (place.inside + place.fraction);
          half.x = place.x * half.fraction / place.fraction;
          half.y = place.y * half.fraction / place.fraction;
          if (!settle (half))
            continue;
          const Eigen::Vector3d half_normal = patchNormal (code, half.h);
          const Eigen::Vector3d half_world = patchPoint (code, half.x, half.y, half.h);
          if (!nearTiltedFace (half, half_world, half_normal) || !ownership.owns (p, half_world, half.centrality, half.turn) ||
              !flippedNormal (half_world, half_normal))
            continue;
          flipped = half;
        }
        ++flagged;
        done_ray = flipped.ray;
        // Down to the place tested just inside (the seed for the first).
        const int before = flipped.ray / 2, after = (before + 1) % k;
        const double rho = std::hypot (flipped.x, flipped.y);
        const float inside = static_cast<float> (rho * flipped.inside / flipped.fraction);
        cut[before] = std::min (cut[before], inside);
        if (flipped.ray % 2 == 1)
          cut[after] = std::min (cut[after], inside);
      }
      if (flagged == 0)
        return {};
      return cut;
    }

    /// The patches whose footprints hold a place of patch \a p between its footprint and the \a cut one
    /// (tested on its rays, as cutFootprint): those of its side may take the place, and those facing away
    /// had their places there cleared (PatchOwnership::clearedByFacingAway), which the cut releases.
    std::vector<std::size_t>
    patchesHoldingCut (const PatchEvaluator& evaluator, const PatchOwnership& ownership, std::size_t p,
                       const std::vector<float>& cut, int steps)
    {
      const SparseSurfaceModel& model = evaluator.model ();
      const PatchCode& code = model.patches[p];
      const std::vector<float>& extent = code.footprint.extent;
      std::vector<int> around = ownership.neighbours (p);  // its side's, then those facing away
      const std::vector<int> facing_away = ownership.facingAway (p);
      around.insert (around.end (), facing_away.begin (), facing_away.end ());
      std::vector<char> holds (around.size (), 0);
      const int k = static_cast<int> (extent.size ());
      for (int ray = 0; ray < k; ++ray)
      {
        if (!(cut[ray] < extent[ray]))
          continue;
        const double angle = 2.0 * M_PI * ray / k, c = std::cos (angle), s = std::sin (angle);
        for (int i = 0; i <= steps; ++i)
        {
          const double rho = cut[ray] + (extent[ray] - cut[ray]) * i / steps;
          const double x = rho * c, y = rho * s;
          const Eigen::Vector3d place = code.toWorld (Eigen::Vector3d (x, y, evaluator.height (p, x, y)));
          for (std::size_t j = 0; j < around.size (); ++j)
          {
            const std::size_t q = static_cast<std::size_t> (around[j]);
            const Eigen::Vector3d local = model.patches[q].toLocal (place);
            holds[j] = holds[j] || evaluator.centrality (q, local.x (), local.y ()) <= 1.0;
          }
        }
      }
      std::vector<std::size_t> takers;
      for (std::size_t j = 0; j < around.size (); ++j)
        if (holds[j])
          takers.push_back (static_cast<std::size_t> (around[j]));
      return takers;
    }

    /// Draws \a footprint in to \a cut (as many extents, none larger) and marks the angles lowered
    /// (PatchFootprint::trimmed: a file keeps its border there no further out).
    void
    cutTo (PatchFootprint& footprint, std::vector<float> cut)
    {
      footprint.trimmed.resize (footprint.extent.size (), 0);
      for (std::size_t a = 0; a < cut.size (); ++a)
        if (cut[a] < footprint.extent[a])
          footprint.trimmed[a] = 1;
      footprint.extent = std::move (cut);
    }

    /// \a mesh without the triangles that have a corner out of range or not finite, or nothing when it has
    /// none (the usual case: no copy of the mesh). The encoder leaves such triangles out of its patches, and
    /// the triangle tree refuses them.
    std::optional<TriangleMesh>
    withoutBrokenTriangles (const TriangleMesh& mesh)
    {
      const long n = static_cast<long> (mesh.vertices.size ());
      const auto sound = [&] (const Eigen::Vector3i& t) {
        return std::all_of (t.data (), t.data () + 3, [&] (int v) {
          return v >= 0 && v < n && mesh.vertices[static_cast<std::size_t> (v)].allFinite ();
        });
      };
      if (std::all_of (mesh.triangles.begin (), mesh.triangles.end (), sound))
        return std::nullopt;
      TriangleMesh kept;
      kept.vertices = mesh.vertices;
      std::copy_if (mesh.triangles.begin (), mesh.triangles.end (), std::back_inserter (kept.triangles), sound);
      return kept;
    }
  } // namespace

  FlippedPlaceTrim
  trimFlippedPlaces (const TriangleMesh& input, SparseSurfaceModel& model, const FlippedPlaceOptions& options, int threads)
  {
    options.validate ();
    threads = resolveThreadCount (threads);
    FlippedPlaceTrim trim;
    const std::size_t m = model.numPatches ();
    const std::optional<TriangleMesh> sound = withoutBrokenTriangles (input);
    const TriangleMesh& mesh = sound ? *sound : input;
    if (m == 0 || mesh.triangles.empty ())
      return trim;
    const NearestFaceNormal surface (mesh, threads);
    std::vector<std::size_t> candidates (m);
    for (std::size_t p = 0; p < m; ++p)
      candidates[p] = p;
    std::vector<char> was_cut (m, 0);
    while (trim.rounds < options.max_rounds && !candidates.empty ())
    {
      ++trim.rounds;
      const PatchEvaluator evaluator (model);
      const PatchOwnership ownership (evaluator, PatchOwnershipOptions (), threads);
      const long n = static_cast<long> (candidates.size ());
      std::vector<std::vector<float>> cuts (candidates.size ());
      std::vector<std::size_t> flagged (candidates.size (), 0);
      ParallelFailure failure;
#pragma omp parallel num_threads(threads)
      {
        std::vector<TriangleTree::Nearest> scratch;
        TiltedFaceGrid tilted;
#pragma omp for schedule(dynamic, 8)
        for (long w = 0; w < n; ++w)
          failure.run ([&] {
            const std::size_t i = static_cast<std::size_t> (w);
            cuts[i] = cutFootprint (mesh, surface, evaluator, ownership, candidates[i], options, flagged[i], scratch, tilted);
          });
      }
      failure.rethrow ();
      // Places cut off go to the patches whose footprints hold them, or to none: those are the next
      // round's candidates, with the patches cut (their new rims are tested).
      std::vector<char> next (m, 0);
      std::vector<std::vector<std::size_t>> takers (candidates.size ());
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
      for (long w = 0; w < n; ++w)
      {
        const std::size_t i = static_cast<std::size_t> (w);
        if (!cuts[i].empty ())
          takers[i] = patchesHoldingCut (evaluator, ownership, candidates[i], cuts[i], options.radial_steps);
      }
      for (std::size_t i = 0; i < candidates.size (); ++i)
      {
        if (cuts[i].empty ())
          continue;
        const std::size_t p = candidates[i];
        trim.places += flagged[i];
        was_cut[p] = 1;
        next[p] = 1;
        for (std::size_t q : takers[i])
          next[q] = 1;
      }
      for (std::size_t i = 0; i < candidates.size (); ++i)
        if (!cuts[i].empty ())
          cutTo (model.patches[candidates[i]].footprint, std::move (cuts[i]));
      candidates.clear ();
      for (std::size_t p = 0; p < m; ++p)
        if (next[p])
          candidates.push_back (p);
    }
    trim.patches = static_cast<std::size_t> (std::count (was_cut.begin (), was_cut.end (), 1));
    return trim;
  }
} // namespace pcl_sparse
