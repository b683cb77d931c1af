#pragma once
/// \file patch_samples.h
/// The samples a patch is coded from (METHOD.md step 7) and their spacing (step 9's mu).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// mu: median over the patch's vertices of their mean 1-ring edge length (the full 1-ring in the mesh,
  /// 3D lengths), divided by r_P so it is in the patch's local scaled units. 0 for an empty patch.
  double
  patchSampleSpacing (const Patch& patch, const TriangleMesh& mesh, const MeshTopology& topology);

  /// The same from precomputed per-vertex mean 1-ring edge lengths (meanRingEdgeLengths), so vertices
  /// shared by several patches are measured once. Vertices with no neighbour (length <= 0) are skipped.
  double
  patchSampleSpacing (const Patch& patch, const std::vector<double>& mean_ring_edge_lengths);

  /// Mean length of the edges from each vertex to its 1-ring (#V; 0 for a vertex without neighbours).
  std::vector<double>
  meanRingEdgeLengths (const TriangleMesh& mesh, const MeshTopology& topology);

  /// A point on one of a patch's triangles: its corners as positions in patch.vertices / patch.local, and
  /// barycentric weights (summing to 1).
  struct PatchSurfacePoint
  {
    Eigen::Vector3i corners;
    Eigen::Vector3d weights;

    /// The weighted combination of \a values at the corners (e.g. patch.local).
    Eigen::Vector3d
    interpolate (const std::vector<Eigen::Vector3d>& values) const
    {
      return weights[0] * values[corners[0]] + weights[1] * values[corners[1]] + weights[2] * values[corners[2]];
    }
  };

  /// \a count points drawn uniformly by area on the patch's own triangles (patch.triangles, face ids of
  /// \a mesh): a random triangle by area and a uniform barycentric point in it. Deterministic for a given
  /// \a seed. Empty when the patch has no triangle of positive area.
  std::vector<PatchSurfacePoint>
  drawPatchSurfacePoints (const Patch& patch, const TriangleMesh& mesh, int count, std::uint64_t seed);

  /// \a count points drawn uniformly by area on the patch's own triangles (patch.triangles, face ids of
  /// \a mesh), in local coordinates
  /// (x', y', z'): a random triangle by area, a uniform barycentric point in it, and the barycentric
  /// combination of the corners' local coordinates (the mesh's own surface there, since the local map is
  /// affine): drawPatchSurfacePoints interpolating patch.local.
  std::vector<Eigen::Vector3d>
  drawPatchSurfaceSamples (const Patch& patch, const TriangleMesh& mesh, int count, std::uint64_t seed);

  /// A well-mixed 64-bit seed for item \a index under \a seed (splitmix64), so per-patch random streams do
  /// not depend on the thread that codes the patch.
  std::uint64_t
  mixSeed (std::uint64_t seed, std::uint64_t index);
} // namespace pcl_sparse
