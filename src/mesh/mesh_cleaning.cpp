#include <pcl_sparse/mesh/mesh_cleaning.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/vertex_welding.h>

namespace pcl_sparse
{
  CleanedMesh
  cleanMesh (const TriangleMesh& input, const CleaningOptions& options)
  {
    // Welding: faces on the first vertex at each position; the other vertices are dropped below and mapped
    // to their first one at the end.
    std::vector<int> first_at;
    TriangleMesh welded;
    if (options.weld_coincident_vertices)
    {
      first_at = findCoincidentVertices (input);
      welded.vertices = input.vertices;
      welded.triangles = input.triangles;
      for (Eigen::Vector3i& t : welded.triangles)
        for (int k = 0; k < 3; ++k)
          t[k] = first_at[t[k]];
    }
    const TriangleMesh& mesh = options.weld_coincident_vertices ? welded : input;
    const int num_vertices = static_cast<int> (mesh.vertices.size ());
    const int num_faces = static_cast<int> (mesh.triangles.size ());

    std::vector<char> keep_vertex (num_vertices, 1);
    if (options.drop_non_finite_vertices)
      for (int v = 0; v < num_vertices; ++v)
        keep_vertex[v] = mesh.vertices[v].allFinite ();

    // Faces first: which faces survive decides which vertices are still referenced.
    std::vector<int> first_copy;
    if (options.drop_duplicate_faces)
      first_copy = findDuplicateFaces (mesh);
    CleanedMesh out;
    std::vector<char> referenced (num_vertices, 0);
    for (int f = 0; f < num_faces; ++f)
    {
      const auto& t = mesh.triangles[f];
      if (!keep_vertex[t[0]] || !keep_vertex[t[1]] || !keep_vertex[t[2]])
        continue;
      if (options.drop_degenerate_faces && isDegenerateFace (mesh, f))
        continue;
      // The first copy may itself be dropped (degenerate or non-finite); then all copies are gone too,
      // which is what we want since they are the same triangle.
      if (options.drop_duplicate_faces && first_copy[f] != f)
        continue;
      out.face_to_input.push_back (f);
      referenced[t[0]] = referenced[t[1]] = referenced[t[2]] = 1;
    }

    out.input_to_vertex.assign (num_vertices, -1);
    for (int v = 0; v < num_vertices; ++v)
    {
      if (!keep_vertex[v] || (options.drop_unreferenced_vertices && !referenced[v]) || (!first_at.empty () && first_at[v] != v))
        continue;
      out.input_to_vertex[v] = static_cast<int> (out.vertex_to_input.size ());
      out.vertex_to_input.push_back (v);
    }
    for (std::size_t v = 0; v < first_at.size (); ++v)
      out.input_to_vertex[v] = out.input_to_vertex[first_at[v]];

    out.mesh.vertices.reserve (out.vertex_to_input.size ());
    for (int v : out.vertex_to_input)
      out.mesh.vertices.push_back (mesh.vertices[v]);
    out.mesh.triangles.reserve (out.face_to_input.size ());
    for (int f : out.face_to_input)
    {
      const auto& t = mesh.triangles[f];
      out.mesh.triangles.emplace_back (out.input_to_vertex[t[0]], out.input_to_vertex[t[1]], out.input_to_vertex[t[2]]);
    }
    return out;
  }
} // namespace pcl_sparse
