// A separate project using the installed pcl_sparse as a PCL user would (run by the consumer_project test):
// a torus checked for its counts and topology, then the README's program on a pcl::PolygonMesh loaded with
// PCL's own pcl::io::loadPolygonFile. Prints "consumer: ok" and exits 0 when every check holds.
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/conversions.h>
#include <pcl/io/vtk_lib_io.h>

#include <cmath>
#include <cstdio>

namespace
{
  bool
  torusCountsAgree ()
  {
    const pcl_sparse::TriangleMesh mesh = pcl_sparse::makeTorus (24, 12);
    const pcl_sparse::MeshTopology topology = pcl_sparse::buildMeshTopology (mesh);
    const pcl_sparse::MeshReport report = pcl_sparse::computeMeshReport (mesh, topology);
    std::printf ("vertices: %zu\nfaces: %zu\nedges: %zu\ngenus: %d\n", report.vertices, report.faces, report.edges,
                 report.genus);
    return report.vertices == 24 * 12 && report.faces == 2 * 24 * 12 && report.edges == 3 * 24 * 12 &&
           report.closed && report.genus == 1;
  }

  /// The README's program: pcl::PolygonMesh -> sparse model -> resampled PointNormal cloud.
  pcl::PointCloud<pcl::PointNormal>
  resamplePolygonMesh (const pcl::PolygonMesh& mesh, std::size_t points)
  {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    pcl::fromPCLPointCloud2 (mesh.cloud, *cloud);
    pcl_sparse::SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputCloud (cloud);
    encoder.setInputPolygons (std::make_shared<std::vector<pcl::Vertices>> (mesh.polygons));
    pcl_sparse::SparseSurfaceModel model;
    encoder.compute (model);
    pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (std::make_shared<pcl_sparse::SparseSurfaceModel> (model));
    resampling.setPointCount (points);
    pcl::PointCloud<pcl::PointNormal> out;
    resampling.compute (out);
    return out;
  }

  /// Resamples a unit sphere read back by PCL's loader: every point near radius 1, normals outward.
  bool
  sphereResamples ()
  {
    pcl_sparse::saveTriangleMesh ("consumer-sphere.obj", pcl_sparse::makeIcosphere (3));
    pcl::PolygonMesh mesh;
    if (pcl::io::loadPolygonFile ("consumer-sphere.obj", mesh) == 0)
      return std::printf ("pcl::io::loadPolygonFile read nothing\n"), false;
    const pcl::PointCloud<pcl::PointNormal> out = resamplePolygonMesh (mesh, 5000);
    // Means: the icosphere's flat faces sit up to 0.003 inside the sphere (the samples come from them), and
    // the paper's even atoms bend normals near patch borders (docs/METHOD.md).
    double radius_error = 0.0, dot = 0.0;
    for (const pcl::PointNormal& p : out)
    {
      radius_error += std::abs (p.getVector3fMap ().norm () - 1.0);
      dot += p.getNormalVector3fMap ().dot (p.getVector3fMap ().normalized ());
    }
    radius_error /= static_cast<double> (out.size ());
    dot /= static_cast<double> (out.size ());
    std::printf ("resampled points: %zu\nmean radius error: %g\nmean normal dot: %g\n", out.size (), radius_error, dot);
    return out.size () == 5000 && radius_error < 0.005 && dot > 0.98;
  }
} // namespace

int
main ()
{
  const bool ok = torusCountsAgree () && sphereResamples ();
  std::printf ("%s\n", ok ? "consumer: ok" : "consumer: WRONG");
  return ok ? 0 : 1;
}
