#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/patch_samples.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/impl/sparse_surface_encoder.hpp>
#include <pcl_sparse/mesh/bounding_box.h>
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

    /// The cosines of options.attributes.basis, as many as the height's basis has (the height's basis
    /// itself when it is that one).
    SurfaceBasis::ConstPtr
    attributeBasis (const SurfaceBasis::ConstPtr& basis, const SparseSurfaceEncoderOptions& options)
    {
      const auto* cosine = dynamic_cast<const CosineAtoms*> (basis.get ());
      if (cosine && cosine->kind () == options.attributes.basis)
        return basis;
      return makeCosineBasis (options.attributes.basis, cosine ? cosine->frequencies () : options.dictionary_frequencies);
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
    require (coding.noise_level >= 0.0 && std::isfinite (coding.noise_level),
             "noise level must be >= 0, got " + std::to_string (coding.noise_level));
    require (dictionary_frequencies >= 1 && dictionary_frequencies <= CosineAtoms::max_frequencies,
             "dictionary frequencies must be in [1, 64], got " + std::to_string (dictionary_frequencies));
    require (basis == CosineBasisKind::Paper || basis == CosineBasisKind::Dct,
             "basis must be Paper or Dct, got " + std::to_string (static_cast<int> (basis)));
    require (attributes.basis == CosineBasisKind::Paper || attributes.basis == CosineBasisKind::Dct,
             "attribute basis must be Paper or Dct, got " + std::to_string (static_cast<int> (attributes.basis)));
    require (attributes.max_atoms >= 1,
             "attribute L (atoms per channel) must be >= 1, got " + std::to_string (attributes.max_atoms));
    require (attributes.tolerance >= 0.0 && std::isfinite (attributes.tolerance),
             "attribute tolerance must be >= 0, got " + std::to_string (attributes.tolerance));
  }

  bool
  hasSurfaceArea (const TriangleMesh& mesh)
  {
    const long num_vertices = static_cast<long> (mesh.vertices.size ());
    for (const Eigen::Vector3i& t : mesh.triangles)
    {
      if (t.minCoeff () < 0 || t.maxCoeff () >= num_vertices)
        return true;
      const Eigen::Vector3d& a = mesh.vertices[t[0]];
      const Eigen::Vector3d n = (mesh.vertices[t[1]] - a).cross (mesh.vertices[t[2]] - a);
      if (n.allFinite () && n.stableNorm () > 0.0)
        return true;
    }
    return false;
  }

  SparseSurfaceEncoderOptions
  encoderPresetOptions (EncoderPreset preset)
  {
    SparseSurfaceEncoderOptions options;
    if (preset == EncoderPreset::Paper)
    {
      options.basis = CosineBasisKind::Paper;
      options.patches.cone_angle = M_PI / 2.0;
    }
    return options;
  }

  EncoderPreset
  encoderPresetFromName (const std::string& name)
  {
    if (name == "default")
      return EncoderPreset::Default;
    if (name == "paper")
      return EncoderPreset::Paper;
    throw Error ("unknown preset '" + name + "': expected default or paper");
  }

  SurfaceEncoding
  encodeSurface (const TriangleMesh& mesh, const MeshTopology& topology, const SparseSurfaceEncoderOptions& options,
                 const SurfaceBasis::ConstPtr& basis, int num_threads, const ProgressCallback& progress,
                 SparseSurfaceModel& model)
  {
    return encodeSurface (mesh, VertexAttributes (), topology, options, basis, num_threads, progress, model);
  }

  SurfaceEncoding
  encodeSurface (const TriangleMesh& mesh, const VertexAttributes& attributes, const MeshTopology& topology,
                 const SparseSurfaceEncoderOptions& options, const SurfaceBasis::ConstPtr& basis, int num_threads,
                 const ProgressCallback& progress, SparseSurfaceModel& model,
                 const std::vector<Eigen::Vector3d>& point_normals, const std::vector<std::uint8_t>& seed_vertices)
  {
    AttributeCodingInput attribute_input;
    if (!attributes.empty ())
    {
      attributes.validate (mesh.vertices.size (), "SparseSurfaceEncoder");
      attribute_input.values = &attributes;
      attribute_input.channels = attributes.channelInfo ();
      attribute_input.basis = attributeBasis (basis, options);
      attribute_input.nyquist_factor = options.coding.nyquist_factor;
      attribute_input.nyquist_rule = options.coding.nyquist_rule;
      attribute_input.options = options.attributes;
    }
    const auto start = std::chrono::steady_clock::now ();
    SurfaceEncoding encoding;

    // Steps 2-6: patches with frames and local coordinates.
    encoding.patches = sampleFeatureAwarePatches (mesh, topology, options.patches, {}, {}, num_threads, progress, point_normals,
                                                  seed_vertices).patches;
    encoding.timings.patches = secondsSince (start);

    // Steps 7-9: code every patch into its own slot.
    const auto coding_start = std::chrono::steady_clock::now ();
    const std::vector<Patch>& patches = encoding.patches;
    const std::vector<double> ring_lengths = meanRingEdgeLengths (mesh, topology);
    const long num_patches = static_cast<long> (patches.size ());
    std::vector<PatchCode> codes (patches.size ());
    encoding.coding_info.assign (patches.size (), PatchCodingInfo ());
    std::atomic<long> done (0);
    const int threads = num_threads > 0 ? num_threads : omp_get_max_threads ();
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads) if(num_patches > 64)
    for (long p = 0; p < num_patches; ++p)
    {
      codes[p] = codePatch (patches[p], static_cast<std::size_t> (p), mesh, ring_lengths, *basis, options.coding,
                            &encoding.coding_info[p], attribute_input.values ? &attribute_input : nullptr);
      const long finished = ++done;
      if (progress && omp_get_thread_num () == 0 && finished % 64 == 0)
        progress ("coding", static_cast<double> (finished) / num_patches);
    }
    if (progress)
      progress ("coding", 1.0);
    encoding.timings.coding = secondsSince (coding_start);

    model.basis = basis;
    model.patches = std::move (codes);
    model.attribute_channels = attribute_input.channels;
    model.attribute_basis = attribute_input.basis;
    model.num_input_vertices = mesh.vertices.size ();
    model.bbox_diagonal = boundingBoxDiagonal (mesh);
    encoding.timings.total = secondsSince (start);
    return encoding;
  }

#define PCL_SPARSE_INSTANTIATE_ENCODER(T) template class SparseSurfaceEncoder<T>;
  PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_INSTANTIATE_ENCODER)
#undef PCL_SPARSE_INSTANTIATE_ENCODER
} // namespace pcl_sparse
