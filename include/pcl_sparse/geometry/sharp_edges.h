#pragma once
/// \file sharp_edges.h
/// Sharp (feature) edges by dihedral angle, and the vertices near them: the yardstick for where feature
/// detectors should put their keypoints (tests and bench/harris.sh).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// Manifold edges (exactly two faces) whose faces' normals differ by more than a given angle.
  /// \param[in] mesh         the mesh
  /// \param[in] topology     its topology
  /// \param[in] min_degrees  angle between the two face normals (180 degrees minus the interior dihedral
  ///                         angle) above which an edge is sharp
  /// \return ascending edge ids into topology.edges
  std::vector<int>
  findSharpEdges (const TriangleMesh& mesh, const MeshTopology& topology, double min_degrees);

  /// Flags the vertices near a sharp edge (findSharpEdges).
  /// \param[in] mesh         the mesh
  /// \param[in] topology     its topology
  /// \param[in] min_degrees  sharpness threshold, as in findSharpEdges
  /// \param[in] rings        how many rings around the edges' endpoints count as near (0: the endpoints)
  /// \return #V flags
  std::vector<bool>
  verticesNearSharpEdges (const TriangleMesh& mesh, const MeshTopology& topology, double min_degrees, int rings);
} // namespace pcl_sparse
