#pragma once
/// \file mesh_report.h
/// What is in a triangle mesh and what is wrong with it: counts, defects, topology (boundary loops,
/// components, genus) and scale. Linear in the mesh size; used by pcl_sparse_info and by the stages to
/// refuse meshes they cannot handle.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// Summary of a mesh. Edge counts come from MeshTopology (an edge belongs to every face that uses it).
  struct MeshReport
  {
    std::size_t vertices = 0;               ///< #V as stored (unreferenced vertices included)
    std::size_t faces = 0;                  ///< #F
    std::size_t edges = 0;                  ///< undirected edges
    std::size_t unreferenced_vertices = 0;  ///< vertices used by no face
    std::size_t non_finite_vertices = 0;    ///< vertices with a NaN or Inf coordinate
    std::size_t degenerate_faces = 0;       ///< faces with a repeated index or zero area (isDegenerateFace)
    std::size_t duplicate_faces = 0;        ///< faces with the same vertex set as an earlier face (extra copies)
    std::size_t boundary_edges = 0;         ///< edges used by one face
    std::size_t boundary_loops = 0;         ///< connected pieces of the boundary-edge graph (loops touching
                                            ///< at a vertex count as one; on a manifold mesh they never touch)
    std::size_t nonmanifold_edges = 0;      ///< edges used by more than two faces
    std::size_t nonmanifold_vertices = 0;   ///< vertices whose faces form more than one fan over manifold edges
    std::size_t components = 0;             ///< face components (faces joined through shared vertices);
                                            ///< unreferenced vertices are not components
    long euler_characteristic = 0;          ///< V - E + F over referenced vertices
    bool manifold = false;                  ///< has faces, no non-manifold edge or vertex, no face with a
                                            ///< repeated index (a point cloud is not a manifold mesh)
    bool orientable = false;                ///< manifold and every component can be oriented consistently
    bool closed = false;                    ///< manifold and no boundary edge
    int genus = -1;                         ///< sum over components of (2 - chi_c - b_c) / 2; -1 (unknown)
                                            ///< unless manifold and orientable
    double bbox_diagonal = 0.0;             ///< diagonal of the bounding box of the finite vertices
    double mean_edge_length = 0.0;          ///< mean length over edges with finite end points
  };

  /// Counts, defects, topology and scale of a mesh. O(#V + #F) apart from sorting the few faces around
  /// each vertex.
  /// \param[in] mesh      the mesh
  /// \param[in] topology  its topology (buildMeshTopology (mesh))
  /// \return the report
  MeshReport
  computeMeshReport (const TriangleMesh& mesh, const MeshTopology& topology);

  /// Whether a face repeats a corner, (a, a, b) in any order: no area, and a side that is not an edge.
  inline bool
  hasRepeatedIndex (const Eigen::Vector3i& t)
  {
    return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
  }

  /// Whether a triangle repeats a vertex index or has zero area. Zero area means
  /// |(b - a) x (c - a)| <= 1e-12 * (longest edge)^2 (collinear corners up to rounding); a face with a
  /// non-finite corner is not called degenerate here (it is counted by non_finite_vertices).
  /// \param[in] mesh  the mesh
  /// \param[in] f     face index into mesh.triangles
  /// \return true for a degenerate face
  bool
  isDegenerateFace (const TriangleMesh& mesh, int f);

  /// The number of edges used by more than two faces, as the stages see them: faces repeating a corner, which
  /// they leave out (SurfaceStage::getFacesWithRepeatedCorners), are not counted; otherwise
  /// MeshReport::nonmanifold_edges. Without building the topology: the face sides bucketed by vertex,
  /// O(#V + #F). Faces must index existing vertices.
  /// \param[in] mesh        the mesh
  /// \param[in] first_copy  empty (default), or findDuplicateFaces (mesh): the extra copies of a face, which
  ///                        the stages leave out too, are then not counted
  /// \return the number of non-manifold edges
  std::size_t
  countNonManifoldEdges (const TriangleMesh& mesh, const std::vector<int>& first_copy = {});

  /// For every face, the index of the first face with the same vertex set (itself when it is the first);
  /// orientation is ignored. O(#V + #F log(max valence)).
  /// \param[in] mesh  the mesh
  /// \return #F face indices
  std::vector<int>
  findDuplicateFaces (const TriangleMesh& mesh);
} // namespace pcl_sparse
