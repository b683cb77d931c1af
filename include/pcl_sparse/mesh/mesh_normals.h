#pragma once
/// \file mesh_normals.h
/// Face normals, face areas and vertex normals of a triangle mesh (docs/METHOD.md step 2).

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// How face normals are weighted into a vertex normal.
  enum class NormalWeighting
  {
    Area,  ///< by face area (sum of the unnormalised face normals)
    Angle  ///< by the face's interior angle at the vertex (Thürmer & Wüthrich)
  };

  /// Unit normal of every face, oriented by the corner order (counter-clockwise = outward).
  /// \param[in] mesh  the mesh
  /// \return #F unit normals; the zero vector for degenerate faces (zero area)
  std::vector<Eigen::Vector3d>
  computeFaceNormals (const TriangleMesh& mesh);

  /// Area of every face.
  /// \param[in] mesh  the mesh
  /// \return #F areas
  std::vector<double>
  computeFaceAreas (const TriangleMesh& mesh);

  /// Unit normal of every vertex as the weighted mean of its faces' normals (docs/METHOD.md step 2).
  /// \param[in] mesh       the mesh
  /// \param[in] topology   its topology (buildMeshTopology)
  /// \param[in] weighting  face weights: area (default) or corner angle
  /// \return #V unit normals; the zero vector for vertices with no non-degenerate face
  std::vector<Eigen::Vector3d>
  computeVertexNormals (const TriangleMesh& mesh, const MeshTopology& topology,
                        NormalWeighting weighting = NormalWeighting::Area);
} // namespace pcl_sparse
