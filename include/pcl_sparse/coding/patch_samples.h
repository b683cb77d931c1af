#pragma once
/// \file patch_samples.h
/// The samples a patch is coded from (docs/METHOD.md step 7) and their spacing (step 9's mu).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/patches/patch.h>

#include <cstdint>
#include <vector>

namespace pcl_sparse
{
  /// Sample spacing mu of a patch: median over its vertices of their mean 1-ring edge length (the full
  /// 1-ring in the mesh, 3D lengths), divided by r_P so it is in the patch's local scaled units.
  /// Vertices with no neighbour are skipped.
  /// \param[in] patch     radius and vertices set
  /// \param[in] mesh      the mesh
  /// \param[in] topology  its topology
  /// \return mu; 0 for an empty patch
  double
  patchSampleSpacing (const Patch& patch, const TriangleMesh& mesh, const MeshTopology& topology);

  /// patchSampleSpacing from precomputed per-vertex mean 1-ring edge lengths, so vertices shared by
  /// several patches are measured once.
  /// \param[in] patch                   radius and vertices set
  /// \param[in] mean_ring_edge_lengths  #V, meanRingEdgeLengths; entries <= 0 (no neighbour) are skipped
  /// \return mu; 0 for an empty patch
  double
  patchSampleSpacing (const Patch& patch, const std::vector<double>& mean_ring_edge_lengths);

  /// Mean length of the edges from each vertex to its 1-ring.
  /// \param[in] mesh      the mesh
  /// \param[in] topology  its topology
  /// \return #V lengths; 0 for a vertex without neighbours
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

  /// Points drawn uniformly by area on a patch's own triangles: a random triangle by area and a uniform
  /// barycentric point in it.
  /// \param[in] patch  triangles (face ids of \a mesh) and vertices set
  /// \param[in] mesh   the mesh
  /// \param[in] count  number of points
  /// \param[in] seed   seed of the draws: the same seed gives the same points
  /// \return \a count points; empty when the patch has no triangle of positive area
  std::vector<PatchSurfacePoint>
  drawPatchSurfacePoints (const Patch& patch, const TriangleMesh& mesh, int count, std::uint64_t seed);

  /// Points drawn uniformly by area on a patch's own triangles, in local coordinates (x', y', z'): a
  /// random triangle by area, a uniform barycentric point in it, and the barycentric combination of the
  /// corners' local coordinates (the mesh's own surface there, since the local map is affine):
  /// drawPatchSurfacePoints interpolating patch.local.
  /// \param[in] patch  triangles (face ids of \a mesh) and local coordinates set
  /// \param[in] mesh   the mesh
  /// \param[in] count  number of points
  /// \param[in] seed   seed of the draws: the same seed gives the same points
  /// \return \a count points; empty when the patch has no triangle of positive area
  std::vector<Eigen::Vector3d>
  drawPatchSurfaceSamples (const Patch& patch, const TriangleMesh& mesh, int count, std::uint64_t seed);

  /// A well-mixed 64-bit seed for one item under a global seed (splitmix64), so per-patch random streams
  /// do not depend on the thread that codes the patch.
  /// \param[in] seed   the global seed
  /// \param[in] index  the item (patch index)
  /// \return the item's seed
  std::uint64_t
  mixSeed (std::uint64_t seed, std::uint64_t index);
} // namespace pcl_sparse
