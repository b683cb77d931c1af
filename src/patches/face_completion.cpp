#include <pcl_sparse/patches/face_completion.h>

#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/patches/face_placement.h>

#include <Eigen/Geometry>

#include <numeric>

namespace pcl_sparse
{
  FaceCompletionResult
  completePatchFaces (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                      const PatchOptions& options, std::vector<Patch>& patches, const std::vector<std::uint8_t>& must_cover)
  {
    FaceCompletionResult result;
    const int num_faces = static_cast<int> (mesh.triangles.size ());
    std::vector<std::uint8_t> in_patch (num_faces, 0);
    for (const Patch& p : patches)
      for (int f : p.triangles)
        in_patch[f] = 1;

    // Candidates are the patches holding a corner as grown, so they do not depend on the completion order.
    FacePlacer placer (mesh, topology, geometry, options, patches);
    for (int f = 0; f < num_faces; ++f)
    {
      if (in_patch[f] || !(geometry.face_areas[f] > 0.0))
        continue;
      const Eigen::Vector3i& t = mesh.triangles[f];
      if (!must_cover.empty () && !must_cover[t[0]] && !must_cover[t[1]] && !must_cover[t[2]])
        continue;
      ++result.faces_in_no_patch;
      const FacePlacer::Placement placement = placer.place (f);
      if (placement.patch < 0)
      {
        result.uncovered.push_back (f);
        continue;
      }
      in_patch[f] = 1;
      ++result.completed;
      result.without_smooth_variation += !placement.smooth_variation;
    }
    // Faces left in no patch: the patches at their corners (as grown) keep their footprints' full reach,
    // which is what covers such a face (PatchCode footprint, clip_footprints_at_border).
    for (int f : result.uncovered)
      for (int k = 0; k < 3; ++k)
        for (int p : placer.holdersOf (mesh.triangles[f][k]))
          patches[p].beside_uncovered_face = true;
    return result;
  }

  std::vector<int>
  facesInNoPatch (const TriangleMesh& mesh, const std::vector<Patch>& patches)
  {
    std::vector<std::uint8_t> in_patch (mesh.triangles.size (), 0);
    for (const Patch& p : patches)
      for (int f : p.triangles)
        in_patch[f] = 1;
    std::vector<int> faces;
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const double area =
          (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross (mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm ();
      if (!in_patch[f] && area > 0.0)
        faces.push_back (static_cast<int> (f));
    }
    return faces;
  }

  FaceCoverage
  faceCoverage (const TriangleMesh& mesh, const std::vector<Patch>& patches)
  {
    const std::vector<double> areas = computeFaceAreas (mesh);
    const std::vector<int> faces = facesInNoPatch (mesh, patches);
    const double total = std::accumulate (areas.begin (), areas.end (), 0.0);
    double uncovered = 0.0;
    for (int f : faces)
      uncovered += areas[f];
    FaceCoverage coverage;
    coverage.faces_in_no_patch = faces.size ();
    coverage.area_fraction = total > 0.0 ? uncovered / total : 0.0;
    return coverage;
  }
} // namespace pcl_sparse
