#pragma once
/// \file mesh_cleaning.h
/// Removes the defects MeshReport counts (non-finite and unreferenced vertices, degenerate and duplicate
/// faces) and keeps index maps back to the input, so results on the cleaned mesh can be reported on the
/// file the user gave.

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
  };

  /// A cleaned mesh with maps to and from the input.
  ///   vertex_to_input  #V_clean input index of each cleaned vertex
  ///   input_to_vertex  #V_input cleaned index of each input vertex, or -1 when it was dropped
  ///   face_to_input    #F_clean input index of each cleaned face
  struct CleanedMesh
  {
    TriangleMesh mesh;
    std::vector<int> vertex_to_input;
    std::vector<int> input_to_vertex;
    std::vector<int> face_to_input;
  };

  /// Cleans \a mesh as \a options say. Kept vertices and faces stay in input order. Face indices of
  /// \a mesh must be valid (0 <= i < #V). O(#V + #F log(max valence)).
  CleanedMesh
  cleanMesh (const TriangleMesh& mesh, const CleaningOptions& options = CleaningOptions ());
} // namespace pcl_sparse
