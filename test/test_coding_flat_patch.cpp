#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/patch_coder.h>
#include <pcl_sparse/coding/patch_samples.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using namespace pcl_sparse;

// A flat patch whose plane is not a coordinate plane: its heights in the frame are round-off (~1e-17), not
// shape. The relative tolerance eps ||y|| alone let OMP spend up to L atoms fitting that round-off (the
// flat faces of a rotated CAD part: 720 of anchor-dense's 3672 atoms).
TEST (PatchCoder, FlatPatchOfATiltedPlaneCodesNoAtoms)
{
  const TriangleMesh grid = makePlaneGrid (8, 1.0);
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd (0.7, Eigen::Vector3d (1.0, 2.0, 3.0).normalized ())).toRotationMatrix ();
  const Eigen::Vector3d origin (0.3, -0.1, 0.2);
  TriangleMesh mesh = grid;
  for (Eigen::Vector3d& v : mesh.vertices)
    v = rotation * v + origin;
  const MeshTopology topology = buildMeshTopology (mesh);
  Patch patch;
  patch.seed = 0;
  patch.origin = origin;
  patch.frame = rotation;
  patch.radius = 1.5;
  double largest = 0.0;
  for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
  {
    patch.vertices.push_back (static_cast<int> (v));
    patch.local.push_back (patch.toLocal (mesh.vertices[v]));
    largest = std::max (largest, std::abs (patch.local.back ().z ()));
  }
  for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    patch.triangles.push_back (static_cast<int> (f));
  ASSERT_LT (largest, 1e-14);  // round-off
  ASSERT_GT (largest, 0.0);    // but not exactly 0 (which OMP already codes with no atom)
  for (CosineBasisKind kind : {CosineBasisKind::Paper, CosineBasisKind::Dct})
  {
    const PatchCode code = codePatch (patch, 0, mesh, meanRingEdgeLengths (mesh, topology), *makeCosineBasis (kind, 12),
                                      SparseCodingOptions ());
    EXPECT_TRUE (code.atoms.empty ()) << code.atoms.size () << " atoms";
  }
  // A real height of the same patch is still coded.
  for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
    patch.local[v].z () = 0.1 * patch.local[v].x () * patch.local[v].x ();
  const PatchCode curved = codePatch (patch, 0, mesh, meanRingEdgeLengths (mesh, topology),
                                      *makeCosineBasis (CosineBasisKind::Dct, 12), SparseCodingOptions ());
  EXPECT_FALSE (curved.atoms.empty ());
}
