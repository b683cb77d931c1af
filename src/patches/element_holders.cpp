#include <pcl_sparse/patches/element_holders.h>

#include <limits>

namespace pcl_sparse
{
  ElementHolders
  countElementHolders (const TriangleMesh& mesh, const std::vector<Patch>& patches,
                       const std::vector<std::uint8_t>& seed_vertices)
  {
    // Far from overflow however many patches later count down from it.
    constexpr int kHeldElsewhere = std::numeric_limits<int>::max () / 2;
    ElementHolders holders;
    holders.vertices.assign (mesh.vertices.size (), 0);
    holders.faces.assign (mesh.triangles.size (), 0);
    if (!seed_vertices.empty ())
    {
      for (std::size_t v = 0; v < holders.vertices.size (); ++v)
        holders.vertices[v] = seed_vertices[v] ? 0 : kHeldElsewhere;
      for (std::size_t f = 0; f < holders.faces.size (); ++f)
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        holders.faces[f] = seed_vertices[t[0]] || seed_vertices[t[1]] || seed_vertices[t[2]] ? 0 : kHeldElsewhere;
      }
    }
    for (const Patch& patch : patches)
    {
      for (int v : patch.vertices)
        ++holders.vertices[v];
      for (int f : patch.triangles)
        ++holders.faces[f];
    }
    return holders;
  }
} // namespace pcl_sparse
