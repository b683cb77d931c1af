#pragma once
/// \file sparse_surface_encoder.hpp
/// \brief Definitions of SparseSurfaceEncoder (encoder/sparse_surface_encoder.h).

#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/surface/impl/surface_stage.hpp>

namespace pcl_sparse
{
  template <typename PointInT>
  void
  SparseSurfaceEncoder<PointInT>::compute (SparseSurfaceModel& model)
  {
    encoding_ = SurfaceEncoding ();
    this->initCompute ();
    // Every face degenerate: no surface to code (rho bounds A_p / A with A = 0, normals are arbitrary).
    if (!hasSurfaceArea (*this->surface_))
      this->fail ("the mesh has no area: all " + std::to_string (this->surface_->triangles.size ()) +
                  " faces are degenerate");
    options_.validate ();
    computeModel (model);
    this->deinitCompute ();
  }

  template <typename PointInT>
  void
  SparseSurfaceEncoder<PointInT>::computeModel (SparseSurfaceModel& model)
  {
    const SurfaceBasis::ConstPtr basis =
      basis_ ? basis_ : makeCosineBasis (options_.basis, options_.dictionary_frequencies);
    SparseSurfaceEncoderOptions options = options_;
    if (this->surfaceIsScan () && options.scan_noise_floor && options.coding.noise_level == 0.0)
      options.coding.noise_level = this->cloud_surface_->noise;
    options.patches.harris_rings = harrisRingsFor (options.patches.harris_rings, this->surfaceIsScan ());
    encoding_ = encodeSurface (*this->surface_, *this->surface_topology_, options, basis, this->num_threads_,
                               this->progress_, model);
    // A scan is encoded in its local frame: the model and patches go back to the input's frame.
    if (!this->surface_origin_.isZero (0.0))
    {
      model.translate (this->surface_origin_);
      for (Patch& patch : encoding_.patches)
        patch.origin += this->surface_origin_;
    }
  }
} // namespace pcl_sparse
