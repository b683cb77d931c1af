#include <pcl_sparse/patches/patch_merging.h>

#include <pcl_sparse/patches/element_holders.h>
#include <pcl_sparse/patches/face_placement.h>

#include <algorithm>

namespace pcl_sparse
{
  std::vector<bool>
  mergeSmallPatches (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                     const PatchOptions& options, int max_own_elements, std::vector<Patch>& patches,
                     const std::vector<std::uint8_t>& seed_vertices)
  {
    std::vector<bool> merged (patches.size (), false);
    if (max_own_elements < 0)
      return merged;
    ElementHolders holders = countElementHolders (mesh, patches, seed_vertices);
    std::vector<int>& vertex_holders = holders.vertices;
    std::vector<int>& face_holders = holders.faces;
    FacePlacer placer (mesh, topology, geometry, options, patches);
    std::vector<int> own_vertices, own_faces, pending, gained_vertices;
    std::vector<int> placed;  // own faces placed in a neighbour
    for (std::size_t i = patches.size (); i-- > 0;)
    {
      const Patch& patch = patches[i];
      if (patch.beside_uncovered_face)
        continue;
      own_vertices.clear ();
      own_faces.clear ();
      for (int v : patch.vertices)
        if (vertex_holders[v] == 1)
          own_vertices.push_back (v);
      for (int f : patch.triangles)
        if (face_holders[f] == 1)
          own_faces.push_back (f);
      if (static_cast<int> (own_vertices.size () + own_faces.size ()) > max_own_elements)
        continue;

      const int p = static_cast<int> (i);
      placer.setRemoved (p, true);
      const std::size_t mark = placer.mark ();
      placed.clear ();
      gained_vertices.clear ();
      pending = own_faces;
      // A face may fit a neighbour only once another own face brought it a corner: retry while any is placed.
      for (bool progress = true; progress && !pending.empty ();)
      {
        progress = false;
        std::size_t kept = 0;
        for (int f : pending)
        {
          const FacePlacer::Placement placement = placer.place (f, true);
          if (placement.patch < 0)
          {
            pending[kept++] = f;
            continue;
          }
          progress = true;
          placed.push_back (f);
          const std::vector<int>& vertices = patches[placement.patch].vertices;
          gained_vertices.insert (gained_vertices.end (), vertices.end () - placement.num_vertices, vertices.end ());
        }
        pending.resize (kept);
      }
      std::sort (gained_vertices.begin (), gained_vertices.end ());
      const bool vertices_kept = std::all_of (own_vertices.begin (), own_vertices.end (), [&] (int v) {
        return std::binary_search (gained_vertices.begin (), gained_vertices.end (), v);
      });
      if (!pending.empty () || !vertices_kept)
      {
        placer.rollback (mark);
        placer.setRemoved (p, false);
        continue;
      }
      merged[i] = true;
      holders.release (patch);
      for (int f : placed)
        ++face_holders[f];
      for (int v : gained_vertices)
        ++vertex_holders[v];
    }
    return merged;
  }
} // namespace pcl_sparse
