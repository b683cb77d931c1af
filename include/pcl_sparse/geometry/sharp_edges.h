#pragma once
/// \file sharp_edges.h
/// Sharp (feature) edges by dihedral angle, and the vertices near them: the yardstick for where feature
/// detectors should put their keypoints (tests and bench/harris.sh).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// Manifold edges (exactly two faces) whose faces' normals differ by more than \a min_degrees (the
  /// angle between the normals, i.e. 180 degrees minus the interior dihedral angle).
  ///   returns  ascending edge ids into topology.edges
  std::vector<int>
  findSharpEdges (const TriangleMesh& mesh, const MeshTopology& topology, double min_degrees);

  /// Flags the vertices within \a rings rings (0: the endpoints only) of an endpoint of a sharp edge.
  ///   returns  #V flags
  std::vector<bool>
  verticesNearSharpEdges (const TriangleMesh& mesh, const MeshTopology& topology, double min_degrees, int rings);
} // namespace pcl_sparse
