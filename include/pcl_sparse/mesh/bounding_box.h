#pragma once
/// \file bounding_box.h
/// The length scale of a shape: the diagonal of its axis-aligned bounding box. Every "fraction of the
/// bounding-box diagonal" in the library (Harris radii, RMSE/diag, the file format's tolerance) uses it.

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace pcl_sparse
{
  /// \brief The axis-aligned bounding box of the finite points of \a points; empty (isEmpty ()) when none
  /// is finite.
  Eigen::AlignedBox3d
  finiteBoundingBox (const std::vector<Eigen::Vector3d>& points);

  /// Coordinates the library refuses beyond (as input to encode, as a model to resample): resampled clouds
  /// are float (up to 3.4e38), and squared lengths overflow far sooner in the pipeline.
  constexpr double max_coordinate = 1e30;

  /// \brief The largest |coordinate| of the finite \a points moved by \a origin (a scan's local frame to
  /// the world); 0 when none is finite. Compared with max_coordinate by the encoder and buildCloudSurface.
  double
  largestCoordinate (const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero ());

  /// Length of the diagonal of the axis-aligned bounding box of \a points (#points by 3). Non-finite
  /// points are ignored; 0 when no point is finite.
  double
  boundingBoxDiagonal (const std::vector<Eigen::Vector3d>& points);

  /// Bounding-box diagonal of the finite vertices some face uses (faces with an index out of range are
  /// skipped); 0 when there is none. A scan's surface: its stray points are in no triangle.
  double
  surfaceBoundingBoxDiagonal (const TriangleMesh& mesh);

  /// The mesh's scale: the bounding-box diagonal of the vertices its faces use (surfaceBoundingBoxDiagonal),
  /// or of all its finite vertices when no face has one. A vertex no face uses (a stray "v 1000 1000 1000"
  /// in an OBJ) set the model's scale, and with it a file's quantisation step and Harris's radius.
  inline double
  boundingBoxDiagonal (const TriangleMesh& mesh)
  {
    const double surface = surfaceBoundingBoxDiagonal (mesh);
    return surface > 0.0 ? surface : boundingBoxDiagonal (mesh.vertices);
  }
} // namespace pcl_sparse
