#include <pcl_sparse/patches/face_completion.h>

#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/patches/face_placement.h>
#include <pcl_sparse/patches/hidden_triangles.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>
#include <utility>

namespace pcl_sparse
{
  namespace
  {
    /// A patch grown from a face is kept only while its growth radius r (from its seed, in the face's
    /// plane) has r^2 <= this x its area A (a strip seen from its end: r = length, A = length x width, so
    /// at most 40 times longer than wide; a square seen from a corner: 2). A
    /// patch's footprint is star-shaped around its seed (64 rays), so over a long strip it spans wedges
    /// off the strip several times the strip's area, and the patch's plane, carried past the creases
    /// beside it, put points off the surface there: on blade (fillet strips at r^2 / A = 56-57) the
    /// cloud's mean distance to the mesh rose from 2.4e-5 to 5.7e-5 of the diagonal. Such a strip stays in
    /// no patch, covered by its neighbours' unclipped footprints as before. Measured: 40 keeps every
    /// patch on couplingdown (r^2 / A up to 29), all but 0.04 % of cheese-cgal's area and 0.0007 % of
    /// turbine's; 24 leaves 1 % of cheese-cgal's (bench/results/face_seeded_patches.md).
    constexpr double kMaxFacePatchSpread = 40.0;

    /// The faces of positive area in \a areas (computeFaceAreas) that are a triangle of no patch, ascending.
    std::vector<int>
    facesInNoPatch (const TriangleMesh& mesh, const std::vector<Patch>& patches, const std::vector<double>& areas)
    {
      std::vector<std::uint8_t> in_patch (mesh.triangles.size (), 0);
      for (const Patch& p : patches)
        for (int f : p.triangles)
          in_patch[f] = 1;
      std::vector<int> faces;
      for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
        if (!in_patch[f] && areas[f] > 0.0)
          faces.push_back (static_cast<int> (f));
      return faces;
    }

    /// Each face of result.uncovered not in a patch yet, in ascending order, grows a patch over faces
    /// (PatchGrower::growFromFace: its own normal is the cone's axis, smooth variation between adjacent
    /// faces), seeded at its first corner the partition answers for, and kept if it is compact enough
    /// (kMaxFacePatchSpread); the faces of a patch not kept are not tried again. Faces a kept patch takes
    /// leave the list.
    void
    seedPatchesOnFaces (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                        const PatchOptions& options, const std::vector<std::uint8_t>& must_cover,
                        std::vector<std::uint8_t>& in_patch, std::vector<Patch>& patches, FaceCompletionResult& result)
    {
      if (result.uncovered.empty ())
        return;
      PatchGrower grower (mesh, topology, geometry, options);
      Patch patch;
      for (int f : result.uncovered)
      {
        if (in_patch[f])
          continue;
        const Eigen::Vector3i& t = mesh.triangles[f];
        int seed = t[0];
        for (int k = 0; k < 3 && !must_cover.empty (); ++k)
          if (must_cover[t[k]])
          {
            seed = t[k];
            break;
          }
        const double grown_radius = grower.growFromFace (seed, f, patch);
        double area = 0.0;
        for (int g : patch.triangles)
          area += geometry.face_areas[g];
        if (patch.triangles.empty () || grown_radius * grown_radius > kMaxFacePatchSpread * area)
        {
          for (int g : patch.triangles)
            in_patch[g] = in_patch[g] ? in_patch[g] : 2;
          continue;
        }
        for (int g : patch.triangles)
          in_patch[g] = 1;
        patches.push_back (patch);
        ++result.seeded_patches;
      }
      std::vector<int> left;
      for (int f : result.uncovered)
        if (in_patch[f] != 1)
          left.push_back (f);
      result.uncovered = std::move (left);
    }

    /// A face released from a patch (hidden_triangles.h) and the patch it left.
    struct ReleasedFace
    {
      int face;
      int patch;
    };

    /// Removes every patch's hidden triangles (PatchOptions::hidden_triangle_gap), marks in \a in_patch (all
    /// 0) the faces the patches hold afterwards; the released faces no other patch holds join result.uncovered
    /// (ascending), to grow patches of their own.
    std::vector<ReleasedFace>
    removeHiddenTriangles (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                           double min_gap, int num_threads, std::vector<Patch>& patches, std::vector<std::uint8_t>& in_patch,
                           FaceCompletionResult& result)
    {
      // Each patch is looked at on its own, so in parallel; the removals follow in patch order.
      const int num_patches = static_cast<int> (patches.size ());
      std::vector<std::vector<int>> hidden (patches.size ());
#pragma omp parallel num_threads(resolveThreadCount (num_threads))
      {
        HiddenTriangleFinder finder (mesh, topology, geometry);
#pragma omp for schedule(dynamic, 64)
        for (int p = 0; p < num_patches; ++p)
          hidden[p] = finder.find (patches[p], min_gap);
      }
      std::vector<ReleasedFace> released;
      for (int p = 0; p < num_patches; ++p)
      {
        if (hidden[p].empty ())
          continue;
        removePatchTriangles (mesh, hidden[p], patches[p]);
        for (int f : hidden[p])
          released.push_back ({f, p});
      }
      if (released.empty ())
        return released;
      for (const Patch& p : patches)
        for (int f : p.triangles)
          in_patch[f] = 1;
      for (const ReleasedFace& r : released)
        if (!in_patch[r.face])
          result.uncovered.push_back (r.face);
      std::sort (result.uncovered.begin (), result.uncovered.end ());
      result.uncovered.erase (std::unique (result.uncovered.begin (), result.uncovered.end ()), result.uncovered.end ());
      return released;
    }

    /// Gives each released face no patch took back to the patch it left, with its corners, at the end of its
    /// triangles (counted with completion's: it keeps the cone and no-flip conditions it was taken under).
    void
    restoreReleasedFaces (const TriangleMesh& mesh, const std::vector<ReleasedFace>& released, std::vector<Patch>& patches,
                          std::vector<std::uint8_t>& in_patch, FaceCompletionResult& result)
    {
      for (const ReleasedFace& r : released)
      {
        if (in_patch[r.face] == 1)
        {
          ++result.released_faces;
          continue;
        }
        Patch& patch = patches[r.patch];
        patch.triangles.push_back (r.face);
        ++patch.completed_triangles;
        for (int k = 0; k < 3; ++k)
        {
          const int v = mesh.triangles[r.face][k];
          if (std::find (patch.vertices.begin (), patch.vertices.end (), v) == patch.vertices.end ())
            patch.vertices.push_back (v);
        }
        in_patch[r.face] = 1;
        result.uncovered.erase (std::remove (result.uncovered.begin (), result.uncovered.end (), r.face),
                                result.uncovered.end ());
      }
    }
  } // namespace

  FaceCompletionResult
  completePatchFaces (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                      const PatchOptions& options, std::vector<Patch>& patches, const std::vector<std::uint8_t>& must_cover)
  {
    FaceCompletionResult result;
    const int num_faces = static_cast<int> (mesh.triangles.size ());
    std::vector<std::uint8_t> in_patch (num_faces, 0);
    for (const Patch& p : patches)
      for (int f : p.triangles)
        in_patch[f] = 1;

    // Candidates are the patches holding a corner as grown, so they do not depend on the completion order.
    FacePlacer placer (mesh, topology, geometry, options, patches);
    for (int f = 0; f < num_faces; ++f)
    {
      if (in_patch[f] || !(geometry.face_areas[f] > 0.0))
        continue;
      const Eigen::Vector3i& t = mesh.triangles[f];
      if (!must_cover.empty () && !must_cover[t[0]] && !must_cover[t[1]] && !must_cover[t[2]])
        continue;
      ++result.faces_in_no_patch;
      const FacePlacer::Placement placement = placer.place (f);
      if (placement.patch < 0)
      {
        result.uncovered.push_back (f);
        continue;
      }
      in_patch[f] = 1;
      ++result.completed;
      result.without_smooth_variation += !placement.smooth_variation;
    }
    if (options.seed_patches_on_faces)
      seedPatchesOnFaces (mesh, topology, geometry, options, must_cover, in_patch, patches, result);
    // Faces left in no patch: the patches at their corners (as grown) keep their footprints' full reach,
    // which is what covers such a face (PatchCode footprint, clip_footprints_at_border).
    for (int f : result.uncovered)
      for (int k = 0; k < 3; ++k)
        for (int p : placer.holdersOf (mesh.triangles[f][k]))
          patches[p].beside_uncovered_face = true;
    return result;
  }

  FaceCompletionResult
  releaseHiddenPatchTriangles (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                               const PatchOptions& options, std::vector<Patch>& patches,
                               const std::vector<std::uint8_t>& must_cover, int num_threads)
  {
    FaceCompletionResult result;
    if (!(options.hidden_triangle_gap > 0.0))
      return result;
    std::vector<std::uint8_t> in_patch (mesh.triangles.size (), 0);
    const std::vector<ReleasedFace> released = removeHiddenTriangles (mesh, topology, geometry, options.hidden_triangle_gap,
                                                                      num_threads, patches, in_patch, result);
    if (released.empty ())
      return result;
    seedPatchesOnFaces (mesh, topology, geometry, options, must_cover, in_patch, patches, result);
    restoreReleasedFaces (mesh, released, patches, in_patch, result);
    return result;
  }

  std::vector<int>
  facesInNoPatch (const TriangleMesh& mesh, const std::vector<Patch>& patches)
  {
    return facesInNoPatch (mesh, patches, computeFaceAreas (mesh));
  }

  FaceCoverage
  faceCoverage (const TriangleMesh& mesh, const std::vector<Patch>& patches)
  {
    const std::vector<double> areas = computeFaceAreas (mesh);
    const std::vector<int> faces = facesInNoPatch (mesh, patches, areas);
    const double total = std::accumulate (areas.begin (), areas.end (), 0.0);
    double uncovered = 0.0;
    for (int f : faces)
      uncovered += areas[f];
    FaceCoverage coverage;
    coverage.faces_in_no_patch = faces.size ();
    coverage.area_fraction = total > 0.0 ? uncovered / total : 0.0;
    return coverage;
  }
} // namespace pcl_sparse
