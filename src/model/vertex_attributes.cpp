#include <pcl_sparse/model/vertex_attributes.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_sparse
{
  const char*
  attributeChannelName (AttributeChannel channel)
  {
    switch (channel)
    {
      case AttributeChannel::Red: return "r";
      case AttributeChannel::Green: return "g";
      case AttributeChannel::Blue: return "b";
      case AttributeChannel::Alpha: return "a";
      case AttributeChannel::Intensity: return "intensity";
    }
    return "unknown";
  }

  void
  VertexAttributes::validate (std::size_t num_vertices, const std::string& what) const
  {
    std::vector<bool> seen (num_attribute_channels, false);
    for (AttributeChannel channel : channels)
    {
      const int id = static_cast<int> (channel);
      if (id < 0 || id >= num_attribute_channels)
        throw Error (what + ": unknown attribute channel " + std::to_string (id));
      if (seen[id])
        throw Error (what + ": attribute channel '" + attributeChannelName (channel) + "' given twice");
      seen[id] = true;
    }
    if (values.cols () != static_cast<Eigen::Index> (channels.size ()) ||
        values.rows () != static_cast<Eigen::Index> (num_vertices))
      throw Error (what + ": attributes are " + std::to_string (values.rows ()) + " x " + std::to_string (values.cols ()) +
                   ", expected " + std::to_string (num_vertices) + " vertices x " + std::to_string (channels.size ()) +
                   " channels");
    for (std::size_t c = 0; c < channels.size (); ++c)
    {
      const auto column = values.col (static_cast<Eigen::Index> (c));
      for (Eigen::Index v = 0; v < column.size (); ++v)
        if (!std::isfinite (column[v]))
          throw Error (what + ": attribute '" + attributeChannelName (channels[c]) + "' of vertex " + std::to_string (v) +
                       " is not a number (fillAttributeGaps gives such values their nearest vertex's)");
      if (isColourChannel (channels[c]) && column.size () > 0 && (column.minCoeff () < 0.0f || column.maxCoeff () > 255.0f))
        throw Error (what + ": colour channel '" + attributeChannelName (channels[c]) + "' outside 0 .. 255");
    }
  }

  std::vector<AttributeChannelInfo>
  VertexAttributes::channelInfo (const std::vector<Eigen::Vector3i>& faces) const
  {
    std::vector<AttributeChannelInfo> info (channels.size ());
    for (std::size_t c = 0; c < channels.size (); ++c)
    {
      info[c].channel = channels[c];
      if (isColourChannel (channels[c]))
        continue;  // 0 .. 255, the default
      const auto column = values.col (static_cast<Eigen::Index> (c));
      if (faces.empty ())
      {
        info[c].lower = column.size () > 0 ? column.minCoeff () : 0.0f;
        info[c].upper = column.size () > 0 ? column.maxCoeff () : 0.0f;
        continue;
      }
      float lower = std::numeric_limits<float>::infinity (), upper = -lower;
      for (const Eigen::Vector3i& f : faces)
        for (int k = 0; k < 3; ++k)
        {
          lower = std::min (lower, column[f[k]]);
          upper = std::max (upper, column[f[k]]);
        }
      info[c].lower = lower;
      info[c].upper = upper;
    }
    return info;
  }
} // namespace pcl_sparse
