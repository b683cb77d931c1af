#pragma once
// Encode a mesh, resample a model: the two steps most tests and benches of the whole pipeline start with.

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <memory>

namespace pcl_sparse_test
{
  /// The model of \a mesh encoded with \a options.
  inline pcl_sparse::SparseSurfaceModel::Ptr
  encodeMesh (const pcl_sparse::TriangleMesh::ConstPtr& mesh,
              const pcl_sparse::SparseSurfaceEncoderOptions& options = pcl_sparse::SparseSurfaceEncoderOptions ())
  {
    pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (mesh);
    encoder.setOptions (options);
    auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
    encoder.compute (*model);
    return model;
  }

  /// \a count points resampled from \a model with \a options (default: the default resampling options).
  inline pcl::PointCloud<pcl::PointNormal>
  resampleModel (const pcl_sparse::SparseSurfaceModel::ConstPtr& model, std::size_t count,
                 const pcl_sparse::SparseSurfaceResamplingOptions& options = pcl_sparse::SparseSurfaceResamplingOptions ())
  {
    pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setOptions (options);
    resampling.setPointCount (count);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    return cloud;
  }
} // namespace pcl_sparse_test
