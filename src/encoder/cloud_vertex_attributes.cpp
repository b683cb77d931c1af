#include <pcl_sparse/encoder/cloud_vertex_attributes.h>

#include <algorithm>

namespace pcl_sparse
{
  VertexAttributes
  scanVertexAttributes (const ScanCloud& scan)
  {
    const std::size_t n = scan.size ();
    const bool colour = scan.colors.size () == n && n > 0;
    const bool alpha = colour && std::find (scan.fields.begin (), scan.fields.end (), "rgba") != scan.fields.end ();
    const bool intensity = scan.intensities.size () == n && n > 0;
    VertexAttributes attributes;
    if (colour)
      attributes.channels = {AttributeChannel::Red, AttributeChannel::Green, AttributeChannel::Blue};
    if (alpha)
      attributes.channels.push_back (AttributeChannel::Alpha);
    if (intensity)
      attributes.channels.push_back (AttributeChannel::Intensity);
    attributes.values.resize (static_cast<Eigen::Index> (n), static_cast<Eigen::Index> (attributes.channels.size ()));
    for (std::size_t i = 0; i < n; ++i)
    {
      const Eigen::Index row = static_cast<Eigen::Index> (i);
      Eigen::Index c = 0;
      if (colour)
      {
        // PCL's packing: 0xAARRGGBB.
        const std::uint32_t rgba = scan.colors[i];
        attributes.values (row, c++) = static_cast<float> ((rgba >> 16) & 0xFF);
        attributes.values (row, c++) = static_cast<float> ((rgba >> 8) & 0xFF);
        attributes.values (row, c++) = static_cast<float> (rgba & 0xFF);
        if (alpha)
          attributes.values (row, c++) = static_cast<float> (rgba >> 24);
      }
      if (intensity)
        attributes.values (row, c++) = scan.intensities[i];
    }
    return attributes;
  }
} // namespace pcl_sparse
