#pragma once
/// \file sparse_surface_encoder.h
/// The whole encoding pipeline as one PCL-style stage (METHOD.md steps 2-11):
///
///   pcl_sparse::SparseSurfaceEncoder encoder;
///   encoder.setInputMesh (mesh);        // TriangleMesh::ConstPtr
///   encoder.setOptions (options);       // SparseSurfaceEncoderOptions, paper defaults
///   pcl_sparse::SparseSurfaceModel model;
///   encoder.compute (model);
///   const pcl_sparse::ModelStatistics stats = model.statistics (mesh->vertices);
///
/// Stages: feature-aware seed sampling and patch growth with frames (FeatureAwarePatchSampling, which
/// runs Harris 3D), then per patch the sparse coding (patch_coder.h) in parallel over patches, each patch
/// writing only its own output slot, so the model is identical for any thread count.

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/patch_coder.h>
#include <pcl_sparse/model/surface_basis.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/patches/patch.h>
#include <pcl_sparse/patches/patch_options.h>

#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// Every parameter of the pipeline. Defaults are the paper's (delta = pi/6, cone pi/2, eta = 1.01,
  /// rho = 0.001, sigma = 0.8, f = 0.5, L = 12, eps = 0.01, m_min = 64, 144 cosine atoms).
  struct SparseSurfaceEncoderOptions
  {
    PatchOptions patches;             ///< seed sampling and growth: rho, delta, cone_angle, eta, sigma, ...
    SparseCodingOptions coding;       ///< f, Nyquist rule, L, eps, m_min, footprint angles, seed
    int dictionary_frequencies = 12;  ///< n: the cosine dictionary has n^2 atoms (paper: 12, 144 atoms)
    /// Cosine atoms: Paper = cos(i pi x) cos(j pi y) (the paper's, even only); Dct = cos(i pi (x + 1) / 2)
    /// cos(j pi (y + 1) / 2), same count, even and odd (ours, lower error floor). Ignored after setBasis.
    CosineBasisKind basis = CosineBasisKind::Paper;

    /// Throws pcl_sparse::Error naming the first option out of range: the patch options, rho > 0,
    /// 0 <= f <= 1, L >= 1, eps in (0, 1), m_min >= 0, footprint angles >= 3, n in [1, 64].
    void validate () const;
  };

  /// Wall-clock seconds of the stages of the last compute().
  struct EncoderTimings
  {
    double patches = 0.0;  ///< Harris 3D, seed sampling, patch growth, frames
    double coding = 0.0;   ///< samples, Nyquist cap, OMP, footprints
    double total = 0.0;
  };

  class SparseSurfaceEncoder
  {
  public:
    using Ptr = std::shared_ptr<SparseSurfaceEncoder>;
    using ConstPtr = std::shared_ptr<const SparseSurfaceEncoder>;

    SparseSurfaceEncoder () = default;
    virtual ~SparseSurfaceEncoder () = default;

    /// The mesh to encode (required).
    void setInputMesh (const TriangleMesh::ConstPtr& mesh) { mesh_ = mesh; }
    const TriangleMesh::ConstPtr& getInputMesh () const { return mesh_; }

    void setOptions (const SparseSurfaceEncoderOptions& options) { options_ = options; }
    const SparseSurfaceEncoderOptions& getOptions () const { return options_; }

    /// A basis other than the cosine dictionary (optional; default: makeCosineBasis (basis, n)).
    void setBasis (const SurfaceBasis::ConstPtr& basis) { basis_ = basis; }

    /// OpenMP threads (0 = OpenMP's default). The model does not depend on it.
    void setNumberOfThreads (int threads) { num_threads_ = threads; }
    void setProgressCallback (const ProgressCallback& progress) { progress_ = progress; }

    /// Encodes the mesh into \a model (replacing its content). Throws pcl_sparse::Error for a missing
    /// or empty mesh and options out of range.
    void compute (SparseSurfaceModel& model);

    const EncoderTimings& getTimings () const { return timings_; }
    /// The patches of the last compute() (with frames and local coordinates), one per model patch.
    const std::vector<Patch>& getPatches () const { return patches_; }
    /// Per-patch diagnostics of the last compute(), one per model patch.
    const std::vector<PatchCodingInfo>& getCodingInfo () const { return coding_info_; }

    const std::string& getClassName () const { return name_; }

  protected:
    virtual void computeModel (SparseSurfaceModel& model);

    TriangleMesh::ConstPtr mesh_;
    SparseSurfaceEncoderOptions options_;
    SurfaceBasis::ConstPtr basis_;
    int num_threads_ = 0;
    ProgressCallback progress_;

    EncoderTimings timings_;
    std::vector<Patch> patches_;
    std::vector<PatchCodingInfo> coding_info_;
    std::string name_ = "SparseSurfaceEncoder";
  };
} // namespace pcl_sparse
