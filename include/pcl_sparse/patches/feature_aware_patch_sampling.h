#pragma once
/// \file feature_aware_patch_sampling.h
/// Feature-aware seed sampling and patch construction (docs/METHOD.md steps 4, 5 and 6) as a PCL-style stage.
///
///   pcl_sparse::FeatureAwarePatchSampling<pcl::PointXYZ> sampling;
///   sampling.setInputCloud (cloud);            // the vertices, and
///   sampling.setInputPolygons (polygons);      // the faces (or setInputMesh (TriangleMesh::ConstPtr))
///   sampling.setOptions (options);             // PatchOptions, paper defaults
///   sampling.setResponses (harris_responses);  // optional: per-vertex Harris 3D response (NaN: none)
///   sampling.setKeypoints (harris_keypoints);  // optional: keypoint vertex indices
///   std::vector<pcl_sparse::Patch> patches;
///   sampling.compute (patches);
///
/// Candidates are the keypoints by decreasing response, then every other vertex by decreasing response
/// (ties by index, vertices without a response last). Each candidate not marked invalid grows a patch
/// (patch_growth.h); the patch is kept if it has at least min_patch_size vertices and covers a vertex not
/// yet covered; then its vertices closer than sigma * r_P to the seed become invalid seeds. The loop stops
/// once every vertex is covered.
///
/// Coverage (our addition; the authors' code leaves 58 % of CAD-like meshes and 11.5 % of turbine.off
/// uncovered): after the loop, each still-uncovered vertex, in candidate order, seeds a patch of any size.
/// Such vertices sit on creases or in strips between creases, where no vertex normal is within delta of
/// the faces, so besides the method's growth the pass grows from each of the vertex's faces with smooth
/// variation measured between adjacent faces (PatchGrower::growFromFace) and keeps the variant covering
/// most uncovered vertices. A vertex without a proper face gets a one-vertex patch with a guarded frame
/// (radius = its mean edge length). Unreferenced vertices get one-vertex patches when
/// PatchOptions::cover_unreferenced_vertices (by default on scans only) and they lie farther from the faces
/// than PatchOptions::unreferenced_patch_spacings, else they are reported by getUncoveredVertices; NaN
/// vertices no face uses (the holes of a mesh made from an organized cloud) always are.
/// Non-manifold edges and vertices are cut first (non_manifold_split.h), so no patch crosses them.
///
/// Cost: one growth costs O(R log R) for the R vertices it visits, never O(#V); frames are fitted in
/// parallel. The output is the same for any thread count.

#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/surface/surface_stage.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_frame.h>
#include <pcl_sparse/patches/patch_options.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// \brief The default candidate order's input: Harris 3D responses and keypoints (default Harris3DOptions,
  /// \a num_threads OpenMP threads, 0 = default) computed on \a mesh scaled to a unit bounding-box
  /// diagonal. Harris 3D is not scale invariant (harris3d.h), so this makes the seeds, and everything
  /// downstream, independent of the mesh's length unit.
  /// \param[in] mesh the mesh
  /// \param[in] topology its topology
  /// \param[in] num_threads OpenMP threads (0 = default)
  /// \param[out] responses #V responses (NaN: none)
  /// \param[out] keypoints vertex indices, decreasing response
  /// \param[in] rings fixed ring count (> 0), or 0 for the adaptive neighbourhood (default)
  void
  computeUnitScaleHarris3D (const TriangleMesh& mesh, const MeshTopology& topology, int num_threads,
                            std::vector<double>& responses, std::vector<int>& keypoints, int rings = 0);

  /// \brief PatchOptions::harris_rings resolved for a surface: 0 means adaptive (0) on a mesh and 2 rings on
  /// a scan; < 0 adaptive (0); k > 0 stays k.
  inline int
  harrisRingsFor (int harris_rings, bool scan)
  {
    return harris_rings == 0 ? (scan ? 2 : 0) : std::max (0, harris_rings);
  }

  /// \brief The options whose defaults depend on the surface (harris_rings, max_fruitless_seeds,
  /// tail_pruning_after, max_patch_vertices, steep_frame_angle, cover_unreferenced_vertices,
  /// hidden_triangle_gap) resolved for a
  /// mesh or a scan, and delta replaced by lidar_delta on a lidar frame's rings.
  /// \param[in] options the options as given
  /// \param[in] scan    whether the surface is a scan's neighbourhood surface
  /// \param[in] lidar_rings  whether that surface joins a spinning lidar's rings (CloudNeighborhood::LidarRings)
  /// \return the options with those fields resolved
  inline PatchOptions
  patchOptionsFor (PatchOptions options, bool scan, bool lidar_rings = false)
  {
    if (lidar_rings && options.lidar_delta > 0.0)
      options.delta = options.lidar_delta;
    options.harris_rings = harrisRingsFor (options.harris_rings, scan);
    if (options.max_fruitless_seeds < 0)
      options.max_fruitless_seeds = scan ? 256 : 0;
    if (options.tail_pruning_after < 0.0)
      options.tail_pruning_after = scan ? 0.9 : 1.0;
    if (options.max_patch_vertices < 0)
      options.max_patch_vertices = scan ? 4096 : 0;
    if (options.steep_frame_angle < 0.0)
      options.steep_frame_angle = scan ? 0.0 : M_PI / 2.5;
    if (options.cover_unreferenced_vertices < 0)
      options.cover_unreferenced_vertices = scan ? 1 : 0;
    if (options.hidden_triangle_gap < 0.0)
      options.hidden_triangle_gap = scan ? 0.0 : 0.3;
    return options;
  }

  /// \brief Everything feature-aware patch sampling produces.
  struct PatchSamplingResult
  {
    std::vector<Patch> patches;              ///< with frames, radii and local coordinates
    std::vector<double> responses;           ///< responses the candidates were ordered by (given or Harris 3D)
    std::vector<int> keypoints;              ///< keypoints tried first (given or Harris 3D)
    std::vector<int> uncovered;              ///< vertices in no patch, ascending
    std::vector<int> unreferenced;           ///< vertices no face uses, ascending
    std::size_t num_coverage_patches = 0;    ///< patches (a suffix) added by the coverage pass and kept
    std::size_t num_redundant = 0;           ///< patches dropped as redundant (PatchOptions::drop_redundant_patches)
    std::size_t num_merged = 0;              ///< patches merged into neighbours (PatchOptions::merge_own_elements)
    std::size_t num_completed_faces = 0;     ///< faces face completion added to a patch (complete_faces)
    /// Proper faces (area > 0) in no patch after face completion, ascending (with complete_faces; empty
    /// without it).
    std::vector<int> uncovered_faces;
    std::size_t num_grown = 0;               ///< seeds grown by the sampling loop, kept or not
    std::vector<PatchFrameKind> frame_kinds; ///< how each patch's frame was chosen
  };

  /// \brief Feature-aware seed sampling, patch growth and frames of a whole mesh (the stage's mathematics).
  /// \param[in] mesh the mesh (face indices in range)
  /// \param[in] topology buildMeshTopology (mesh)
  /// \param[in] options seed sampling and growth options
  /// \param[in] responses #V feature responses ordering the candidates (NaN: none), or empty
  /// \param[in] keypoints vertex indices tried first; with \a responses empty too, Harris 3D gives both
  /// \param[in] num_threads OpenMP threads (0 = default); the result does not depend on it
  /// \param[in] progress progress callback (may be empty)
  /// \param[in] point_normals #V unit normals to grow and frame patches with (a scan's PCA normals; see
  ///            computePatchGrowthGeometry), or empty (default) for the mesh's own
  /// \param[in] seed_vertices empty (default: every vertex may seed a patch and must be covered), or #V
  ///            flags: only flagged vertices seed patches and must be covered, the others are surface the
  ///            patches may grow over (a tile's margin, tiles/tiled_surface_encoder.h)
  /// \return the patches and what the sampling saw
  /// Throws pcl_sparse::Error for options out of range, face indices out of range, or responses /
  /// keypoints / normals that do not fit the mesh.
  PatchSamplingResult
  sampleFeatureAwarePatches (const TriangleMesh& mesh, const MeshTopology& topology, const PatchOptions& options,
                             const std::vector<double>& responses, const std::vector<int>& keypoints, int num_threads,
                             const ProgressCallback& progress, const std::vector<Eigen::Vector3d>& point_normals = {},
                             const std::vector<std::uint8_t>& seed_vertices = {});

  /// \brief Feature-aware patch sampling as a PCL-style stage (input: see SurfaceStage).
  /// \tparam PointInT point type of the input cloud
  template <typename PointInT>
  class FeatureAwarePatchSampling : public SurfaceStage<PointInT>
  {
  public:
    using Ptr = std::shared_ptr<FeatureAwarePatchSampling<PointInT>>;
    using ConstPtr = std::shared_ptr<const FeatureAwarePatchSampling<PointInT>>;

    FeatureAwarePatchSampling () : SurfaceStage<PointInT> ("FeatureAwarePatchSampling", IndexUse::CropSurface) {}

    /// \brief Seed sampling and growth options (paper defaults).
    void setOptions (const PatchOptions& options) { options_ = options; }
    const PatchOptions& getOptions () const { return options_; }

    /// \brief Per-vertex feature response ordering the candidates (#V entries, NaN = none). Empty (default),
    /// with no keypoints either: computeUnitScaleHarris3D (Harris 3D, default options, unit-diagonal scale).
    void setResponses (const std::vector<double>& responses) { responses_ = responses; }
    /// \brief Keypoints tried first (vertex indices). Empty with empty responses (default): Harris 3D
    /// keypoints. Empty with responses given: no keypoints, candidates purely by response.
    void setKeypoints (const std::vector<int>& keypoints) { keypoints_ = keypoints; }

    /// \brief Partitions the surface into overlapping patches, each with its frame, radius and local
    /// coordinates. Throws pcl_sparse::Error for a missing input, invalid face indices, options out of
    /// range or responses / keypoints that do not fit the surface.
    /// \param[out] patches the patches (replaced)
    void compute (std::vector<Patch>& patches);

    /// \brief Responses and keypoints the last compute ordered its candidates with (given or Harris 3D).
    const std::vector<double>& getResponses () const { return result_.responses; }
    const std::vector<int>& getKeypoints () const { return result_.keypoints; }

    /// \brief Vertices in no patch after the last compute (unreferenced vertices unless
    /// cover_unreferenced_vertices, which by default holds on scans only, and then those next to the faces,
    /// unreferenced_patch_spacings), ascending.
    const std::vector<int>& getUncoveredVertices () const { return result_.uncovered; }
    /// \brief Vertices no face uses (ascending), whatever the option.
    const std::vector<int>& getUnreferencedVertices () const { return result_.unreferenced; }
    /// \brief Patches (a suffix of the output) added by the coverage pass, not by the sampling loop.
    std::size_t getNumCoveragePatches () const { return result_.num_coverage_patches; }
    /// \brief Patches dropped as redundant (PatchOptions::drop_redundant_patches).
    std::size_t getNumRedundantPatches () const { return result_.num_redundant; }
    /// \brief Patches merged into their neighbours (PatchOptions::merge_own_elements).
    std::size_t getNumMergedPatches () const { return result_.num_merged; }
    /// \brief Seeds grown by the sampling loop, kept or not (cost indicator).
    std::size_t getNumGrownSeeds () const { return result_.num_grown; }
    /// \brief How each output patch's frame was chosen.
    const std::vector<PatchFrameKind>& getFrameKinds () const { return result_.frame_kinds; }

  protected:
    /// \brief The stage proper, on the surface initCompute prepared.
    virtual void computePatches (std::vector<Patch>& patches);

    PatchOptions options_;
    std::vector<double> responses_;
    std::vector<int> keypoints_;
    PatchSamplingResult result_;
  };
} // namespace pcl_sparse

#ifdef PCL_NO_PRECOMPILE
#include <pcl_sparse/patches/impl/feature_aware_patch_sampling.hpp>
#else
#define PCL_SPARSE_EXTERN_PATCH_SAMPLING(T) extern template class pcl_sparse::FeatureAwarePatchSampling<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_EXTERN_PATCH_SAMPLING)
#undef PCL_SPARSE_EXTERN_PATCH_SAMPLING
#endif
