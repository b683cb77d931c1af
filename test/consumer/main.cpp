// Builds a torus with the installed library and checks its counts and topology; exit 0 when all agree.
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <cstdio>

int
main ()
{
  const pcl_sparse::TriangleMesh mesh = pcl_sparse::makeTorus (24, 12);
  const pcl_sparse::MeshTopology topology = pcl_sparse::buildMeshTopology (mesh);
  const pcl_sparse::MeshReport report = pcl_sparse::computeMeshReport (mesh, topology);
  std::printf ("vertices: %zu\nfaces: %zu\nedges: %zu\ngenus: %d\n", report.vertices, report.faces, report.edges,
               report.genus);
  const bool ok = report.vertices == 24 * 12 && report.faces == 2 * 24 * 12 && report.edges == 3 * 24 * 12 &&
                  report.closed && report.genus == 1;
  std::printf ("%s\n", ok ? "consumer: ok" : "consumer: WRONG COUNTS");
  return ok ? 0 : 1;
}
