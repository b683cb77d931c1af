#include <pcl_sparse/patches/impl/feature_aware_patch_sampling.hpp>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/geometry/nearest_point_grid.h>
#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/mesh/mesh_components.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/face_completion.h>
#include <pcl_sparse/patches/non_manifold_split.h>
#include <pcl_sparse/patches/patch_growth.h>
#include <pcl_sparse/patches/patch_merging.h>
#include <pcl_sparse/patches/redundant_patches.h>

#include "speculative_growth.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    /// Growth helpers of the sampling loop (speculative_growth.h): at most this many (each holds a grower of
    /// about 14 bytes per vertex, and the loop takes the patches of one thread or two most of the time),
    /// on meshes of at least this many vertices (below, the loop takes milliseconds).
    constexpr int kMaxGrowthHelpers = 3;
    constexpr std::size_t kMinVerticesForHelpers = 20000;

    /// Candidate order: \a keypoints first, then the other vertices; each part in the order of
    /// orderVerticesByResponse (decreasing response, ties by increasing index, no response last).
    std::vector<int>
    candidateOrder (std::size_t num_vertices, const std::vector<double>& responses, const std::vector<int>& keypoints,
                    int num_threads)
    {
      const std::vector<double> no_responses (responses.empty () ? num_vertices : 0, std::nan (""));
      const std::vector<double>& ranked = responses.empty () ? no_responses : responses;
      std::vector<std::uint8_t> is_keypoint (num_vertices, 0);
      std::vector<int> first, rest;
      for (int k : keypoints)
        if (!is_keypoint[k])
        {
          is_keypoint[k] = 1;
          first.push_back (k);
        }
      rest.reserve (num_vertices - first.size ());
      for (std::size_t v = 0; v < num_vertices; ++v)
        if (!is_keypoint[v])
          rest.push_back (static_cast<int> (v));
      sortByHarris3DRank (ranked, first, num_threads);
      sortByHarris3DRank (ranked, rest, num_threads);
      first.insert (first.end (), rest.begin (), rest.end ());
      return first;
    }

    /// Mean length of the edges at each vertex (0 for isolated vertices) and over the whole mesh.
    double
    meanEdgeLength (const TriangleMesh& mesh, const MeshTopology& topology, int v)
    {
      double sum = 0.0;
      int count = 0;
      for (int w : topology.neighborsOf (v))
      {
        const double l = (mesh.vertices[w] - mesh.vertices[v]).norm ();
        if (std::isfinite (l))
        {
          sum += l;
          ++count;
        }
      }
      return count > 0 ? sum / count : 0.0;
    }

    /// How near a point lies to the vertices of faces, in their local spacing (PatchOptions::
    /// unreferenced_patch_spacings). The grid is built on the first question: most meshes never ask. Of
    /// equally near vertices the lowest index counts: a vertex rather than its split copies (GrowthMesh).
    class NearestFaceVertex
    {
    public:
      NearestFaceVertex (const TriangleMesh& mesh, const MeshTopology& topology, const std::vector<std::uint8_t>& in_faces)
        : mesh_ (mesh), topology_ (topology), in_faces_ (in_faces) {}

      /// Whether \a p lies within \a spacings mean edge lengths (meanEdgeLength) of the nearest vertex of a
      /// face from that vertex.
      bool
      within (const Eigen::Vector3d& p, double spacings) const
      {
        if (!grid_)
        {
          std::vector<Eigen::Vector3f> points;
          for (std::size_t w = 0; w < in_faces_.size (); ++w)
            if (in_faces_[w])
            {
              vertices_.push_back (static_cast<int> (w));
              points.push_back (mesh_.vertices[w].cast<float> ());
            }
          grid_ = std::make_unique<NearestPointGrid> (points);
        }
        const int nearest = grid_->nearest (p.cast<float> ());
        if (nearest < 0)
          return false;
        const int w = vertices_[static_cast<std::size_t> (nearest)];
        return (p - mesh_.vertices[w]).norm () <= spacings * meanEdgeLength (mesh_, topology_, w);
      }

    private:
      const TriangleMesh& mesh_;
      const MeshTopology& topology_;
      const std::vector<std::uint8_t>& in_faces_;
      mutable std::unique_ptr<NearestPointGrid> grid_;
      mutable std::vector<int> vertices_;
    };

    /// Throws Error ("[FeatureAwarePatchSampling::compute] " + message) unless \a condition.
    void
    require (bool condition, const std::string& message)
    {
      if (!condition)
        throw Error ("[FeatureAwarePatchSampling::compute] " + message);
    }

    void
    validateInputs (const TriangleMesh& mesh, const MeshTopology& topology, const PatchOptions& options,
                    const std::vector<double>& responses, const std::vector<int>& keypoints,
                    const std::vector<Eigen::Vector3d>& point_normals)
    {
      options.validate ();
      const std::size_t num_vertices = mesh.vertices.size ();
      // The message is made only for a bad index: made for every index, it took 6 % of an encoding.
      const auto out_of_range = [num_vertices] (int v) { return v < 0 || static_cast<std::size_t> (v) >= num_vertices; };
      for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
          if (out_of_range (t[k]))
            require (false, "face index " + std::to_string (t[k]) + " out of range (" + std::to_string (num_vertices) +
                              " vertices)");
      require (responses.empty () || responses.size () == num_vertices,
               std::to_string (responses.size ()) + " responses for " + std::to_string (num_vertices) + " vertices");
      require (topology.numVertices () == num_vertices, "the topology (setTopology) is not the input mesh's");
      require (point_normals.empty () || point_normals.size () == num_vertices,
               std::to_string (point_normals.size ()) + " point normals for " + std::to_string (num_vertices) + " vertices");
      for (int k : keypoints)
        if (out_of_range (k))
          require (false, "keypoint " + std::to_string (k) + " out of range");
    }

    /// The mesh the patches grow on: the input, or a copy with non-manifold edges and vertices cut (growth
    /// cannot cross them), with the map back to input vertices.
    struct GrowthMesh
    {
      NonManifoldSplit split;
      MeshTopology split_topology;
      bool is_split = false;
      const TriangleMesh* mesh = nullptr;
      const MeshTopology* topology = nullptr;

      GrowthMesh (const TriangleMesh& input, const MeshTopology& input_topology, int num_threads)
      {
        is_split = splitNonManifoldVertices (input, input_topology, split, num_threads);
        if (is_split)
          split_topology = buildMeshTopology (split.mesh, num_threads);
        mesh = is_split ? &split.mesh : &input;
        topology = is_split ? &split_topology : &input_topology;
      }
      int originalOf (int v) const { return is_split ? split.original[v] : v; }

      /// Per-vertex values of the input on the growth mesh (a split copy takes its original's).
      std::vector<Eigen::Vector3d>
      normalsOf (const std::vector<Eigen::Vector3d>& input_normals) const
      {
        return is_split ? valuesOnSplit (split, input_normals) : input_normals;
      }
    };

    /// Candidates on the input's vertices (\a input_order), each followed by its split copies.
    std::vector<int>
    orderWithCopies (const GrowthMesh& growth, const std::vector<int>& input_order, int num_input)
    {
      const int num_vertices = static_cast<int> (growth.mesh->vertices.size ());
      std::vector<int> order;
      order.reserve (num_vertices);
      std::vector<int> copy_offsets (num_input + 1, 0), copies (num_vertices - num_input);
      for (int v = num_input; v < num_vertices; ++v)
        ++copy_offsets[growth.originalOf (v) + 1];
      std::partial_sum (copy_offsets.begin (), copy_offsets.end (), copy_offsets.begin ());
      std::vector<int> cursor (copy_offsets.begin (), copy_offsets.end () - 1);
      for (int v = num_input; v < num_vertices; ++v)
        copies[cursor[growth.originalOf (v)]++] = v;
      for (int v : input_order)
      {
        order.push_back (v);
        for (int i = copy_offsets[v]; i < copy_offsets[v + 1]; ++i)
          order.push_back (copies[i]);
      }
      return order;
    }

    /// The patches kept so far and the vertices they cover. Only the vertices that must be covered (all,
    /// or the seed region's) count: a patch covering nothing new of them is not kept.
    struct Coverage
    {
      std::vector<Patch>& patches;
      std::vector<std::uint8_t> covered;  ///< 1 covered, 2 need not be covered (outside the seed region)
      int num_covered = 0;

      ///  seedable: empty (every vertex must be covered) or one flag per vertex.
      Coverage (std::vector<Patch>& kept, std::size_t num_vertices, const std::vector<std::uint8_t>& seedable)
        : patches (kept), covered (num_vertices, 0)
      {
        if (!seedable.empty ())
          for (std::size_t v = 0; v < num_vertices; ++v)
            covered[v] = seedable[v] ? 0 : 2;
      }

      void
      keep (const Patch& p)
      {
        for (int u : p.vertices)
          if (!covered[u])
          {
            covered[u] = 1;
            ++num_covered;
          }
        patches.push_back (p);
      }

      long
      newlyCovered (const Patch& p) const
      {
        return std::count_if (p.vertices.begin (), p.vertices.end (), [&] (int u) { return covered[u] == 0; });
      }
    };

    /// The loop's invalid flag of a candidate pruned from its tail (1: near a kept patch's seed).
    constexpr std::uint8_t kFarFromUncovered = 2;

    /// R of PatchOptions::tail_pruning_after: ceil (sqrt (mean vertex count of \a kept)), at least 2.
    int
    tailPruningHops (const std::vector<Patch>& kept)
    {
      double total = 0.0;
      for (const Patch& p : kept)
        total += static_cast<double> (p.vertices.size ());
      const double mean = kept.empty () ? 0.0 : total / static_cast<double> (kept.size ());
      return std::max (2, static_cast<int> (std::ceil (std::sqrt (mean))));
    }

    /// Per vertex, whether it lies within \a hops edges of a vertex still to cover (covered 0): a
    /// breadth-first search from all of them at once.
    std::vector<std::uint8_t>
    nearUncovered (const MeshTopology& topology, const std::vector<std::uint8_t>& covered, int hops)
    {
      std::vector<std::uint8_t> near (covered.size (), 0);
      std::vector<int> frontier, next;
      for (std::size_t u = 0; u < covered.size (); ++u)
        if (covered[u] == 0)
        {
          near[u] = 1;
          frontier.push_back (static_cast<int> (u));
        }
      for (int h = 0; h < hops && !frontier.empty (); ++h)
      {
        next.clear ();
        for (int u : frontier)
          for (int w : topology.neighborsOf (u))
            if (!near[w])
            {
              near[w] = 1;
              next.push_back (w);
            }
        frontier.swap (next);
      }
      return near;
    }

    /// Sampling loop (docs/METHOD.md step 4), sequential by nature: each candidate not marked invalid grows a
    /// patch, kept if large enough and covering a new vertex; its vertices near the seed become invalid.
    /// With more than one thread, helpers grow the next valid candidates ahead of the loop
    /// (speculative_growth.h): the same patches, sooner. Returns the number of seeds grown.
    std::size_t
    runSamplingLoop (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                     const std::vector<int>& order, const std::vector<std::uint8_t>& referenced, int target,
                     const PatchOptions& options, int threads, PatchGrower& grower, Coverage& coverage,
                     const ProgressCallback& progress)
    {
      const std::size_t num_vertices = mesh.vertices.size ();
      std::unique_ptr<std::atomic<std::uint8_t>[]> invalid (new std::atomic<std::uint8_t>[num_vertices] ());
      std::vector<std::uint8_t> never_grown (num_vertices);
      for (std::size_t v = 0; v < num_vertices; ++v)
        never_grown[v] = !referenced[v] || coverage.covered[v] == 2;
      // Helpers pay on large inputs only (a patch of a few dozen vertices grows in microseconds).
      const int helpers = num_vertices >= kMinVerticesForHelpers ? std::min (threads - 1, kMaxGrowthHelpers) : 0;
      SpeculativeGrowth speculative (mesh, topology, geometry, options, order, never_grown, invalid.get (), helpers);
      std::size_t num_grown = 0;
      int fruitless = 0;  // grown seeds in a row that covered nothing new
      Patch patch;
      // The pruned tail (PatchOptions::tail_pruning_after; unresolved, < 0, is a mesh's: never): once,
      // covered candidates far from every uncovered vertex are marked, and the helpers skip them too.
      const double prune_fraction = options.tail_pruning_after < 0.0 ? 1.0 : options.tail_pruning_after;
      const long prune_start = static_cast<long> (std::ceil (prune_fraction * target));
      bool pruned = prune_fraction >= 1.0;
      auto pruneTail = [&] () {
        if (pruned || coverage.num_covered < prune_start)
          return;
        pruned = true;
        const std::vector<std::uint8_t> near =
          nearUncovered (topology, coverage.covered, tailPruningHops (coverage.patches));
        for (std::size_t u = 0; u < num_vertices; ++u)
          if (coverage.covered[u] == 1 && !near[u])
          {
            std::uint8_t valid = 0;
            invalid[u].compare_exchange_strong (valid, kFarFromUncovered, std::memory_order_relaxed);
          }
      };
      pruneTail ();
      const int progress_step = std::max (1, target / 100);
      int next_progress = 0;
      for (std::size_t i = 0; i < order.size (); ++i)
      {
        const int v = order[i];
        if (coverage.num_covered >= target)
          break;
        if (options.max_fruitless_seeds > 0 && fruitless >= options.max_fruitless_seeds)
          break;
        if (never_grown[v])
          continue;
        const std::uint8_t state = invalid[v].load (std::memory_order_relaxed);
        if (state == kFarFromUncovered)
          ++fruitless;  // the paper's loop grows it and finds nothing new
        if (state)
          continue;
        ++num_grown;
        ++fruitless;
        const double radius = speculative.grow (i, grower, patch);
        if (static_cast<int> (patch.size ()) < options.min_patch_size)
          continue;
        if (coverage.newlyCovered (patch) == 0)
          continue;
        fruitless = 0;
        coverage.keep (patch);
        const double reach = options.sigma * radius;
        for (int u : patch.vertices)
          if ((mesh.vertices[u] - mesh.vertices[v]).norm () < reach)
            invalid[u].store (1, std::memory_order_relaxed);
        invalid[v].store (1, std::memory_order_relaxed);
        pruneTail ();
        if (progress && coverage.num_covered >= next_progress)
        {
          progress ("patches", static_cast<double> (coverage.num_covered) / std::max (1, target));
          next_progress = coverage.num_covered + progress_step;
        }
      }
      return num_grown;
    }

    /// Coverage pass (ours): a vertex the loop left uncovered seeds its own patch, whatever its size. Such
    /// vertices are mostly on creases or in strips of faces between creases, where no vertex normal is
    /// within delta of the faces, so the method's growth from them stops at once. Growth from each of
    /// their faces, with smooth variation between adjacent faces (growFromFace), covers whole strips: the
    /// variant covering most uncovered vertices is kept (ties: the larger patch, then the method's growth,
    /// then the lowest face).
    void
    runCoveragePass (const MeshTopology& topology, const PatchGrowthGeometry& geometry, const std::vector<int>& order,
                     const std::vector<std::uint8_t>& referenced, int target, PatchGrower& grower, Coverage& coverage)
    {
      Patch patch, trial;
      for (int v : order)
      {
        if (coverage.num_covered >= target)
          break;
        if (coverage.covered[v] || !referenced[v])
          continue;
        grower.grow (v, patch);
        long best = coverage.newlyCovered (patch);
        for (int f : topology.facesOf (v))
        {
          if (!(geometry.face_areas[f] > 0.0))
            continue;
          grower.growFromFace (v, f, trial);
          const long n = coverage.newlyCovered (trial);
          if (n > best || (n == best && trial.size () > patch.size ()))
          {
            best = n;
            std::swap (patch, trial);
          }
        }
        coverage.keep (patch);
      }
    }

    /// Frames (docs/METHOD.md step 6), in parallel: one output per patch. Patches grown from a face refuse
    /// steep jets from face_steep_frame_angle on (PatchOptions).
    std::vector<PatchFrameKind>
    fitFrames (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
               double steep_frame_angle, double face_steep_frame_angle, int threads, std::vector<Patch>& patches)
    {
      double global_edge = 0.0;
      if (!topology.edges.empty ())
      {
        for (const auto& e : topology.edges)
          global_edge += (mesh.vertices[e[1]] - mesh.vertices[e[0]]).norm ();
        global_edge /= static_cast<double> (topology.edges.size ());
      }
      if (!(global_edge > 0.0) || !std::isfinite (global_edge))
        global_edge = 1.0;
      std::vector<PatchFrameKind> frame_kinds (patches.size ());
      const int num_patches = static_cast<int> (patches.size ());
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
      for (int i = 0; i < num_patches; ++i)
      {
        Patch& p = patches[i];
        const double guard = meanEdgeLength (mesh, topology, p.seed);
        const Eigen::Vector3d& seed_normal =
          p.seed_face >= 0 ? geometry.face_normals[p.seed_face] : geometry.vertex_normals[p.seed];
        const double steep = p.seed_face >= 0 ? face_steep_frame_angle : steep_frame_angle;
        frame_kinds[i] = computePatchFrame (mesh, seed_normal, guard > 0.0 ? guard : global_edge, p, steep);
      }
      return frame_kinds;
    }

    /// Back to the input's vertex indices; a patch holding two copies of one vertex keeps the first.
    void
    mapToInputVertices (const GrowthMesh& growth, int num_input, std::vector<Patch>& patches)
    {
      std::vector<std::uint8_t> seen (num_input, 0);
      for (Patch& p : patches)
      {
        p.seed = growth.originalOf (p.seed);
        std::size_t n = 0;
        for (std::size_t i = 0; i < p.vertices.size (); ++i)
        {
          const int o = growth.originalOf (p.vertices[i]);
          if (seen[o])
            continue;
          seen[o] = 1;
          p.vertices[n] = o;
          p.local[n] = p.local[i];
          ++n;
        }
        p.vertices.resize (n);
        p.local.resize (n);
        for (int v : p.vertices)
          seen[v] = 0;
      }
    }

    /// Input vertices in no patch, ascending.
    std::vector<int>
    verticesInNoPatch (const std::vector<Patch>& patches, int num_input)
    {
      std::vector<std::uint8_t> in_patch (num_input, 0);
      for (const Patch& p : patches)
        for (int v : p.vertices)
          in_patch[v] = 1;
      std::vector<int> uncovered;
      for (int v = 0; v < num_input; ++v)
        if (!in_patch[v])
          uncovered.push_back (v);
      return uncovered;
    }

    /// Drops the patches flagged in \a dropped from \a result, keeping the order of the others; the first
    /// \a num_sampled patches came from the sampling loop (updated), the rest from the coverage pass.
    /// Returns how many were dropped.
    std::size_t
    dropPatches (const std::vector<bool>& dropped, std::size_t& num_sampled, PatchSamplingResult& result)
    {
      std::size_t kept = 0, sampled_dropped = 0;
      for (std::size_t i = 0; i < result.patches.size (); ++i)
      {
        if (dropped[i])
        {
          result.num_coverage_patches -= i >= num_sampled ? 1 : 0;
          sampled_dropped += i < num_sampled ? 1 : 0;
        }
        else
        {
          if (kept != i)  // a self-move would empty the patch
            result.patches[kept] = std::move (result.patches[i]);
          ++kept;
        }
      }
      const std::size_t num_dropped = result.patches.size () - kept;
      result.patches.resize (kept);
      num_sampled -= sampled_dropped;
      return num_dropped;
    }

    /// The vertices of the seed region in no face, added to \a result.unreferenced: when asked
    /// (PatchOptions::cover_unreferenced_vertices), each gets a one-vertex patch but NaN ones and those next
    /// to the faces (unreferenced_patch_spacings), which go to \a result.uncovered, as all go when not asked.
    /// Returns the non-finite vertices in faces, left uncovered whatever the options.
    std::vector<int>
    coverUnreferencedVertices (const GrowthMesh& growth, const std::vector<std::uint8_t>& referenced,
                               const std::vector<std::uint8_t>& seedable, const PatchOptions& options, PatchGrower& grower,
                               Coverage& coverage, PatchSamplingResult& result)
    {
      const TriangleMesh& mesh = *growth.mesh;
      const MeshTopology& topology = *growth.topology;
      // Unresolved (< 0), it is a mesh's: its unreferenced vertices are not on its surface.
      const bool cover = patchOptionsFor (options, false).cover_unreferenced_vertices > 0;
      const NearestFaceVertex next_to_faces (mesh, topology, referenced);
      Patch patch;
      std::vector<int> non_finite_in_faces;
      for (int v = 0; v < static_cast<int> (mesh.vertices.size ()); ++v)
        if (!referenced[v] && growth.originalOf (v) == v && (seedable.empty () || seedable[v]))
        {
          if (topology.facesOf (v).size () > 0)
          {
            non_finite_in_faces.push_back (v);
            continue;
          }
          result.unreferenced.push_back (v);
          // A NaN point no face uses (the holes of a mesh made from an organized cloud) has nothing to code:
          // a patch there had a NaN origin, and the model could be neither saved nor resampled.
          if (!cover || !mesh.vertices[v].allFinite () ||
              (options.unreferenced_patch_spacings > 0.0 &&
               next_to_faces.within (mesh.vertices[v], options.unreferenced_patch_spacings)))
            result.uncovered.push_back (v);
          else
          {
            grower.grow (v, patch);
            coverage.keep (patch);
          }
        }
      return non_finite_in_faces;
    }
  } // namespace

  void
  computeUnitScaleHarris3D (const TriangleMesh& mesh, const MeshTopology& topology, int num_threads,
                            std::vector<double>& responses, std::vector<int>& keypoints, int rings)
  {
    Harris3DOptions harris;
    harris.num_threads = num_threads;
    harris.rings = std::max (0, rings);
    // Harris 3D responses depend on the length unit (harris3d.h): computed on the mesh scaled to a unit
    // bbox diagonal, the seeds, and so the whole model, do not depend on the input's units.
    const double diagonal = boundingBoxDiagonal (mesh);
    TriangleMesh unit;
    const bool rescale = diagonal > 0.0 && std::isfinite (diagonal) && diagonal != 1.0;
    if (rescale)
    {
      unit.triangles = mesh.triangles;
      unit.vertices.resize (mesh.vertices.size ());
      for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
        unit.vertices[v] = mesh.vertices[v] / diagonal;
    }
    const TriangleMesh& harris_mesh = rescale ? unit : mesh;
    responses = computeHarris3DResponses (harris_mesh, topology, harris);
    keypoints = selectHarris3DKeypoints (harris_mesh, topology, responses, harris, mesh.vertices.size ());
  }

  PatchSamplingResult
  sampleFeatureAwarePatches (const TriangleMesh& input, const MeshTopology& input_topology, const PatchOptions& options,
                             const std::vector<double>& responses, const std::vector<int>& keypoints, int num_threads,
                             const ProgressCallback& progress, const std::vector<Eigen::Vector3d>& point_normals,
                             const std::vector<std::uint8_t>& seed_vertices)
  {
    validateInputs (input, input_topology, options, responses, keypoints, point_normals);
    require (seed_vertices.empty () || seed_vertices.size () == input.vertices.size (),
             std::to_string (seed_vertices.size ()) + " seed flags for " + std::to_string (input.vertices.size ()) +
               " vertices");
    const int threads = resolveThreadCount (num_threads);
    const int num_input = static_cast<int> (input.vertices.size ());
    PatchSamplingResult result;

    // Default feature order: Harris 3D with its default options (docs/METHOD.md step 3).
    result.responses = responses;
    result.keypoints = keypoints;
    if (responses.empty () && keypoints.empty ())
      computeUnitScaleHarris3D (input, input_topology, num_threads, result.responses, result.keypoints, options.harris_rings);

    const GrowthMesh growth (input, input_topology, num_threads);
    const TriangleMesh& mesh = *growth.mesh;
    const MeshTopology& topology = *growth.topology;
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    const PatchGrowthGeometry geometry = computePatchGrowthGeometry (mesh, topology, growth.normalsOf (point_normals), num_threads);
    const std::vector<int> order =
      orderWithCopies (growth, candidateOrder (num_input, result.responses, result.keypoints, threads), num_input);

    std::vector<std::uint8_t> referenced (num_vertices, 0);
    std::vector<std::uint8_t> seedable;  // on the growth mesh: a split copy takes its original's flag
    if (!seed_vertices.empty ())
    {
      seedable.resize (num_vertices);
      for (int v = 0; v < num_vertices; ++v)
        seedable[v] = seed_vertices[growth.originalOf (v)] ? 1 : 0;
    }
    // The loop can cover only vertices of components with at least min_patch_size vertices (a patch lies
    // in one): it ends once those are covered. Counting the others too, a mesh with one stray triangle
    // never reached its target and grew a patch from every remaining candidate, O(V^2) (found by a review:
    // 275 s for a 90k-vertex grid beside one triangle); the coverage pass covers them.
    const std::vector<int> component_sizes = faceComponentSizes (mesh);
    int target = 0, loop_target = 0;
    for (int v = 0; v < num_vertices; ++v)
    {
      // A non-finite vertex in faces (a mesh given through the API; the loaders refuse it) is not on the
      // surface either: no growth takes it (its faces have no area), and the coverage pass seeded a patch
      // with a NaN origin there, which could be neither saved nor resampled.
      referenced[v] = topology.facesOf (v).size () > 0 && mesh.vertices[v].allFinite ();
      const bool counted = referenced[v] && (seedable.empty () || seedable[v]);
      target += counted;
      loop_target += counted && component_sizes[v] >= options.min_patch_size;
    }

    PatchGrower grower (mesh, topology, geometry, options);
    Coverage coverage (result.patches, num_vertices, seedable);
    result.num_grown =
      runSamplingLoop (mesh, topology, geometry, order, referenced, loop_target, options, threads, grower, coverage, progress);
    std::size_t num_sampled = result.patches.size ();
    if (options.cover_all_vertices)
      runCoveragePass (topology, geometry, order, referenced, target, grower, coverage);
    if (progress)
      progress ("patches", 1.0);
    const std::vector<int> non_finite_in_faces =
      coverUnreferencedVertices (growth, referenced, seedable, options, grower, coverage, result);
    result.num_coverage_patches = result.patches.size () - num_sampled;
    if (options.complete_faces)
    {
      // Faces of the seed region only (a face with a seedable corner): a tile's margin is another tile's.
      FaceCompletionResult completion = completePatchFaces (mesh, topology, geometry, options, result.patches, seedable);
      result.num_completed_faces = completion.completed;
      result.num_coverage_patches += completion.seeded_patches;
      result.uncovered_faces = std::move (completion.uncovered);
    }
    if (options.drop_redundant_patches)
      result.num_redundant = dropPatches (redundantPatches (mesh, result.patches, seedable), num_sampled, result);
    if (options.merge_own_elements > 0)
      result.num_merged = dropPatches (
        mergeSmallPatches (mesh, topology, geometry, options, options.merge_own_elements, result.patches, seedable),
        num_sampled, result);
    if (options.complete_faces && options.seed_patches_on_faces)
    {
      PatchOptions release = options;  // unresolved (< 0), it is a mesh's
      release.hidden_triangle_gap = patchOptionsFor (options, false).hidden_triangle_gap;
      const std::size_t seeded =
        releaseHiddenPatchTriangles (mesh, topology, geometry, release, result.patches, seedable, threads).seeded_patches;
      result.num_coverage_patches += seeded;
      if (seeded > 0)  // the new patches grow over faces completion left in no patch too
      {
        const std::vector<int> left = facesInNoPatch (mesh, result.patches);
        std::vector<int> still;
        std::set_intersection (result.uncovered_faces.begin (), result.uncovered_faces.end (), left.begin (), left.end (),
                               std::back_inserter (still));
        result.uncovered_faces = std::move (still);
      }
    }

    // Unresolved (< 0), it is a mesh's.
    const double steep_frame_angle = patchOptionsFor (options, false).steep_frame_angle;
    const double face_steep_frame_angle = steep_frame_angle > 0.0 && options.face_steep_frame_angle > 0.0
                                            ? std::min (steep_frame_angle, options.face_steep_frame_angle)
                                            : steep_frame_angle;
    result.frame_kinds =
      fitFrames (mesh, topology, geometry, steep_frame_angle, face_steep_frame_angle, threads, result.patches);
    if (growth.is_split)
      mapToInputVertices (growth, num_input, result.patches);
    if (!non_finite_in_faces.empty ())
    {
      const std::size_t middle = result.uncovered.size ();
      result.uncovered.insert (result.uncovered.end (), non_finite_in_faces.begin (), non_finite_in_faces.end ());
      std::inplace_merge (result.uncovered.begin (), result.uncovered.begin () + middle, result.uncovered.end ());
    }
    if (!options.cover_all_vertices)
      result.uncovered = verticesInNoPatch (result.patches, num_input);
    return result;
  }

#define PCL_SPARSE_INSTANTIATE_PATCH_SAMPLING(T) template class FeatureAwarePatchSampling<T>;
  PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_INSTANTIATE_PATCH_SAMPLING)
#undef PCL_SPARSE_INSTANTIATE_PATCH_SAMPLING
} // namespace pcl_sparse
