#pragma once
/// \file point_kd_tree.h
/// A kd-tree over 3D float points answering one query at a time: FLANN's single kd-tree, built and searched
/// as pcl::KdTreeFLANN builds and searches it (leaf size 15, exact search), so it finds the same neighbours in
/// the same order, but without the OpenMP region that FLANN's batch search opens for every query. PCL hands
/// FLANN one query at a time, and each such region costs two futex system calls: 200000 7-NN queries took
/// 0.83-1.13 s through pcl::search::KdTree and 0.26-0.32 s here (bench/results/point_kd_tree.md). Thread-safe
/// for queries (const).

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  class PointKdTree
  {
  public:
    /// \brief Builds the tree over \a points (copied; every coordinate must be finite).
    /// \throws pcl_sparse::Error for a non-finite coordinate
    explicit PointKdTree (const pcl::PointCloud<pcl::PointXYZ>& points);
    ~PointKdTree ();
    PointKdTree (const PointKdTree&) = delete;
    PointKdTree& operator= (const PointKdTree&) = delete;

    /// Number of points.
    std::size_t size () const { return size_; }

    /// \brief The min(k, size ()) points nearest \a query, nearest first (as pcl::KdTreeFLANN::nearestKSearch).
    /// \param[in] query      where to search (finite)
    /// \param[in] k          how many (none for k <= 0)
    /// \param[out] indices   their numbers in the points given
    /// \param[out] squared   their squared distances
    void nearestK (const pcl::PointXYZ& query, int k, std::vector<int>& indices, std::vector<float>& squared) const;

    /// \brief The point nearest \a query if its squared distance is less than \a bound_squared: the nearestK (k 1)
    /// answer, found sooner the tighter the bound (branches farther than it are not searched), and nothing
    /// allocated. ModelSurfaceDistance caps a distance it already has by the nearest resampled point.
    /// \param[in] query          where to search (finite)
    /// \param[in] bound_squared  only points nearer than this (squared; infinity: any)
    /// \param[out] index         its number in the points given (unchanged when there is none)
    /// \param[out] squared       its squared distance (unchanged when there is none)
    /// \return whether there was one
    bool nearestWithin (const pcl::PointXYZ& query, float bound_squared, int& index, float& squared) const;

    /// \brief Every point whose squared distance to \a query is less than float (radius^2) (as
    /// pcl::KdTreeFLANN::radiusSearch without a neighbour limit: a point at exactly the radius is left out).
    /// \param[in] query      where to search (finite)
    /// \param[in] radius     the search radius
    /// \param[out] indices   their numbers in the points given
    /// \param[out] squared   their squared distances
    /// \param[in] sorted     nearest first (ties by number); else in the tree's order
    void radius (const pcl::PointXYZ& query, double radius, std::vector<int>& indices, std::vector<float>& squared,
                 bool sorted = true) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::size_t size_ = 0;
  };
} // namespace pcl_sparse
