#pragma once
/// \file mesh_cleaning.h
/// Removes the defects MeshReport counts (non-finite and unreferenced vertices, degenerate and duplicate
/// faces), optionally welds coincident vertices, and keeps index maps back to the input, so results on the
/// cleaned mesh can be reported on the file the user gave.

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// What cleanMesh removes. Defaults: everything, since every later stage assumes finite, referenced
  /// vertices and proper, distinct triangles.
  struct CleaningOptions
  {
    /// Drop vertices no (kept) face uses. Default true.
    bool drop_unreferenced_vertices = true;
    /// Drop faces with a repeated index or zero area (isDegenerateFace in mesh_report.h). Default true.
    bool drop_degenerate_faces = true;
    /// Drop every face with the same vertex set as an earlier face; the first one is kept. Default true.
    bool drop_duplicate_faces = true;
    /// Drop vertices with NaN/Inf coordinates together with the faces that use them. Default true.
    bool drop_non_finite_vertices = true;
    /// Merge each vertex into the first vertex at exactly its position (findCoincidentVertices), before the
    /// face rules above, so faces this makes degenerate or repeated are dropped by them. Default false: it
    /// joins what the file kept apart (a triangle soup, but also seams a writer split on purpose).
    bool weld_coincident_vertices = false;
  };

  /// A cleaned mesh with maps to and from the input.
  struct CleanedMesh
  {
    TriangleMesh mesh;                 ///< the cleaned mesh
    std::vector<int> vertex_to_input;  ///< #V_clean: input index of each cleaned vertex
    std::vector<int> input_to_vertex;  ///< #V_input: cleaned index of each input vertex (a welded vertex:
                                       ///< the one it was merged into), -1 if dropped
    std::vector<int> face_to_input;    ///< #F_clean: input index of each cleaned face
  };

  /// Removes the defects \a options select. Kept vertices and faces stay in input order.
  /// O(#V + #F log(max valence)).
  /// \param[in] mesh     the input; face indices must be valid (0 <= i < #V)
  /// \param[in] options  what to remove (default: everything)
  /// \return the cleaned mesh and its index maps to the input
  CleanedMesh
  cleanMesh (const TriangleMesh& mesh, const CleaningOptions& options = CleaningOptions ());
} // namespace pcl_sparse
