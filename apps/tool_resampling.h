#pragma once
/// \file tool_resampling.h
/// What pcl_sparse_resample and pcl_sparse_decode share: resampling a model in a local frame when it lies
/// far from the origin (map coordinates), and writing the cloud back in the model's frame.

#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <string>

namespace pcl_sparse
{
  namespace tools
  {
    /// A resampled cloud in a local frame and that frame's origin in the model's frame.
    struct LocalCloud
    {
      pcl::PointCloud<pcl::PointNormal> cloud;
      Eigen::Vector3d origin = Eigen::Vector3d::Zero ();  ///< 0 unless the model lies far from the origin
    };

    /// Resamples \a model with \a resampling (its density, options, threads and progress already set). A
    /// model far from the origin for its size (localFrameOrigin of its seeds is not 0: map coordinates) is
    /// resampled moved to that origin, so that float coordinates keep the cloud's resolution.
    LocalCloud
    resampleInLocalFrame (SparseSurfaceResampling<pcl::PointNormal>& resampling, const SparseSurfaceModel::ConstPtr& model);

    /// As above, in the local frame of \a origin (a tiled model's: the same for the whole model and any
    /// region of it, so a region's points are exactly the whole model's there).
    LocalCloud
    resampleInLocalFrame (SparseSurfaceResampling<pcl::PointNormal>& resampling, const SparseSurfaceModel::ConstPtr& model,
                          const Eigen::Vector3d& origin);

    /// Writes \a local to \a path (.pcd / .ply) in the model's frame: float x y z where floats keep the
    /// cloud's resolution (the origin is 0, or every coordinate is within 16 extents of 0), else double
    /// x y z = origin + point (map coordinates; PCL's loader cannot read those into PointXYZ).
    void
    saveLocalCloud (const std::string& path, const LocalCloud& local, bool binary);
  } // namespace tools
} // namespace pcl_sparse
