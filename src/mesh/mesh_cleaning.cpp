#include <pcl_sparse/mesh/mesh_cleaning.h>
#include <pcl_sparse/mesh/mesh_report.h>

namespace pcl_sparse
{
  CleanedMesh
  cleanMesh (const TriangleMesh& mesh, const CleaningOptions& options)
  {
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
      if (!keep_vertex[v] || (options.drop_unreferenced_vertices && !referenced[v]))
        continue;
      out.input_to_vertex[v] = static_cast<int> (out.vertex_to_input.size ());
      out.vertex_to_input.push_back (v);
    }

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
