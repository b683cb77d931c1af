#include <pcl_sparse/patches/feature_aware_patch_sampling.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/non_manifold_split.h>
#include <pcl_sparse/patches/patch_growth.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    /// Candidate order: \a keypoints first, then the other vertices; each part by decreasing response,
    /// ties by increasing index, vertices without a finite response last.
    std::vector<int>
    candidateOrder (std::size_t num_vertices, const std::vector<double>& responses, const std::vector<int>& keypoints)
    {
      auto before = [&] (int a, int b) {
        const double ra = responses.empty () ? NAN : responses[a];
        const double rb = responses.empty () ? NAN : responses[b];
        const bool fa = std::isfinite (ra), fb = std::isfinite (rb);
        if (fa != fb)
          return fa;
        if (fa && ra != rb)
          return ra > rb;
        return a < b;
      };
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
      std::sort (first.begin (), first.end (), before);
      std::sort (rest.begin (), rest.end (), before);
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
  } // namespace

  void
  computeUnitScaleHarris3D (const TriangleMesh& mesh, const MeshTopology& topology, int num_threads,
                            std::vector<double>& responses, std::vector<int>& keypoints)
  {
    Harris3DOptions harris;
    harris.num_threads = num_threads;
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

  void
  FeatureAwarePatchSampling::compute (std::vector<Patch>& patches)
  {
    patches.clear ();
    uncovered_.clear ();
    unreferenced_.clear ();
    frame_kinds_.clear ();
    num_coverage_patches_ = 0;
    num_grown_ = 0;
    if (!mesh_)
      throw Error ("[" + name_ + "::compute] no input mesh (setInputMesh)");
    options_.validate ();
    const std::size_t num_vertices = mesh_->vertices.size ();
    for (const auto& t : mesh_->triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] < 0 || static_cast<std::size_t> (t[k]) >= num_vertices)
          throw Error ("[" + name_ + "::compute] face index " + std::to_string (t[k]) + " out of range (" +
                       std::to_string (num_vertices) + " vertices)");
    if (!responses_.empty () && responses_.size () != num_vertices)
      throw Error ("[" + name_ + "::compute] " + std::to_string (responses_.size ()) + " responses for " +
                   std::to_string (num_vertices) + " vertices");
    if (topology_ && topology_->numVertices () != num_vertices)
      throw Error ("[" + name_ + "::compute] the topology (setTopology) is not the input mesh's");
    for (int k : keypoints_)
      if (k < 0 || static_cast<std::size_t> (k) >= num_vertices)
        throw Error ("[" + name_ + "::compute] keypoint " + std::to_string (k) + " out of range");
    computePatches (patches);
  }

  void
  FeatureAwarePatchSampling::computePatches (std::vector<Patch>& patches)
  {
    const int threads = num_threads_ > 0 ? num_threads_ : omp_get_max_threads ();
    const TriangleMesh& input = *mesh_;
    const int num_input = static_cast<int> (input.vertices.size ());
    MeshTopology own_topology;
    if (!topology_)
      own_topology = buildMeshTopology (input);
    const MeshTopology& input_topology = topology_ ? *topology_ : own_topology;

    // Default feature order: Harris 3D with its default options (METHOD.md step 3).
    used_responses_ = responses_;
    used_keypoints_ = keypoints_;
    if (responses_.empty () && keypoints_.empty ())
    {
      computeUnitScaleHarris3D (input, input_topology, num_threads_, used_responses_, used_keypoints_);
    }

    // Cut non-manifold edges and vertices: growth then cannot cross them.
    NonManifoldSplit split;
    const bool is_split = splitNonManifoldVertices (input, input_topology, split);
    MeshTopology split_topology;
    if (is_split)
      split_topology = buildMeshTopology (split.mesh);
    const MeshTopology& topology = is_split ? split_topology : input_topology;
    const TriangleMesh& mesh = is_split ? split.mesh : input;
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    auto originalOf = [&] (int v) { return is_split ? split.original[v] : v; };

    const PatchGrowthGeometry geometry = computePatchGrowthGeometry (mesh, topology);

    // Candidates on the input's vertices, each followed by its split copies.
    const std::vector<int> input_order = candidateOrder (num_input, used_responses_, used_keypoints_);
    std::vector<int> order;
    order.reserve (num_vertices);
    {
      std::vector<int> copy_offsets (num_input + 1, 0), copies (num_vertices - num_input);
      for (int v = num_input; v < num_vertices; ++v)
        ++copy_offsets[originalOf (v) + 1];
      std::partial_sum (copy_offsets.begin (), copy_offsets.end (), copy_offsets.begin ());
      std::vector<int> cursor (copy_offsets.begin (), copy_offsets.end () - 1);
      for (int v = num_input; v < num_vertices; ++v)
        copies[cursor[originalOf (v)]++] = v;
      for (int v : input_order)
      {
        order.push_back (v);
        for (int i = copy_offsets[v]; i < copy_offsets[v + 1]; ++i)
          order.push_back (copies[i]);
      }
    }

    std::vector<std::uint8_t> referenced (num_vertices, 0);
    for (int v = 0; v < num_vertices; ++v)
      referenced[v] = topology.facesOf (v).size () > 0;
    const int target = static_cast<int> (std::count (referenced.begin (), referenced.end (), 1));

    // Sampling loop (METHOD.md step 4), sequential by nature. (Growing the next candidates speculatively
    // in parallel gives the same output, but on a loaded machine the per-batch barriers cost more than
    // they save: measured 3-6x slower with 2 threads while other jobs ran, so it was dropped.)
    PatchGrower grower (mesh, topology, geometry, options_);
    std::vector<std::uint8_t> covered (num_vertices, 0), invalid (num_vertices, 0);
    int num_covered = 0;
    Patch patch;
    auto keep = [&] (const Patch& p) {
      for (int u : p.vertices)
        if (!covered[u])
        {
          covered[u] = 1;
          ++num_covered;
        }
      patches.push_back (p);
    };
    const int progress_step = std::max (1, target / 100);
    int next_progress = 0;
    for (int v : order)
    {
      if (num_covered >= target)
        break;
      if (invalid[v] || !referenced[v])
        continue;
      ++num_grown_;
      const double radius = grower.grow (v, patch);
      if (static_cast<int> (patch.size ()) < options_.min_patch_size)
        continue;
      if (std::all_of (patch.vertices.begin (), patch.vertices.end (), [&] (int u) { return covered[u] != 0; }))
        continue;
      keep (patch);
      const double reach = options_.sigma * radius;
      for (int u : patch.vertices)
        if ((mesh.vertices[u] - mesh.vertices[v]).norm () < reach)
          invalid[u] = 1;
      invalid[v] = 1;
      if (progress_ && num_covered >= next_progress)
      {
        progress_ ("patches", static_cast<double> (num_covered) / std::max (1, target));
        next_progress = num_covered + progress_step;
      }
    }
    const std::size_t num_sampled = patches.size ();

    // Coverage pass (ours): a vertex the loop left uncovered seeds its own patch, whatever its size. Such
    // vertices are mostly on creases or in strips of faces between creases, where no vertex normal is
    // within delta of the faces, so the method's growth from them stops at once. Growth from each of
    // their faces, with smooth variation between adjacent faces (growFromFace), covers whole strips: the
    // variant covering most uncovered vertices is kept (ties: the larger patch, then the method's growth,
    // then the lowest face).
    if (options_.cover_all_vertices)
    {
      Patch trial;
      auto newlyCovered = [&] (const Patch& p) {
        return std::count_if (p.vertices.begin (), p.vertices.end (), [&] (int u) { return covered[u] == 0; });
      };
      for (int v : order)
      {
        if (num_covered >= target)
          break;
        if (covered[v] || !referenced[v])
          continue;
        grower.grow (v, patch);
        long best = newlyCovered (patch);
        for (int f : topology.facesOf (v))
        {
          if (!(geometry.face_areas[f] > 0.0))
            continue;
          grower.growFromFace (v, f, trial);
          const long n = newlyCovered (trial);
          if (n > best || (n == best && trial.size () > patch.size ()))
          {
            best = n;
            std::swap (patch, trial);
          }
        }
        keep (patch);
      }
    }
    if (progress_)
      progress_ ("patches", 1.0);
    for (int v = 0; v < num_vertices; ++v)
      if (!referenced[v] && originalOf (v) == v)
      {
        unreferenced_.push_back (v);
        if (options_.cover_unreferenced_vertices)
        {
          grower.grow (v, patch);
          keep (patch);
        }
      }
    num_coverage_patches_ = patches.size () - num_sampled;

    // Frames (METHOD.md step 6), in parallel: one output per patch.
    double global_edge = 0.0;
    if (!topology.edges.empty ())
    {
      for (const auto& e : topology.edges)
        global_edge += (mesh.vertices[e[1]] - mesh.vertices[e[0]]).norm ();
      global_edge /= static_cast<double> (topology.edges.size ());
    }
    if (!(global_edge > 0.0) || !std::isfinite (global_edge))
      global_edge = 1.0;
    frame_kinds_.resize (patches.size ());
    const int num_patches = static_cast<int> (patches.size ());
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
    for (int i = 0; i < num_patches; ++i)
    {
      Patch& p = patches[i];
      const double guard = meanEdgeLength (mesh, topology, p.seed);
      const Eigen::Vector3d& seed_normal =
        p.seed_face >= 0 ? geometry.face_normals[p.seed_face] : geometry.vertex_normals[p.seed];
      frame_kinds_[i] = computePatchFrame (mesh, seed_normal, guard > 0.0 ? guard : global_edge, p);
    }

    // Back to the input's vertex indices; a patch holding two copies of one vertex keeps the first.
    if (is_split)
    {
      std::vector<std::uint8_t> seen (num_input, 0);
      for (Patch& p : patches)
      {
        p.seed = originalOf (p.seed);
        std::size_t n = 0;
        for (std::size_t i = 0; i < p.vertices.size (); ++i)
        {
          const int o = originalOf (p.vertices[i]);
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
    if (!options_.cover_unreferenced_vertices)
      uncovered_ = unreferenced_;
    if (!options_.cover_all_vertices)
    {
      std::vector<std::uint8_t> in_patch (num_input, 0);
      for (const Patch& p : patches)
        for (int v : p.vertices)
          in_patch[v] = 1;
      uncovered_.clear ();
      for (int v = 0; v < num_input; ++v)
        if (!in_patch[v])
          uncovered_.push_back (v);
    }
  }
} // namespace pcl_sparse
