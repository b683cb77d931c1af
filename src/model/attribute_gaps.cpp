#include <pcl_sparse/model/attribute_gaps.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/point_kd_tree.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    bool
    finitePosition (const Eigen::Vector3d& p)
    {
      // As float, which the kd-tree holds: a double beyond 3.4e38 is not a usable place either.
      return p.cast<float> ().allFinite ();
    }

    /// Fills the gaps of one channel's \a column; returns the number of values filled, or -1 when no vertex
    /// with a position has a value.
    long long
    fillChannel (Eigen::Ref<Eigen::VectorXf> column, const std::vector<Eigen::Vector3d>& positions)
    {
      if (column.allFinite ())
        return 0;  // the usual case: no tree to build
      const Eigen::Index n = column.size ();
      std::vector<Eigen::Index> gaps;
      std::vector<Eigen::Index> sources;
      pcl::PointCloud<pcl::PointXYZ> source_points;
      for (Eigen::Index v = 0; v < n; ++v)
      {
        const bool usable = finitePosition (positions[static_cast<std::size_t> (v)]);
        if (!std::isfinite (column[v]))
          gaps.push_back (v);
        else if (usable)
        {
          sources.push_back (v);
          const Eigen::Vector3f p = positions[static_cast<std::size_t> (v)].cast<float> ();
          source_points.push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
        }
      }
      // No placed vertex has a value: the channel says nothing about the surface.
      if (sources.empty ())
        return -1;
      const float fallback = column[sources.front ()];
      const PointKdTree tree (source_points);
      std::vector<int> nearest;
      std::vector<float> squared;
      for (Eigen::Index v : gaps)
      {
        const Eigen::Vector3d& p = positions[static_cast<std::size_t> (v)];
        if (!finitePosition (p))
        {
          column[v] = fallback;
          continue;
        }
        const Eigen::Vector3f q = p.cast<float> ();
        // A few, for ties: a scan's duplicate points stand at one place, and the lowest number wins.
        tree.nearestK (pcl::PointXYZ (q.x (), q.y (), q.z ()), 4, nearest, squared);
        std::size_t best = static_cast<std::size_t> (nearest.front ());
        for (std::size_t k = 1; k < nearest.size () && squared[k] == squared.front (); ++k)
          best = std::min (best, static_cast<std::size_t> (nearest[k]));
        column[v] = column[sources[best]];
      }
      return static_cast<long long> (gaps.size ());
    }
  } // namespace

  AttributeGaps
  fillAttributeGaps (VertexAttributes& attributes, const std::vector<Eigen::Vector3d>& positions)
  {
    AttributeGaps gaps;
    if (attributes.empty ())
      return gaps;
    if (attributes.values.rows () != static_cast<Eigen::Index> (positions.size ()))
      throw Error ("fillAttributeGaps: " + std::to_string (attributes.values.rows ()) + " attribute rows for " +
                   std::to_string (positions.size ()) + " vertices");
    std::vector<Eigen::Index> kept;
    for (std::size_t c = 0; c < attributes.channels.size (); ++c)
    {
      const long long filled = fillChannel (attributes.values.col (static_cast<Eigen::Index> (c)), positions);
      if (filled < 0)
        gaps.dropped.push_back (attributes.channels[c]);
      else
      {
        gaps.filled += static_cast<std::size_t> (filled);
        kept.push_back (static_cast<Eigen::Index> (c));
      }
    }
    if (gaps.dropped.empty ())
      return gaps;
    VertexAttributes remaining;
    remaining.values.resize (attributes.values.rows (), static_cast<Eigen::Index> (kept.size ()));
    for (std::size_t k = 0; k < kept.size (); ++k)
    {
      remaining.channels.push_back (attributes.channels[static_cast<std::size_t> (kept[k])]);
      remaining.values.col (static_cast<Eigen::Index> (k)) = attributes.values.col (kept[k]);
    }
    attributes = std::move (remaining);
    return gaps;
  }
} // namespace pcl_sparse
