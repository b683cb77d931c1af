#pragma once
/// \file patch_growth.h
/// Growing one patch from a seed vertex (docs/METHOD.md step 5, the paper's "create_patch").
///
/// Vertices are visited by increasing geodesic distance from the seed (Dijkstra over edges, the walk of
/// DijkstraGeodesic in geodesic.h with this growth as its visitor; the authors use fast marching). A
/// vertex u joins if some non-degenerate triangle t incident to u and to an already accepted corner w
/// satisfies all of:
///   - smooth variation  angle(n_t, n_w) < delta               (n_w: vertex normal of w)
///   - normal cone       angle(n_t, n_s) < cone_angle           (n_s: vertex normal of the seed)
///                       and angle(n_t, n_m) < cone_angle for every patch triangle m (pairwise_cone)
///   - no flip           n_t . n_s > 0, so t projects on the seed's tangent plane with its orientation
///   - area              A_p / A <= rho  or  A_p / A_p^proj <= eta
/// where A_p is the area of the patch triangles once u has joined, t included, A_p^proj its projection on
/// the seed's tangent plane and A the mesh's total area. The area condition is checked with and without
/// t when t is not yet a patch triangle, so it holds for the final patch too.
/// Patch triangles are the faces whose three corners joined and which pass the cone and no-flip tests and
/// the smooth variation test for at least one corner.
/// The growth stops at the first refused vertex (PatchOptions::stop_at_first_refusal, GeodesicVisit::Stop)
/// or, without it, defers refused vertices: each is tested again whenever a neighbour joins later
/// (GeodesicVisit::Defer), since a new accepted corner can give it a justifying triangle.

#include <pcl_sparse/geometry/geodesic.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_options.h>

#include <Eigen/Core>

#include <cstdint>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  /// Per-mesh quantities every growth reads, computed once per mesh.
  struct PatchGrowthGeometry
  {
    std::vector<Eigen::Vector3d> face_normals;    ///< #F unit normals (zero for degenerate faces)
    /// #F the triangles' own unit normals where face_normals are smoothed (point normals given), else
    /// empty. A patch triangle must still project on the seed's plane without flipping: the frames and
    /// footprints rely on it.
    std::vector<Eigen::Vector3d> geometric_normals;
    std::vector<double> face_areas;               ///< #F face areas
    /// #V unit vertex normals, area weighted (zero for vertices with no proper face).
    std::vector<Eigen::Vector3d> vertex_normals;
    /// Length of each 1-ring entry of the topology (computeEdgeLengths, geodesic.h), parallel to
    /// MeshTopology::vertex_neighbors.
    std::vector<double> edge_lengths;
    double total_area = 0.0;                      ///< A, the mesh's total area
  };

  /// Face normals, areas, area-weighted vertex normals, edge lengths and total area of a mesh (parallel,
  /// deterministic).
  /// With \a point_normals (a scan's PCA normals), vertex v takes point_normals[v] and a face the normalised
  /// sum of its corners' normals, where they are non-zero: the triangles of noisy points tilt by tens of
  /// degrees, so their own normals would stop the growth (delta, eta) at a few points and every patch would
  /// code noise. Areas stay the triangles' own.
  /// \param[in] mesh           the mesh
  /// \param[in] topology       its topology
  /// \param[in] point_normals  #V unit normals (zero: none for that vertex), or empty to use the mesh's
  /// \param[in] num_threads    OpenMP threads (0: all)
  /// \return the quantities every growth on this mesh reads
  PatchGrowthGeometry
  computePatchGrowthGeometry (const TriangleMesh& mesh, const MeshTopology& topology,
                              const std::vector<Eigen::Vector3d>& point_normals = {}, int num_threads = 0);

  /// Whether adding face \a f's corners to a patch (which holds the vertices \a holds says) would put all
  /// corners of another face facing away from the patch's seed normal \a ns in it: the patch's vertices
  /// would fold over the seed's plane (a thin ridge), and its code would run between the two sides. Growth
  /// from a face and face completion refuse such a face with the pairwise cone (PatchOptions), as vertex
  /// growth refuses such a vertex.
  /// \param[in] mesh      the mesh
  /// \param[in] topology  its topology
  /// \param[in] geometry  computePatchGrowthGeometry (mesh, topology)
  /// \param[in] ns        the normal the patch grew around (seed vertex's, or seed face's)
  /// \param[in] f         the face that would join
  /// \param[in] holds     callable, holds (v) is whether the patch holds vertex v before \a f joins
  template <typename Holds>
  bool
  addingFaceFolds (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                   const Eigen::Vector3d& ns, int f, const Holds& holds)
  {
    const Eigen::Vector3i& t = mesh.triangles[f];
    auto heldAfter = [&] (int v) { return v == t[0] || v == t[1] || v == t[2] || holds (v); };
    for (int k = 0; k < 3; ++k)
    {
      if (holds (t[k]))
        continue;
      for (int g : topology.facesOf (t[k]))
      {
        const Eigen::Vector3i& u = mesh.triangles[g];
        if (g != f && geometry.face_areas[g] > 0.0 && geometry.face_normals[g].dot (ns) < 0.0 && heldAfter (u[0]) &&
            heldAfter (u[1]) && heldAfter (u[2]))
          return true;
      }
    }
    return false;
  }

  /// Grows patches on one mesh. Scratch arrays (the walk's included) are sized once for the mesh and only
  /// the entries a growth touched are reset, so one growth costs O(R log R) for R visited vertices, independent of the mesh
  /// size. Not thread-safe: one object per thread.
  class PatchGrower
  {
  public:
    /// Sizes the scratch for a mesh. All arguments must outlive the grower.
    /// \param[in] mesh      the mesh
    /// \param[in] topology  its topology
    /// \param[in] geometry  computePatchGrowthGeometry (mesh, topology)
    /// \param[in] options   growth conditions; must be valid (PatchOptions::validate)
    PatchGrower (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                 const PatchOptions& options);

    /// Grows the patch of a seed vertex (docs/METHOD.md step 5). A seed without a normal (isolated, or only
    /// degenerate faces) gives the one-vertex patch.
    /// \param[in]  seed   the seed vertex
    /// \param[out] patch  receives seed, origin, vertices (seed first, growth order) and triangles; frame,
    ///                    radius and local are left to computePatchFrame
    /// \return the growth radius: largest distance from the seed to a patch vertex in the tangent plane
    ///         of the seed's vertex normal (0 for a one-vertex patch)
    double
    grow (int seed, Patch& patch);

    /// Coverage growth (ours) for vertices the method cannot cover: creases and corners whose vertex
    /// normal is more than delta from every incident face, strips of faces between two creases. Grows
    /// over faces from \a seed_face (a face of \a seed), by increasing centroid distance along manifold
    /// edges: a face g joins if it is adjacent to a joined face h with angle(n_g, n_h) < delta, and the
    /// cone (against n_{seed_face}), no-flip and area conditions hold as in grow () (with the pairwise
    /// cone also: every two patch triangles within the cone, and no fold, addingFaceFolds). Stops at the
    /// first refused face when stop_at_first_refusal. Patch vertices are the corners of the joined faces
    /// (seed first), patch triangles the joined faces.
    /// \param[in]  seed       the uncovered vertex the patch is for
    /// \param[in]  seed_face  a face incident to \a seed
    /// \param[out] patch      receives seed, seed_face, origin, vertices and triangles, as grow ()
    /// \return the growth radius in the tangent plane of n_{seed_face}
    double
    growFromFace (int seed, int seed_face, Patch& patch);

  private:
    enum : std::uint8_t { Untouched = 0, Queued = 1, Accepted = 2, Refused = 3 };

    /// The area condition (rho or eta) for a patch of \a size vertices before the candidate joins; waived
    /// below PatchOptions::min_growth_vertices.
    bool areaConditionHolds (double area, double projected_area, std::size_t size) const;
    void reset ();
    /// Cone and no-flip test of face \a f against the seed normal \a ns: n_f . n_s, or -1 when it fails.
    double coneCosine (int f, const Eigen::Vector3d& ns) const;
    /// Smooth variation: angle(n_f, n_w) < delta at vertex \a w.
    bool smoothAt (int f, int w) const;
    /// Pairwise cone: angle(n_f, n_m) < cone for every patch triangle m so far (\a c = n_f . n_s).
    bool pairwiseConeHolds (int f, double c) const;
    /// Records the normal of patch triangle \a f (\a c = n_f . n_s) for pairwiseConeHolds.
    void addPatchNormal (int f, double c);
    /// One pass over the faces of \a u for grow (): the faces u would complete into completed_ (adding
    /// their area and projected area), its candidate justifying faces into candidates_.
    void collectFaces (int u, const Eigen::Vector3d& ns, double& new_area, double& new_projected);
    /// Whether the patch may take area \a area (projected \a projected_area) with some justifying face
    /// of candidates_ for the vertex being tested.
    bool isJustified (double area, double projected_area, std::size_t size) const;

    const TriangleMesh& mesh_;
    const MeshTopology& topology_;
    const PatchGrowthGeometry& geometry_;
    double cos_delta_;
    double cos_cone_;
    double cos_half_cone_;
    bool pairwise_cone_;
    double eta_;
    double rho_area_;  // rho * A
    bool stop_at_first_refusal_;
    std::size_t max_vertices_;  // 0: no bound
    std::size_t min_vertices_;  // area bound waived below this many vertices (0: never)

    DijkstraGeodesic walk_;  // the vertex walk of grow ()
    std::vector<std::uint8_t> state_;  // face growth: vertex membership
    std::vector<int> touched_;
    std::vector<std::pair<double, int>> heap_;  // face growth queue
    /// Whether \a u would complete face \a f (its other corners accepted) facing away from the seed normal
    /// \a ns: with \a u, the patch's vertices would fold over the seed's plane.
    bool completesFoldedFace (int f, int u, const Eigen::Vector3d& ns) const;

    std::vector<int> completed_;  // faces completed by the vertex being tested
    bool folds_ = false;          // the vertex being tested completes a folded face (pairwise cone only)
    std::vector<std::pair<int, double>> candidates_;  // its justifying faces (face, n_t . n_s; -1: complete)
    std::vector<Eigen::Vector3d> patch_normals_;  // normals of the patch triangles so far
    std::vector<Eigen::Vector3d> wide_normals_;   // those further than half the cone from n_s
    std::vector<std::uint8_t> face_state_;        // face growth scratch (sized on first use)
    std::vector<double> face_distance_;
    std::vector<int> touched_faces_;
  };
} // namespace pcl_sparse
