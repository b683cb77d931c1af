#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/patch_samples.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>

#include <Eigen/Geometry>

#include <omp.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <cmath>
#include <limits>

namespace pcl_sparse
{
  namespace
  {
    double
    secondsSince (std::chrono::steady_clock::time_point start)
    {
      return std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
    }

    void
    require (bool condition, const std::string& message)
    {
      if (!condition)
        throw Error ("SparseSurfaceEncoder: " + message);
    }
  } // namespace

  void
  SparseSurfaceEncoderOptions::validate () const
  {
    patches.validate ();
    require (patches.rho > 0.0, "rho must be > 0, got " + std::to_string (patches.rho));
    require (coding.nyquist_factor >= 0.0 && coding.nyquist_factor <= 1.0,
             "Nyquist factor f must be in [0, 1], got " + std::to_string (coding.nyquist_factor));
    require (coding.max_atoms >= 1, "L (atoms per patch) must be >= 1, got " + std::to_string (coding.max_atoms));
    require (coding.tolerance > 0.0 && coding.tolerance < 1.0,
             "eps must be in (0, 1), got " + std::to_string (coding.tolerance));
    require (coding.min_samples >= 0, "min samples must be >= 0, got " + std::to_string (coding.min_samples));
    require (coding.footprint_angles >= 3,
             "footprint angles must be >= 3, got " + std::to_string (coding.footprint_angles));
    require (coding.support_scale >= 1.0 && std::isfinite (coding.support_scale),
             "support scale must be >= 1, got " + std::to_string (coding.support_scale));
    require (dictionary_frequencies >= 1 && dictionary_frequencies <= CosineAtoms::max_frequencies,
             "dictionary frequencies must be in [1, 64], got " + std::to_string (dictionary_frequencies));
    require (basis == CosineBasisKind::Paper || basis == CosineBasisKind::Dct,
             "basis must be Paper or Dct, got " + std::to_string (static_cast<int> (basis)));
  }

  void
  SparseSurfaceEncoder::compute (SparseSurfaceModel& model)
  {
    if (!mesh_ || mesh_->vertices.empty () || mesh_->triangles.empty ())
      throw Error ("[" + name_ + "::compute] no input mesh or an empty one (set a mesh with triangles)");
    // Every face degenerate: no surface to code (rho bounds A_p / A with A = 0, normals are arbitrary).
    // Faces with invalid indices are left to the sampling stage, which names them.
    const long num_vertices = static_cast<long> (mesh_->vertices.size ());
    bool has_area = false;
    for (const Eigen::Vector3i& t : mesh_->triangles)
      if (t.minCoeff () >= 0 && t.maxCoeff () < num_vertices)
      {
        const Eigen::Vector3d& a = mesh_->vertices[t[0]];
        const Eigen::Vector3d n = (mesh_->vertices[t[1]] - a).cross (mesh_->vertices[t[2]] - a);
        if (n.allFinite () && n.stableNorm () > 0.0)
        {
          has_area = true;
          break;
        }
      }
      else
        has_area = true;
    if (!has_area)
      throw Error ("[" + name_ + "::compute] the mesh has no area: all " + std::to_string (mesh_->triangles.size ()) +
                   " faces are degenerate");
    options_.validate ();
    computeModel (model);
  }

  void
  SparseSurfaceEncoder::computeModel (SparseSurfaceModel& model)
  {
    const auto start = std::chrono::steady_clock::now ();
    timings_ = EncoderTimings ();
    const TriangleMesh& mesh = *mesh_;
    SurfaceBasis::ConstPtr basis = basis_;
    if (!basis)
      basis = makeCosineBasis (options_.basis, options_.dictionary_frequencies);

    // Steps 2-6: patches with frames and local coordinates. The topology is built once, for both stages.
    const auto topology = std::make_shared<const MeshTopology> (buildMeshTopology (mesh));
    FeatureAwarePatchSampling sampling;
    sampling.setInputMesh (mesh_);
    sampling.setTopology (topology);
    sampling.setOptions (options_.patches);
    sampling.setNumberOfThreads (num_threads_);
    sampling.setProgressCallback (progress_);
    patches_.clear ();
    sampling.compute (patches_);
    timings_.patches = secondsSince (start);

    // Steps 7-9: code every patch into its own slot.
    const auto coding_start = std::chrono::steady_clock::now ();
    const std::vector<double> ring_lengths = meanRingEdgeLengths (mesh, *topology);
    const long num_patches = static_cast<long> (patches_.size ());
    std::vector<PatchCode> codes (patches_.size ());
    coding_info_.assign (patches_.size (), PatchCodingInfo ());
    std::atomic<long> done (0);
    const int threads = num_threads_ > 0 ? num_threads_ : omp_get_max_threads ();
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads) if(num_patches > 64)
    for (long p = 0; p < num_patches; ++p)
    {
      codes[p] = codePatch (patches_[p], static_cast<std::size_t> (p), mesh, ring_lengths, *basis, options_.coding,
                            &coding_info_[p]);
      const long finished = ++done;
      if (progress_ && omp_get_thread_num () == 0 && finished % 64 == 0)
        progress_ ("coding", static_cast<double> (finished) / num_patches);
    }
    if (progress_)
      progress_ ("coding", 1.0);
    timings_.coding = secondsSince (coding_start);

    model.basis = basis;
    model.patches = std::move (codes);
    model.num_input_vertices = mesh.vertices.size ();
    Eigen::Vector3d lo = Eigen::Vector3d::Constant (std::numeric_limits<double>::infinity ()), hi = -lo;
    for (const Eigen::Vector3d& v : mesh.vertices)
      if (v.allFinite ())
      {
        lo = lo.cwiseMin (v);
        hi = hi.cwiseMax (v);
      }
    model.bbox_diagonal = (hi - lo).allFinite () ? (hi - lo).norm () : 0.0;
    timings_.total = secondsSince (start);
  }
} // namespace pcl_sparse
