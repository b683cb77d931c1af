#pragma once
/// \file sparse_surface_encoder.h
/// The whole encoding pipeline as one PCL-style stage (docs/METHOD.md steps 2-11):
///
///   pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZ> encoder;
///   encoder.setInputCloud (cloud);                 // the mesh's vertices, and
///   encoder.setInputPolygons (polygons);           // its faces (or setInputMesh (TriangleMesh::ConstPtr))
///   encoder.setOptions (options);                  // SparseSurfaceEncoderOptions (defaults: see it)
///   pcl_sparse::SparseSurfaceModel model;
///   encoder.compute (model);
///   const pcl_sparse::ModelStatistics stats = model.statistics (pcl_sparse::cloudPositions (*cloud));
///
/// Stages: feature-aware seed sampling and patch growth with frames (FeatureAwarePatchSampling, which
/// runs Harris 3D), then per patch the sparse coding (patch_coder.h) in parallel over patches, each patch
/// writing only its own output slot, so the model is identical for any thread count.

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/patch_coder.h>
#include <pcl_sparse/model/surface_basis.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/surface/surface_stage.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/model/attribute_gaps.h>
#include <pcl_sparse/model/vertex_attributes.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_options.h>
#include <pcl_sparse/resampling/flipped_places.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Every parameter of the pipeline. Defaults are the paper's numbers (delta = pi/6, eta = 1.01,
  /// rho = 0.001, sigma = 0.8, f = 0.5, L = 12, eps = 0.01, m_min = 64, 144 cosine atoms) where they
  /// measured best, and otherwise what did (README, issue 13): the half-period cosines and the quadric (DctQuadric), the authors'
  /// 72-degree cone instead of the paper's 90, our pairwise cone, face completion, extra samples per
  /// triangle, footprints clipped at their border and the compression bound (CR <= 1).
  /// encoderPresetOptions (EncoderPreset::Paper) gives the paper's configuration.
  struct SparseSurfaceEncoderOptions
  {
    PatchOptions patches;             ///< seed sampling and growth: rho, delta, cone_angle, eta, sigma, ...
    SparseCodingOptions coding;       ///< f, Nyquist rule, L, eps, m_min, footprint angles, seed
    int dictionary_frequencies = 12;  ///< n: the cosine dictionary has n^2 atoms (paper: 12, 144 atoms)
    /// Atoms: DctQuadric (default) = the half-period cosines and the monomials x, y, x^2, x y, y^2 (ours:
    /// the quadric codes a curved patch's bulk, which cosines reach only slowly; lower RMSE than Dct on
    /// every shared mesh at about the same bytes, bench/results/quadric_basis.md); Dct = cos(i pi (x + 1) / 2)
    /// cos(j pi (y + 1) / 2), even and odd (ours: a tilt or an offset left by the frame costs one atom);
    /// Paper = cos(i pi x) cos(j pi y), the paper's, same count, even only. Ignored after setBasis.
    CosineBasisKind basis = CosineBasisKind::DctQuadric;
    /// For a scan (a cloud without polygons, or setInputScan) with coding.noise_level 0: code down to the
    /// scan's estimated noise (CloudSurface::noise) and not below, so that sensor noise is smoothed, not
    /// coded (docs/METHOD.md, scans). Meshes are never affected.
    bool scan_noise_floor = true;
    /// Colour / intensity coding (only when the input has them): L per channel, RMS tolerance.
    AttributeCodingOptions attributes;
    /// Never bigger than the input (ours, issue 13): a model whose compression ratio (13 M + nnz) / (3 N_V)
    /// exceeds this is made cheaper, measured rather than guessed. The patches are sampled again with each
    /// growth floor of budget_growth_floors (PatchOptions::min_growth_vertices: fewer, larger patches where
    /// rho allowed only a few vertices each), with sigma and budget_sigma; every candidate whose frames fit is coded and trimmed to the
    /// coefficients the bound leaves (allocateAtoms: the atoms that remove least error go first), and the
    /// candidate with the lowest RMSE is kept. A model within the bound is not touched. On meshes whose
    /// triangles are large against rho A (bunny-npm-1k, fertility, cheese-cgal at rho 0.001) this keeps
    /// CR <= 1 at the price of some accuracy (bench/results/meshes.md). 0 = no bound (the paper).
    double max_compression_ratio = 1.0;
    /// Growth floors tried when the model exceeds max_compression_ratio (the first candidate is the
    /// model's own patches), with 0 meaning the model's own floor; a candidate with the same patch and
    /// vertex counts as an earlier one is skipped.
    std::vector<int> budget_growth_floors = {0, 16, 24, 32};
    /// The floors are tried with PatchOptions::sigma and with this larger overlap control too: with
    /// sigma >= 1 nearly every vertex of a kept patch stops being a seed, so patches overlap less
    /// (about one patch per vertex instead of two on bunny-npm-1k) and the frames cost less.
    double budget_sigma = 1.2;
    /// Rate against distortion (ours, issue 13): the atoms that buy least are left out for as long as the
    /// model's squared error grows by at most this fraction (allocateAtomsWithinLoss over patchAtomGains:
    /// the patches' residuals over their samples, each weighted by the vertices it answers for). OMP stops
    /// at L atoms on nearly every patch, and its last atoms fit little: at 0.2 (an RMSE about 10 % higher)
    /// the default files of the shared meshes are 0-22 % smaller and resample up to 20 % farther from the
    /// mesh, on 19 of 22 meshes fewer bytes at equal distance than L = 10 (bench/results/atom_loss.md).
    /// A patch facing another across a knife edge or a thin part keeps the atoms that hold its heights within
    /// a third of resampling's clearance there (PatchOwnershipOptions::opposite_clearance: 0.01 of its radius;
    /// a code moved further crosses it); scans are left alone (their codes stop at their noise floor).
    /// 0 = every code as OMP made it (the default and the `paper` preset).
    double atom_loss_allowance = 0.0;
    /// Footprints drawn in where resampling would emit a place whose code's normal points away from the
    /// input surface (trimFlippedPlaces, ours, issue 13): the flipped normals of the default resampling.
    /// Off in the `paper` preset (the paper's footprints).
    bool trim_flipped_places = true;
    /// The angle, rays and rounds of that check.
    FlippedPlaceOptions flipped_places;

    /// Throws pcl_sparse::Error naming the first option out of range ("SparseSurfaceEncoderOptions:
    /// coding.tolerance = 2 is out of range (0 < eps < 1)"): the patch options, rho > 0, 0 <= f <= 1,
    /// L >= 1, eps in (0, 1), quadric preference in [0, 1], m_min in [0, 100000], footprint angles in
    /// [3, 4096], triangle samples in [0, 16], n in [1, 64], attribute L >= 1 and tolerance >= 0,
    /// max_compression_ratio >= 0, growth floors >= 0, budget_sigma >= 0, atom_loss_allowance >= 0,
    /// flipped_places (FlippedPlaceOptions::validate).
    void validate () const;
  };

  /// Named option sets: Default (the struct's defaults, what measures best) and Paper (the paper's
  /// configuration: its cosine atoms, its normal cone of pi / 2 around the seed's normal only (no pairwise
  /// cone), no face completion, no extra samples per triangle, footprints not clipped at their border and no
  /// bound on the compression ratio, every code as OMP made it (no atom loss allowance); every other default
  /// already is the paper's value).
  enum class EncoderPreset
  {
    Default,
    Paper
  };

  /// The options of a preset.
  /// \param[in] preset the preset
  /// \return its options (valid)
  SparseSurfaceEncoderOptions
  encoderPresetOptions (EncoderPreset preset);

  /// The preset named \a name ("default" or "paper").
  /// \param[in] name the name
  /// \return the preset
  /// \throws pcl_sparse::Error for any other name
  EncoderPreset
  encoderPresetFromName (const std::string& name);

  /// Wall-clock seconds of the stages of the last compute().
  struct EncoderTimings
  {
    double patches = 0.0;  ///< Harris 3D, seed sampling, patch growth, frames
    double coding = 0.0;   ///< samples, Nyquist cap, OMP, footprints
    double total = 0.0;
  };

  /// \brief Everything one encoding produces besides the model.
  struct SurfaceEncoding
  {
    std::vector<Patch> patches;               ///< one per model patch, with frames and local coordinates
    std::vector<PatchCodingInfo> coding_info; ///< one per model patch
    EncoderTimings timings;
    FlippedPlaceTrim flipped_places;          ///< what trim_flipped_places cut
  };

  /// \brief Whether some face of \a mesh has a finite, non-zero area (faces with invalid indices count as
  /// having one: they are left to the patch stage, which names them).
  /// \param[in] mesh the mesh
  bool
  hasSurfaceArea (const TriangleMesh& mesh);

  /// \brief Why \a mesh (placed at \a origin) is outside the scales the encoder handles, or an empty string.
  /// Coordinates beyond 1e30 are refused, as the resampling refuses models there (float clouds), and so
  /// is a bounding-box diagonal under 1e-30: squared lengths of such meshes over- or underflow in double
  /// (fandisk scaled by 1e100 or 1e-150 gave 5x its patches and no atom, without a word).
  /// \param[in] mesh the mesh (its finite vertices count)
  /// \param[in] origin where its local frame lies (a scan's surface is centred)
  std::string
  coordinateRangeProblem (const TriangleMesh& mesh, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero ());

  /// \brief The whole encoding of a mesh (the stage's mathematics): patches, then every patch coded.
  /// \param[in] mesh the mesh, with at least one face of non-zero area
  /// \param[in] topology buildMeshTopology (mesh)
  /// \param[in] options validated options
  /// \param[in] basis the basis to code over
  /// \param[in] num_threads OpenMP threads (0 = default); the model does not depend on it
  /// \param[in] progress progress callback (may be empty)
  /// \param[out] model the model (replaced)
  /// \return the patches, coding diagnostics and timings
  SurfaceEncoding
  encodeSurface (const TriangleMesh& mesh, const MeshTopology& topology, const SparseSurfaceEncoderOptions& options,
                 const SurfaceBasis::ConstPtr& basis, int num_threads, const ProgressCallback& progress,
                 SparseSurfaceModel& model);

  /// \brief The same with colour / intensity: every patch also codes each channel of \a attributes
  /// (patch_attribute_coder.h) and the model gets their channels (SparseSurfaceModel::attribute_channels).
  /// The geometry is exactly that of the encoding without attributes. Throws pcl_sparse::Error for
  /// attributes that do not fit the mesh (VertexAttributes::validate).
  /// \param[in] mesh the mesh, with at least one face of non-zero area
  /// \param[in] attributes one row per vertex of \a mesh; empty: as encodeSurface without them
  /// \param[in] topology buildMeshTopology (mesh)
  /// \param[in] options validated options (options.attributes: the attribute coding)
  /// \param[in] basis the basis to code the height over
  /// \param[in] num_threads OpenMP threads (0 = default); the model does not depend on it
  /// \param[in] progress progress callback (may be empty)
  /// \param[out] model the model (replaced)
  /// \param[in] point_normals #V unit normals to grow and frame patches with (a scan's PCA normals,
  ///            sampleFeatureAwarePatches), or empty (default) for the mesh's own
  /// \param[in] seed_vertices empty (default), or #V flags: only flagged vertices seed patches and must be
  ///            covered (sampleFeatureAwarePatches; a tile's core, tiles/tiled_surface_encoder.h)
  /// \return the patches, coding diagnostics and timings
  SurfaceEncoding
  encodeSurface (const TriangleMesh& mesh, const VertexAttributes& attributes, const MeshTopology& topology,
                 const SparseSurfaceEncoderOptions& options, const SurfaceBasis::ConstPtr& basis, int num_threads,
                 const ProgressCallback& progress, SparseSurfaceModel& model,
                 const std::vector<Eigen::Vector3d>& point_normals = {},
                 const std::vector<std::uint8_t>& seed_vertices = {});

  /// \brief The encoder as a PCL-style stage (input: see SurfaceStage).
  /// \tparam PointInT point type of the input cloud
  template <typename PointInT>
  class SparseSurfaceEncoder : public SurfaceStage<PointInT>
  {
  public:
    using Ptr = std::shared_ptr<SparseSurfaceEncoder<PointInT>>;
    using ConstPtr = std::shared_ptr<const SparseSurfaceEncoder<PointInT>>;

    SparseSurfaceEncoder () : SurfaceStage<PointInT> ("SparseSurfaceEncoder", IndexUse::CropSurface) {}

    /// \brief Every parameter of the pipeline (defaults: SparseSurfaceEncoderOptions).
    void setOptions (const SparseSurfaceEncoderOptions& options) { options_ = options; }
    const SparseSurfaceEncoderOptions& getOptions () const { return options_; }

    /// \brief A basis other than the cosine dictionary (optional; default: makeCosineBasis (basis, n)).
    void setBasis (const SurfaceBasis::ConstPtr& basis) { basis_ = basis; }

    /// \brief Colour / intensity per input point (or mesh vertex, or scan point), coded with the geometry.
    /// Without it, a cloud input (with or without polygons) whose point type has rgb / rgba or intensity
    /// gives them automatically (channels r g b [a] and / or intensity), and so does a scan
    /// (setInputScan) with colours or intensities; a TriangleMesh input has none. With setIndices cropping,
    /// and for the points a scan's cleaning keeps, the rows of the surface's points are used. A pointer to
    /// an empty VertexAttributes codes none (geometry only); an empty pointer goes back to automatic.
    /// A value that is not a number (a sensor's missing intensity) takes the nearest surface point's, and a
    /// channel with no value at all is left out (fillAttributeGaps; getAttributeGaps says what changed).
    /// \param[in] attributes one row per input point (cloud), vertex (mesh) or point (setInputScan)
    void setVertexAttributes (const VertexAttributes::ConstPtr& attributes) { attributes_ = attributes; }
    const VertexAttributes::ConstPtr& getVertexAttributes () const { return attributes_; }

    /// \brief Restricts the seeds (the encoding of one tile of a larger input, tiles/tiled_surface_encoder.h):
    /// only flagged points seed patches, and only they must be covered; the others are surface the patches
    /// may grow over. Rows as setVertexAttributes (per input point, vertex or scan point). An empty pointer
    /// (default): every point seeds and is covered.
    /// \param[in] seed_vertices one flag per input point (cloud), vertex (mesh) or point (setInputScan)
    void setSeedVertices (const std::shared_ptr<const std::vector<std::uint8_t>>& seed_vertices) { seed_vertices_ = seed_vertices; }

    /// \brief Encodes the surface into \a model (replacing its content). Throws pcl_sparse::Error for a
    /// missing or empty surface, one without area, and options out of range.
    /// \param[out] model the sparse surface model
    void compute (SparseSurfaceModel& model);

    /// \brief Wall-clock seconds of the stages of the last compute.
    const EncoderTimings& getTimings () const { return encoding_.timings; }
    /// \brief The patches of the last compute (with frames and local coordinates), one per model patch.
    const std::vector<Patch>& getPatches () const { return encoding_.patches; }
    /// \brief Per-patch diagnostics of the last compute, one per model patch.
    const std::vector<PatchCodingInfo>& getCodingInfo () const { return encoding_.coding_info; }
    /// What the last compute() drew in at flipped places (SparseSurfaceEncoderOptions::trim_flipped_places).
    const FlippedPlaceTrim& getFlippedPlaceTrim () const { return encoding_.flipped_places; }
    /// \brief The attribute values of the last compute that were not numbers and were filled, and the
    /// channels left out for having none (see setVertexAttributes).
    const AttributeGaps& getAttributeGaps () const { return attribute_gaps_; }

  protected:
    /// \brief The stage proper, on the surface initCompute prepared.
    virtual void computeModel (SparseSurfaceModel& model);

    /// \brief The attributes of the surface's vertices: setVertexAttributes, else the input cloud's or scan's
    /// colour / intensity (none for a mesh), for the points the surface kept; empty when there are none.
    VertexAttributes surfaceAttributes () const;
    /// \brief setSeedVertices' flags for the surface's vertices (empty when none were set).
    std::vector<std::uint8_t> surfaceSeedVertices () const;

    SparseSurfaceEncoderOptions options_;
    SurfaceBasis::ConstPtr basis_;
    VertexAttributes::ConstPtr attributes_;
    std::shared_ptr<const std::vector<std::uint8_t>> seed_vertices_;
    SurfaceEncoding encoding_;
    AttributeGaps attribute_gaps_;
  };
} // namespace pcl_sparse

#ifdef PCL_NO_PRECOMPILE
#include <pcl_sparse/encoder/impl/sparse_surface_encoder.hpp>
#else
#define PCL_SPARSE_EXTERN_ENCODER(T) extern template class pcl_sparse::SparseSurfaceEncoder<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_EXTERN_ENCODER)
#undef PCL_SPARSE_EXTERN_ENCODER
#endif
