#pragma once
/// \file feature_aware_patch_sampling.hpp
/// \brief Definitions of FeatureAwarePatchSampling (patches/feature_aware_patch_sampling.h).

#include <pcl_sparse/surface/impl/surface_stage.hpp>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>

namespace pcl_sparse
{
  template <typename PointInT>
  void
  FeatureAwarePatchSampling<PointInT>::compute (std::vector<Patch>& patches)
  {
    patches.clear ();
    result_ = PatchSamplingResult ();
    this->initCompute ();
    computePatches (patches);
    this->deinitCompute ();
  }

  template <typename PointInT>
  void
  FeatureAwarePatchSampling<PointInT>::computePatches (std::vector<Patch>& patches)
  {
    const PatchOptions options = patchOptionsFor (options_, this->surfaceIsScan (), this->surfaceIsLidarRings ());
    result_ = sampleFeatureAwarePatches (*this->surface_, *this->surface_topology_, options, responses_, keypoints_,
                                         this->num_threads_, this->progress_, this->surfaceNormals ());
    patches = std::move (result_.patches);
    result_.patches.clear ();
    if (!this->surface_origin_.isZero (0.0))  // a scan's local frame back to the input's
      for (Patch& patch : patches)
        patch.origin += this->surface_origin_;
  }
} // namespace pcl_sparse
