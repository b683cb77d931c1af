#pragma once
/// \file mesh_topology.h
/// Adjacency of a TriangleMesh: vertex -> faces, vertex -> vertices, undirected edges, face -> faces.
/// Built once in O(#V + #F); every later stage walks the mesh through it.

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// A contiguous run of indices inside one of the CSR arrays below.
  struct IndexRange
  {
    const int* first;  ///< first index of the run
    const int* last;   ///< one past the last index
    /// Start of the run, for range-based for.
    const int* begin () const { return first; }
    /// End of the run, for range-based for.
    const int* end () const { return last; }
    /// Number of indices in the run.
    std::size_t size () const { return static_cast<std::size_t> (last - first); }
  };

  /// Connectivity of a triangle mesh. Lists are stored compressed (CSR): the items of vertex v are
  /// items[offsets[v] .. offsets[v + 1]). Everything is sorted, so the topology of a mesh is unique.
  struct MeshTopology
  {
    std::vector<int> vertex_face_offsets;      ///< #V + 1 offsets into vertex_faces
    std::vector<int> vertex_faces;             ///< faces incident to each vertex, ascending
    std::vector<int> vertex_neighbor_offsets;  ///< #V + 1 offsets into vertex_neighbors
    std::vector<int> vertex_neighbors;         ///< 1-ring: vertices sharing an edge with each vertex, ascending
    std::vector<Eigen::Vector2i> edges;        ///< #E undirected edges (a, b), a < b, ascending by (a, b)
    /// #E number of faces using each edge: 1 boundary, 2 manifold, > 2 non-manifold.
    std::vector<int> edge_face_count;
    /// #F edge ids; edge k of face f joins corners k and (k + 1) % 3; -1 where both corners are the same
    /// vertex (degenerate face).
    std::vector<Eigen::Vector3i> face_edges;
    /// #F face across edge k, or -1 on a boundary or non-manifold edge (non-manifold edges are cuts:
    /// nothing walks across them).
    std::vector<Eigen::Vector3i> face_neighbors;

    /// Number of vertices the topology was built for.
    std::size_t numVertices () const { return vertex_face_offsets.empty () ? 0 : vertex_face_offsets.size () - 1; }
    /// Number of undirected edges, #E.
    std::size_t numEdges () const { return edges.size (); }

    /// Faces incident to vertex \a v, ascending.
    IndexRange facesOf (int v) const
    {
      return {vertex_faces.data () + vertex_face_offsets[v], vertex_faces.data () + vertex_face_offsets[v + 1]};
    }
    /// 1-ring of vertex \a v, ascending.
    IndexRange neighborsOf (int v) const
    {
      return {vertex_neighbors.data () + vertex_neighbor_offsets[v],
              vertex_neighbors.data () + vertex_neighbor_offsets[v + 1]};
    }
    /// True if edge \a e is used by one face only.
    bool isBoundaryEdge (int e) const { return edge_face_count[e] == 1; }
    /// True if edge \a e is used by more than two faces.
    bool isNonManifoldEdge (int e) const { return edge_face_count[e] > 2; }
  };

  /// Builds the topology of a mesh in O(#V + #F).
  /// \param[in] mesh         triangle indices must be valid (0 <= i < #V); faces with repeated vertices are
  ///                         allowed and contribute only their proper edges
  /// \param[in] num_threads  OpenMP threads (0: all); the topology does not depend on it
  /// \return the connectivity, every list sorted
  MeshTopology
  buildMeshTopology (const TriangleMesh& mesh, int num_threads = 0);
} // namespace pcl_sparse
