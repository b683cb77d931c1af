#pragma once
/// \file ball_grid.h
/// Balls filed by the cells of a uniform grid that their bounding boxes meet, so that the balls that can hold
/// a point are one hash lookup away instead of a tree search (ModelSurfaceDistance: each patch within its own
/// reach of its seed, reaches spreading over 10x on a CAD part).

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  class BallGrid
  {
  public:
    /// \brief Files each ball in the cells its bounding box meets. Build O(B log B) for B filings: about 8-27
    /// per ball whose radius is about \a cell. The cell grows (doubling) where the grid would need more than
    /// 2^21 cells along an axis or more than 64 filings per ball (a few huge balls).
    /// \param[in] centres  the balls' centres (finite)
    /// \param[in] radii    their radii (finite, >= 0), as many
    /// \param[in] cell     the cells' side asked for (> 0): about the typical radius
    /// \throws pcl_sparse::Error for counts that differ, a non-finite centre or radius, a negative radius, balls
    ///         spanning more than a double holds or a cell that is not positive and finite
    BallGrid (const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& radii, double cell);

    /// \brief The balls whose bounding box meets the cell of \a p, in increasing index: every ball holding
    /// \a p is among them (and others near it). None for a point outside every box. Thread-safe.
    /// \return [first, last) of ball indices
    std::pair<const int*, const int*> candidates (const Eigen::Vector3d& p) const;

    /// The cells' side used (at least the one asked for).
    double cell () const { return cell_; }

  private:
    bool cellOf (const Eigen::Vector3d& p, std::uint64_t& key) const;

    double cell_ = 1.0;
    Eigen::Vector3d low_ = Eigen::Vector3d::Zero ();  ///< the grid's corner: the low corner of every box
    Eigen::Vector3i cells_ = Eigen::Vector3i::Zero ();  ///< cells along each axis
    std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> ranges_;  ///< cell -> [begin, end) in balls_
    std::vector<int> balls_;
  };
} // namespace pcl_sparse
