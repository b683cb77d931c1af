#pragma once
// Encode a mesh, resample a model: the two steps most tests and benches of the whole pipeline start with.

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/file_tolerance.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/resampling/model_mesh_distance.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse_test
{
  /// The model of \a mesh encoded with \a options on \a threads threads (0: OpenMP's default).
  inline pcl_sparse::SparseSurfaceModel::Ptr
  encodeMesh (const pcl_sparse::TriangleMesh::ConstPtr& mesh,
              const pcl_sparse::SparseSurfaceEncoderOptions& options = pcl_sparse::SparseSurfaceEncoderOptions (),
              int threads = 0)
  {
    pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (mesh);
    encoder.setOptions (options);
    encoder.setNumberOfThreads (threads);
    auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
    encoder.compute (*model);
    return model;
  }

  /// The options derivedWriteOptions takes from \a model's errors at \a vertices (its input's): the bound's
  /// file, which `pcl_sparse_encode -o` starts from before it measures others (measuredWriteOptions); those
  /// statistics in \a stats if given.
  inline pcl_sparse::ModelWriteOptions
  boundWriteOptions (const pcl_sparse::SparseSurfaceModel& model, const std::vector<Eigen::Vector3d>& vertices,
                     pcl_sparse::ModelStatistics* stats = nullptr)
  {
    std::vector<double> errors;
    const pcl_sparse::ModelStatistics statistics = model.statistics (vertices, &errors);
    if (stats)
      *stats = statistics;
    return pcl_sparse::derivedWriteOptions (statistics, errors, model.bbox_diagonal);
  }

  /// The bytes of \a model's file written with boundWriteOptions; the statistics in \a stats if given.
  inline std::vector<std::uint8_t>
  defaultFileBytes (const pcl_sparse::SparseSurfaceModel& model, const std::vector<Eigen::Vector3d>& vertices,
                    pcl_sparse::ModelStatistics* stats = nullptr)
  {
    return pcl_sparse::encodeModel (model, boundWriteOptions (model, vertices, stats));
  }

  /// The section \a tag of a file's \a info (a section of 0 bytes when the file has none).
  inline pcl_sparse::ModelFileSection
  fileSection (const pcl_sparse::ModelFileInfo& info, const std::string& tag)
  {
    for (const pcl_sparse::ModelFileSection& section : info.sections)
      if (section.tag == tag)
        return section;
    return pcl_sparse::ModelFileSection ();
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

  /// The Chamfer distance (world units) between \a model and \a mesh with \a points points a side, sampled as
  /// bench/bench_format samples them.
  inline double
  chamferOf (const pcl_sparse::SparseSurfaceModel::ConstPtr& model, const pcl_sparse::TriangleMesh& mesh, std::size_t points)
  {
    const pcl_sparse::MeshSurfaceDistance to_mesh (mesh);
    std::vector<Eigen::Vector3d> on_mesh;
    pcl_sparse::sampleMeshSurface (mesh, points, 11, on_mesh);
    return pcl_sparse::modelChamferDistance (model, to_mesh, on_mesh, points).value ();
  }
} // namespace pcl_sparse_test
