#pragma once
/// \file attribute_gaps.h
/// Attribute values a sensor left out (a NaN intensity on a point with a position): filled from the nearest
/// point that has one, so that one missing return does not fail the encoding of a whole scan.

#include <pcl_sparse/model/vertex_attributes.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// What fillAttributeGaps changed.
  struct AttributeGaps
  {
    std::size_t filled = 0;                 ///< values that were not finite and took a neighbour's
    std::vector<AttributeChannel> dropped;  ///< channels with no finite value at all, removed
  };

  /// \brief Gives every non-finite value of \a attributes the value of the nearest vertex (Euclidean, over
  /// \a positions) with a finite value in the same channel; ties go to the lower vertex number. Vertices
  /// without a finite position take the first placed vertex's value (they are in no face: nothing samples
  /// them, and the channel's range is taken over faces, VertexAttributes::channelInfo). A channel with no finite value at a vertex with a
  /// position is removed. Rows of \a attributes and \a positions must match.
  /// \param[in,out] attributes one row per vertex
  /// \param[in] positions      the vertices' positions
  /// \return the number of values filled and the channels removed
  AttributeGaps
  fillAttributeGaps (VertexAttributes& attributes, const std::vector<Eigen::Vector3d>& positions);
} // namespace pcl_sparse
