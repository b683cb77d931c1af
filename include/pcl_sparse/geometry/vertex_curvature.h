#pragma once
/// \file vertex_curvature.h
/// Principal curvatures and directions at every vertex: a degree-2 jet (fitMongeJet) over the vertex's
/// k-ring, in the frame of its vertex normal (docs/METHOD.md step 6 applies the same fit to whole patches).

#include <pcl_sparse/geometry/quadric_fit.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// Jet of every vertex fitted to its k-ring (the vertex included), origin at the vertex, frame from its
  /// normal. Where the fit is underdetermined (fewer than 6 points, collinear points, zero normal) the
  /// entry is a jet with NaN curvatures. OpenMP over vertices.
  /// \param[in] mesh      the mesh
  /// \param[in] topology  its topology
  /// \param[in] normals   #V unit vertex normals (computeVertexNormals); each jet's normal is oriented
  ///                      like its vertex's
  /// \param[in] rings     k, the rings each fit uses
  /// \return #V jets (curvature sign convention of MongeJet: a sphere with outward normals has 1 / r)
  std::vector<MongeJet>
  computeVertexMongeJets (const TriangleMesh& mesh, const MeshTopology& topology,
                          const std::vector<Eigen::Vector3d>& normals, int rings = 2);
} // namespace pcl_sparse
