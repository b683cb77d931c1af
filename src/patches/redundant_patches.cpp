#include <pcl_sparse/patches/redundant_patches.h>

#include <algorithm>
#include <limits>

namespace pcl_sparse
{
  std::vector<bool>
  redundantPatches (const TriangleMesh& mesh, const std::vector<Patch>& patches,
                    const std::vector<std::uint8_t>& seed_vertices)
  {
    // Holders of what this partition answers for; the rest start at "always held".
    constexpr int kHeldElsewhere = std::numeric_limits<int>::max () / 2;
    const bool tiled = !seed_vertices.empty ();
    std::vector<int> vertex_holders (mesh.vertices.size (), 0), face_holders (mesh.triangles.size (), 0);
    if (tiled)
    {
      for (std::size_t v = 0; v < vertex_holders.size (); ++v)
        vertex_holders[v] = seed_vertices[v] ? 0 : kHeldElsewhere;
      for (std::size_t f = 0; f < face_holders.size (); ++f)
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        face_holders[f] = seed_vertices[t[0]] || seed_vertices[t[1]] || seed_vertices[t[2]] ? 0 : kHeldElsewhere;
      }
    }
    for (const Patch& patch : patches)
    {
      for (int v : patch.vertices)
        ++vertex_holders[v];
      for (int f : patch.triangles)
        ++face_holders[f];
    }
    const auto heldElsewhere = [] (const std::vector<int>& indices, const std::vector<int>& holders) {
      return std::all_of (indices.begin (), indices.end (), [&] (int i) { return holders[i] >= 2; });
    };
    std::vector<bool> redundant (patches.size (), false);
    for (std::size_t i = patches.size (); i-- > 0;)
    {
      const Patch& patch = patches[i];
      if (patch.beside_uncovered_face || !heldElsewhere (patch.vertices, vertex_holders) ||
          !heldElsewhere (patch.triangles, face_holders))
        continue;
      redundant[i] = true;
      for (int v : patch.vertices)
        --vertex_holders[v];
      for (int f : patch.triangles)
        --face_holders[f];
    }
    return redundant;
  }
} // namespace pcl_sparse
