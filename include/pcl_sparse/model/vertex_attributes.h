#pragma once
/// \file vertex_attributes.h
/// Colour and intensity of an input surface's vertices: signals over each patch's domain like the height,
/// which the encoder codes per patch over the same atoms and resampling evaluates at every output point.

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// What an attribute channel holds. The values are the file format's channel ids (docs/FORMAT.md).
  enum class AttributeChannel : std::uint8_t
  {
    Red = 0,        ///< colour, 0 .. 255 as in PCL's rgb
    Green = 1,
    Blue = 2,
    Alpha = 3,      ///< PCL's rgba alpha, 0 .. 255
    Intensity = 4   ///< PCL's intensity field, any range
  };

  /// Number of AttributeChannel values.
  constexpr int num_attribute_channels = 5;

  /// "r", "g", "b", "a" or "intensity" (PCL's field names).
  const char*
  attributeChannelName (AttributeChannel channel);

  /// Whether \a channel is a colour component (0 .. 255).
  inline bool
  isColourChannel (AttributeChannel channel)
  {
    return channel != AttributeChannel::Intensity;
  }

  /// One attribute channel of a model: which quantity, and the range evaluated values are clamped to
  /// (0 .. 255 for colour, the input's smallest to largest value for intensity).
  struct AttributeChannelInfo
  {
    AttributeChannel channel = AttributeChannel::Red;
    double lower = 0.0;
    double upper = 255.0;
  };

  /// Per-vertex attribute values of an input surface.
  ///   channels  C distinct channels (e.g. Red, Green, Blue; or Intensity)
  ///   values    #V by C, column c holding channel c of every vertex (finite values)
  struct VertexAttributes
  {
    using Ptr = std::shared_ptr<VertexAttributes>;
    using ConstPtr = std::shared_ptr<const VertexAttributes>;

    std::vector<AttributeChannel> channels;
    Eigen::MatrixXf values;

    bool empty () const { return channels.empty (); }

    /// \brief Throws pcl_sparse::Error, naming \a what, unless the channels are distinct and valid, values
    /// has C columns and \a num_vertices rows, and every value is finite (colour within 0 .. 255).
    /// \param[in] num_vertices vertices of the surface the attributes belong to
    /// \param[in] what the caller, for the message
    void validate (std::size_t num_vertices, const std::string& what) const;

    /// \brief The rows of \a indices, in that order (the points a surface keeps).
    /// \param[in] indices row indices (int or std::size_t), each < values.rows ()
    template <typename Index>
    VertexAttributes
    selectRows (const std::vector<Index>& indices) const
    {
      VertexAttributes selected;
      selected.channels = channels;
      selected.values.resize (static_cast<Eigen::Index> (indices.size ()), values.cols ());
      for (std::size_t i = 0; i < indices.size (); ++i)
        selected.values.row (static_cast<Eigen::Index> (i)) = values.row (static_cast<Eigen::Index> (indices[i]));
      return selected;
    }

    /// \brief Each channel with the range a model clamps it to (colour 0 .. 255, intensity its min .. max).
    /// The range also sets the coding tolerance (AttributeCodingOptions::tolerance), so it is taken over the
    /// corners of \a faces, the vertices a surface samples: a vertex in no face (an organized cloud's NaN
    /// point, a stray point) would otherwise widen it without bound and the surface's values coded away.
    /// \param[in] faces the surface's triangles (indices < values.rows ()); empty: every vertex counts
    std::vector<AttributeChannelInfo> channelInfo (const std::vector<Eigen::Vector3i>& faces = {}) const;
  };
} // namespace pcl_sparse
