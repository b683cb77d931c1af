#pragma once
/// \file sparse_surface_resampling.h
/// Resampling a SparseSurfaceModel into a pcl::PointCloud<PointOutT> at any density (docs/METHOD.md step 12):
/// the main use of the representation.
///
///   pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> resampling;  // or PointXYZ, PointXYZRGBNormal, ...
///   resampling.setInputModel (model);
///   resampling.setPointCount (100000);                               // or setDensity / setSpacing
///   pcl::PointCloud<pcl::PointNormal> cloud;
///   resampling.compute (cloud);
///
/// The output point type takes what it has fields for: x y z always, normal_x.. and curvature where it
/// has them (PointNormal is filled directly; other types are copied from it field by field), and r g b
/// (a) and intensity from the model's attribute codes when it has them (point_attributes.h).
///
/// Each patch draws points only inside its own footprint and keeps those it owns (patch_ownership.h),
/// so overlaps do not double the density. Heights come from the codes, normals from the analytic
/// gradient, n = R normalise(-h_x, -h_y, 1), oriented like the frame's N (the encoder orients N like the
/// input's faces), and `curvature` is the signed mean curvature from the Hessian (patch_geometry.h:
/// +1/a on a sphere of radius a with outward normals; this is NOT PCL's surface variation).
///
/// Sampling is stratified by area: each patch lays a grid of cells of one expected point each over its
/// local plane (cell side 1 / (r_P sqrt(density)) in local units; at least 8 cells a side, smaller cells
/// weighing their share, on a patch of fewer points), jitters one candidate per cell, weights
/// it by the area element sqrt(1 + h_x^2 + h_y^2), and picks its points by systematic sampling along the
/// cells in serpentine order. This gives blue-noise-like spacing (nearest-neighbour distance CV 0.2 on
/// smooth models, about 0.22-0.27 on the shared meshes, against about 0.5 for uniform random points and
/// for PCL's MLS upsampling) and, with setPointCount, exactly the requested count: the total is split over
/// the patches by owned area (largest remainder). At high density, cells well inside or outside a
/// patch's owned part are classified by blocks (a quadtree over cell corners) instead of one by one.
/// Places where a code leaves its plausible range (|h| > 1, or steeper than 50 degrees from its frame: an
/// oscillating code of a tiny patch, or a patch reaching over an edge) are left to the overlapping patches
/// (PatchOwnershipOptions).
///
/// Deterministic: every random number is a hash of (seed, patch, cell, draw), patches run in parallel and
/// their points are concatenated in patch order, so the cloud is the same for any thread count.
///
/// Speed (bench/results/resample_speed.md): the first point of each cell, most points, is evaluated 32
/// places at a time (PatchEvaluator::sampleBlock, the same bits as one by one); with a count, the output
/// cloud is constructed by one thread while the others start the candidate pass.
///
/// Streaming (clouds larger than memory): compute (callback) hands the same points to a callback block by
/// block, in cloud order, with memory bounded by the block size (ResamplingStreamOptions) instead of the
/// point count (and the largest patch's candidates, about 20 bytes each). A first pass keeps only each
/// patch's weight (and the candidates of the first patches, up to a budget), the counts per patch follow as in the in-memory form, then each block draws again the
/// candidates of its patches that were not kept (the same hashes give the same candidates) and selects
/// its points; a patch cut by a block edge resumes where the previous block stopped. The points are bit
/// for bit those of compute (cloud), for any block size and thread count.
///
///   resampling.setPointCount (200000000);
///   std::unique_ptr<pcl_sparse::PointNormalStreamWriter> writer;   // io/cloud_stream_writer.h
///   resampling.compute ([&] (const pcl_sparse::ResampledBlock<pcl::PointNormal>& block) {
///     if (!writer)
///       writer = std::make_unique<pcl_sparse::PointNormalStreamWriter> ("huge.pcd", block.total);
///     writer->write (block.cloud);
///   });
///   writer->finish ();                                              // renames the complete file
///
/// The authors' code draws (r, angle) uniformly in the whole unit disk, which clusters points at the
/// centre and places points where the patch has no data; we sample uniformly by area inside the footprint.

#include <pcl_sparse/common/point_types.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/common/stage_base.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/patch_ownership.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Options of SparseSurfaceResampling.
  struct SparseSurfaceResamplingOptions
  {
    /// Seed of every random choice.
    std::uint64_t seed = 42;
    /// How far a candidate moves from its cell centre, as a fraction of the cell (1 = fully jittered
    /// sampling, 0 = a regular grid per patch). Nearest-neighbour CV grows with it (on the shared meshes
    /// about 0.22-0.26 at 0.4, 0.23-0.31 at 0.6, 0.28-0.35 at 0.8); below ~0.3 the rotated grids of the
    /// patches start to show. In [0, 1].
    double jitter = 0.4;
    /// Cap on the area element sqrt(1 + |grad h|^2) used as a place's weight (10: slopes up to 84 degrees
    /// count fully), so a patch whose code oscillates steeply cannot absorb the point budget. >= 1 (1:
    /// every place weighs the same), finite.
    double max_area_weight = 10.0;
    /// Largest number of cells per patch in the area pass that sizes the cells when a total count is
    /// requested (a quarter of the final pass's cells when that is fewer). >= 1.
    int area_pass_cells = 64;
    /// Ownership of overlapping places (its own ranges, PatchOwnershipOptions::validate).
    PatchOwnershipOptions ownership;

    /// Checks the ranges: jitter in [0, 1], max_area_weight >= 1 and finite, area_pass_cells >= 1, and
    /// ownership's (PatchOwnershipOptions::validate). Any seed is valid.
    /// \throws pcl_sparse::Error naming the first out-of-range field
    void validate () const;
  };

  /// Options of the streamed compute (SparseSurfaceResampling::compute with a callback). They bound its
  /// memory and never change the points.
  struct ResamplingStreamOptions
  {
    /// Largest number of points per block (2^21: 96 MB of pcl::PointNormal, plus 4 bytes of patch number
    /// per point). Larger blocks give the threads more patches to share.
    std::size_t block_points = std::size_t (1) << 21;
    /// Bytes of candidate places (about 20 per point) the weight pass may keep for the blocks (128 MB);
    /// the patches beyond it are drawn a second time in their block. A cloud whose candidates fit costs
    /// what an in-memory compute costs.
    std::size_t kept_candidate_bytes = std::size_t (128) << 20;
  };

  /// One block of a streamed compute: consecutive points of the cloud compute (cloud) would give.
  template <typename PointT>
  struct ResampledBlock
  {
    /// The block's points (one row, is_dense = true).
    pcl::PointCloud<PointT> cloud;
    /// Patch that produced each point.
    std::vector<int> patches;
    /// Attribute channels of each point, as getPointAttributes (empty unless the output type has colour
    /// or intensity and the model has attributes).
    std::vector<float> attributes;
    /// Index of the block's first point in the whole cloud.
    std::size_t first = 0;
    /// Number of points of the whole cloud (known from the first block on).
    std::size_t total = 0;
  };

  /// \brief What the resampling stage is, whatever the output point type: its input, density, options
  /// and the resampling itself into pcl::PointNormal. Use SparseSurfaceResampling<PointOutT>.
  class SparseSurfaceResamplingBase : public StageBase
  {
  public:
    using PointCloud = pcl::PointCloud<pcl::PointNormal>;

    /// Largest point count compute accepts (a guard against typos such as -n 1e12).
    static constexpr std::size_t max_points = 1000000000;

    /// \brief The model to resample. Tables built from it are kept across computes: call again after
    /// changing it.
    /// \param[in] model the sparse surface model
    void setInputModel (const SparseSurfaceModel::ConstPtr& model);
    const SparseSurfaceModel::ConstPtr& getInputModel () const { return model_; }

    /// \brief Exactly \a count points in total (1 .. max_points).
    void setPointCount (std::size_t count);
    /// \brief \a density points per unit of surface area (world units), in expectation.
    void setDensity (double density);
    /// \brief Mean spacing \a spacing between neighbouring points: density 1 / spacing^2.
    void setSpacing (double spacing);

    /// \brief The number of each patch of the model in a larger model it was cut from (a region of a tiled
    /// model, TiledModel::patchNumbers): random draws are keyed by it, so the region gives the points the
    /// whole model gives there. Empty (default): patch p is number p. Kept across computes.
    /// \param[in] numbers one per patch of the input model, increasing
    void setPatchNumbers (const std::vector<std::size_t>& numbers) { patch_numbers_ = numbers; }
    const std::vector<std::size_t>& getPatchNumbers () const { return patch_numbers_; }

    /// \brief Options (seed, jitter, ownership); compute checks them (SparseSurfaceResamplingOptions::validate).
    void setOptions (const SparseSurfaceResamplingOptions& options) { options_ = options; ownership_.reset (); }
    const SparseSurfaceResamplingOptions& getOptions () const { return options_; }

    /// \brief Block size and kept candidates of the streamed compute (never change the points).
    void setStreamOptions (const ResamplingStreamOptions& options) { stream_ = options; }
    const ResamplingStreamOptions& getStreamOptions () const { return stream_; }

    /// \brief Patch that produced each point of the last compute (empty after a streamed compute: each
    /// block has its own).
    const std::vector<int>& getPointPatches () const { return point_patches_; }
    /// \brief Attribute values of each point of the last compute, model->attribute_channels.size () per
    /// point, point after point (clamped to each channel's range). Empty unless the output type has
    /// colour or intensity and the model has attributes.
    const std::vector<float>& getPointAttributes () const { return point_attributes_; }
    /// \brief Surface area of the model (sum of owned areas) estimated by the last compute.
    double getEstimatedArea () const { return estimated_area_; }
    /// \brief Density used by the last compute (points per unit area).
    double getDensityUsed () const { return density_used_; }

  protected:
    SparseSurfaceResamplingBase () : StageBase ("SparseSurfaceResampling") {}

    /// \brief Checks the input and options, then resamples into \a output (replaced; one row,
    /// is_dense = true), and with \a with_attributes each point's attribute channels (getPointAttributes).
    /// Throws pcl_sparse::Error if no model, no basis, no patches, no density was set, the options are out
    /// of range (SparseSurfaceResamplingOptions::validate), or the density would give more than max_points
    /// points.
    void resample (PointCloud& output, bool with_attributes = false);

    /// \brief The streamed form of resample: the same points, handed to \a callback block by block in
    /// cloud order (at least one call: an empty cloud gives one empty block). Same checks and errors.
    void resampleBlocks (const std::function<void (const ResampledBlock<pcl::PointNormal>&)>& callback,
                         bool with_attributes = false);

    /// \brief The stage proper, after the checks.
    virtual void computeResampling (PointCloud& output);

  private:
    enum class Mode { None, Count, Density };
    struct Passes;
    struct BlockPlan;

    /// Throws unless the model, the density and the options can be resampled.
    void checkSetup () const;
    /// Builds the evaluator and ownership tables unless kept from the last compute.
    void prepareTables ();
    /// The density, then the candidate pass (drawAllCandidates) at it; sets the estimated area and the
    /// density used.
    void weighPatches (Passes& passes, PointCloud* prefill, std::size_t keep_bytes);

    /// Density for a total count, from a coarse pass measuring each patch's owned area.
    double densityForCount () const;
    /// Throws if \a density could give more than max_points points.
    void checkDensityBound (double density) const;
    /// Throws if a cloud of \a points held in memory would not fit in this machine's memory (about 90 bytes a
    /// point, measured): a clear error instead of an OOM kill or std::bad_alloc after minutes of work.
    void checkCloudFitsInMemory (double points) const;
    /// Candidate pass at \a density (redone once if a count is asked and the area is off by > 2 %).
    /// With \a prefill, one thread first constructs that cloud with count_ points (a few page faults per
    /// point, serial) while the others start on the patches.
    /// Each patch's candidates take at most \a keep_bytes in all: the others are dropped once weighed.
    void drawAllCandidates (double& density, Passes& passes, PointCloud* prefill, std::size_t keep_bytes) const;
    /// Points per patch: largest remainder of the weights for a count, else rounded at random.
    std::vector<std::size_t> pointsPerPatch (const std::vector<double>& weights) const;
    /// Selection pass: every patch writes its own slice of the output, in patch order (\a output is
    /// reconstructed unless \a prefilled and already of the right size).
    void selectAllPoints (const std::vector<std::size_t>& counts, Passes& passes, PointCloud& output, bool prefilled);
    /// Streamed selection: the points of blocks of at most stream_.block_points, each handed to \a callback.
    void streamAllPoints (const std::vector<std::size_t>& counts, Passes& passes,
                          const std::function<void (const ResampledBlock<pcl::PointNormal>&)>& callback);
    /// Draws the candidates a block's patches lack and cuts its patches into pieces for the threads.
    void planBlock (const std::vector<std::size_t>& offsets, std::size_t begin, std::size_t end, Passes& passes,
                    BlockPlan& plan) const;

    /// The number patch \a p has in the model random draws are keyed by (setPatchNumbers).
    std::size_t patchNumber (std::size_t p) const { return patch_numbers_.empty () ? p : patch_numbers_[p]; }

    SparseSurfaceModel::ConstPtr model_;
    SparseSurfaceResamplingOptions options_;
    std::vector<std::size_t> patch_numbers_;
    ResamplingStreamOptions stream_;
    Mode mode_ = Mode::None;
    std::size_t count_ = 0;
    double density_ = 0.0;
    // Built on the first compute, kept while the model and options are the same.
    std::shared_ptr<PatchEvaluator> evaluator_;
    std::shared_ptr<PatchOwnership> ownership_;
    std::vector<int> point_patches_;
    bool with_attributes_ = false;
    std::vector<float> point_attributes_;
    double estimated_area_ = 0.0;
    double density_used_ = 0.0;
  };

  /// \brief The resampling stage (PCL style): setInputModel, one of setPointCount / setDensity /
  /// setSpacing, then compute (cloud).
  /// \tparam PointOutT output point type (x y z needed; normals and curvature filled where it has them)
  template <typename PointOutT>
  class SparseSurfaceResampling : public SparseSurfaceResamplingBase
  {
  public:
    using Ptr = std::shared_ptr<SparseSurfaceResampling<PointOutT>>;
    using ConstPtr = std::shared_ptr<const SparseSurfaceResampling<PointOutT>>;
    using PointCloudOut = pcl::PointCloud<PointOutT>;

    /// \brief Resamples the model into \a output (replaced; organised as one row, is_dense = true; empty if it throws).
    /// Throws pcl_sparse::Error if no model, no basis, no patches, no density was set, the options are out
    /// of range (SparseSurfaceResamplingOptions::validate), the density would give more than max_points
    /// points, or the cloud would not fit in this machine's memory (resample in blocks then: compute
    /// with a BlockCallback).
    /// \param[out] output the resampled cloud
    void compute (PointCloudOut& output);

    /// What the streamed compute hands over: one block of the cloud.
    using Block = ResampledBlock<PointOutT>;
    /// Called once per block, in cloud order, from the calling thread.
    using BlockCallback = std::function<void (const Block&)>;

    /// \brief The streamed form, for clouds larger than memory: the points compute (cloud) would give, bit
    /// for bit, handed to \a callback in blocks of at most getStreamOptions ().block_points points (at
    /// least one call; an empty cloud gives one empty block). Memory is bounded by the block size and
    /// ResamplingStreamOptions::kept_candidate_bytes, not by the point count; it costs at most one more
    /// candidate pass than compute (cloud). The estimated area and density are set before the first call.
    /// Throws as compute (cloud) does, and passes on what \a callback throws (no further block is made).
    /// \param[in] callback receives each block (valid during the call only)
    void compute (const BlockCallback& callback);
  };
} // namespace pcl_sparse

#ifdef PCL_NO_PRECOMPILE
#include <pcl_sparse/resampling/impl/sparse_surface_resampling.hpp>
#else
#define PCL_SPARSE_EXTERN_RESAMPLING(T) extern template class pcl_sparse::SparseSurfaceResampling<T>;
PCL_SPARSE_FOR_EACH_OUTPUT_POINT_TYPE (PCL_SPARSE_EXTERN_RESAMPLING)
#undef PCL_SPARSE_EXTERN_RESAMPLING
#endif
