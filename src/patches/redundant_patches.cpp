#include <pcl_sparse/patches/redundant_patches.h>

#include <pcl_sparse/patches/element_holders.h>

#include <algorithm>

namespace pcl_sparse
{
  std::vector<bool>
  redundantPatches (const TriangleMesh& mesh, const std::vector<Patch>& patches,
                    const std::vector<std::uint8_t>& seed_vertices)
  {
    ElementHolders holders = countElementHolders (mesh, patches, seed_vertices);
    std::vector<int>& vertex_holders = holders.vertices;
    std::vector<int>& face_holders = holders.faces;
    const auto heldElsewhere = [] (const std::vector<int>& indices, const std::vector<int>& counts) {
      return std::all_of (indices.begin (), indices.end (), [&] (int i) { return counts[i] >= 2; });
    };
    std::vector<bool> redundant (patches.size (), false);
    for (std::size_t i = patches.size (); i-- > 0;)
    {
      const Patch& patch = patches[i];
      if (patch.beside_uncovered_face || !heldElsewhere (patch.vertices, vertex_holders) ||
          !heldElsewhere (patch.triangles, face_holders))
        continue;
      redundant[i] = true;
      holders.release (patch);
    }
    return redundant;
  }
} // namespace pcl_sparse
