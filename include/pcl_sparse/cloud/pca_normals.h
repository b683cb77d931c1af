#pragma once
/// \file pca_normals.h
/// Point normals by principal component analysis of each neighbourhood: the direction of least variance
/// of the point and its neighbours (the same estimator as pcl::NormalEstimation, in double precision on
/// offsets from the point, so map coordinates and float rounding do not bias it).

#include <pcl_sparse/cloud/point_neighborhoods.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Unit normals, unoriented (the sign is whatever the eigen solver gives: deterministic, meaningless).
  ///   positions  #P positions
  ///   usable     #P flags: only usable points take part, as centre or neighbour
  ///   normals    #P output; entries of the points in \a only (all points when null) are overwritten: the
  ///              PCA normal, or zero when fewer than 3 usable points (the point and 2 neighbours) are there
  void
  estimatePcaNormals (const std::vector<Eigen::Vector3d>& positions, const PointNeighborhoods& neighborhoods,
                      const std::vector<std::uint8_t>& usable, int num_threads, std::vector<Eigen::Vector3d>& normals,
                      const std::vector<int>* only = nullptr);
} // namespace pcl_sparse
