/// Meshes for the memory benchmark (bench/memory.sh), which measures pcl_sparse_encode's peak memory:
///   bench_memory subdivide IN OUT.ply [times]   midpoint subdivision (each triangle into 4), times x
///   bench_memory torus N OUT.ply                an N x N torus (N^2 vertices, closed, genus 1)
/// Midpoint subdivision keeps the surface (the new vertices lie on the old faces), so the encoder sees
/// the same shape at 4x the vertex count: memory per vertex, not a different geometry, is measured.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>

using namespace pcl_sparse;

namespace
{
  TriangleMesh
  subdivideMidpoint (const TriangleMesh& mesh)
  {
    TriangleMesh out;
    out.vertices = mesh.vertices;
    out.vertices.reserve (mesh.vertices.size () + 3 * mesh.triangles.size () / 2 + 16);
    out.triangles.reserve (4 * mesh.triangles.size ());
    std::unordered_map<std::uint64_t, int> midpoints;
    midpoints.reserve (3 * mesh.triangles.size () / 2 + 16);
    auto midpoint = [&] (int a, int b) {
      const std::uint64_t key = (static_cast<std::uint64_t> (std::min (a, b)) << 32) | static_cast<std::uint32_t> (std::max (a, b));
      const auto found = midpoints.find (key);
      if (found != midpoints.end ())
        return found->second;
      const int index = static_cast<int> (out.vertices.size ());
      out.vertices.push_back (0.5 * (mesh.vertices[a] + mesh.vertices[b]));
      midpoints.emplace (key, index);
      return index;
    };
    for (const Eigen::Vector3i& t : mesh.triangles)
    {
      const int ab = midpoint (t[0], t[1]), bc = midpoint (t[1], t[2]), ca = midpoint (t[2], t[0]);
      out.triangles.emplace_back (t[0], ab, ca);
      out.triangles.emplace_back (t[1], bc, ab);
      out.triangles.emplace_back (t[2], ca, bc);
      out.triangles.emplace_back (ab, bc, ca);
    }
    return out;
  }
} // namespace

int
main (int argc, char** argv)
{
  try
  {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "subdivide" && (argc == 4 || argc == 5))
    {
      TriangleMesh mesh = loadTriangleMesh (argv[2]);
      const int times = argc == 5 ? std::atoi (argv[4]) : 1;
      for (int i = 0; i < times; ++i)
        mesh = subdivideMidpoint (mesh);
      saveTriangleMesh (argv[3], mesh);
      std::printf ("%s: %zu vertices, %zu faces\n", argv[3], mesh.vertices.size (), mesh.triangles.size ());
      return 0;
    }
    if (mode == "torus" && argc == 4)
    {
      const int n = std::atoi (argv[2]);
      const TriangleMesh mesh = makeTorus (n, n, 1.0, 0.3);
      saveTriangleMesh (argv[3], mesh);
      std::printf ("%s: %zu vertices, %zu faces\n", argv[3], mesh.vertices.size (), mesh.triangles.size ());
      return 0;
    }
    std::fprintf (stderr, "usage: %s subdivide IN OUT.ply [times] | torus N OUT.ply\n", argv[0]);
    return 1;
  }
  catch (const Error& e)
  {
    std::fprintf (stderr, "bench_memory: %s\n", e.what ());
    return 1;
  }
}
