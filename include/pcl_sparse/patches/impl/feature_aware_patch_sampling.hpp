#pragma once
/// \file feature_aware_patch_sampling.hpp
/// \brief Definitions of FeatureAwarePatchSampling (patches/feature_aware_patch_sampling.h).

#include <pcl_sparse/mesh/impl/surface_stage.hpp>
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
    result_ = sampleFeatureAwarePatches (*this->surface_, *this->surface_topology_, options_, responses_, keypoints_,
                                         this->num_threads_, this->progress_);
    patches = std::move (result_.patches);
    result_.patches.clear ();
  }
} // namespace pcl_sparse
