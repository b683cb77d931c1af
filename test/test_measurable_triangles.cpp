// Which triangles exact distances can be measured on (geometry/measurable_triangles.h), and that the exact and
// the sampled distance to a mesh refuse the same ones.
#include "error_message.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/measurable_triangles.h>
#include <pcl_sparse/geometry/point_triangle_distance.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/model_mesh_distance.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace pcl_sparse;
using pcl_sparse_test::errorMessage;

namespace
{
  /// Gives corner \a c of triangle \a f a vertex of its own at \a position (no other triangle shares the flaw).
  void
  moveCorner (TriangleMesh& mesh, std::size_t f, int c, const Eigen::Vector3d& position)
  {
    mesh.triangles[f][c] = static_cast<int> (mesh.vertices.size ());
    mesh.vertices.push_back (position);
  }
} // namespace

TEST (MeasurableTriangles, EachFlawIsNamed)
{
  TriangleMesh mesh = makePlaneGrid (4, 0.5);
  EXPECT_EQ (triangleFlaw (mesh, 0), TriangleFlaw::kNone);
  EXPECT_NO_THROW (requireMeasurableTriangles (mesh, "caller"));
  moveCorner (mesh, 3, 1, Eigen::Vector3d (0.0, 0.0, 2e75));
  const int corner = mesh.triangles[3][1];
  EXPECT_EQ (triangleFlaw (mesh, 3), TriangleFlaw::kCornerTooLarge);
  mesh.vertices[corner].z () = -std::numeric_limits<double>::infinity ();
  EXPECT_EQ (triangleFlaw (mesh, 3), TriangleFlaw::kCornerNotFinite);
  mesh.vertices[corner].z () = std::nan ("");
  EXPECT_EQ (triangleFlaw (mesh, 3), TriangleFlaw::kCornerNotFinite);
  mesh.triangles[3][0] = -1;  // the first flawed corner's flaw
  EXPECT_EQ (triangleFlaw (mesh, 3), TriangleFlaw::kCornerOutOfRange);
  mesh.triangles[3][0] = static_cast<int> (mesh.vertices.size ());
  EXPECT_EQ (triangleFlaw (mesh, 3), TriangleFlaw::kCornerOutOfRange);
  EXPECT_EQ (errorMessage ([&] { requireMeasurableTriangles (TriangleMesh (), "caller"); }),
             "caller: the mesh has no triangle");
}

// The message names the first flawed triangle whatever the threads, in the caller's words.
TEST (MeasurableTriangles, FirstFlawedTriangleOnAnyThreadCount)
{
  TriangleMesh sphere = makeIcosphere (5);
  const std::size_t last = sphere.triangles.size () - 1;
  sphere.triangles[last][1] = -1;
  moveCorner (sphere, last / 2, 0, Eigen::Vector3d (std::nan (""), 0.0, 0.0));
  moveCorner (sphere, 4000, 2, Eigen::Vector3d (0.0, -1e76, 0.0));
  for (const int threads : {1, 2, 3})
    EXPECT_EQ (errorMessage ([&] { requireMeasurableTriangles (sphere, "caller", threads); }),
               "caller: triangle 4000 has a corner coordinate over 1e75 (distances to it overflow)")
      << threads;
}

// Exact and sampled distances refuse the same triangles; before they shared the check, the sampled distance
// measured a corner over 1e75 and gave NaN where the exact one refused it.
TEST (MeasurableTriangles, ExactAndSampledDistancesRefuseTheSameTriangles)
{
  // A triangle far out, each corner 1e78 along an axis: its distance from the origin overflows to NaN.
  TriangleMesh huge = makeIcosphere (2);
  for (int c = 0; c < 3; ++c)
    moveCorner (huge, 9, c, 1e78 * Eigen::Vector3d::Unit (c));
  const Eigen::Vector3i& t = huge.triangles[9];
  EXPECT_TRUE (std::isnan (pointTriangleDistance (Eigen::Vector3d::Zero (), huge.vertices[t[0]], huge.vertices[t[1]],
                                                  huge.vertices[t[2]])));
  const std::string exact = errorMessage ([&] { MeshSurfaceDistance distance (huge); });
  const std::string sampled = errorMessage ([&] { MeshSurfaceDistance distance (huge, MeshSurfaceDistance::Sampling {1000}); });
  EXPECT_NE (exact.find ("triangle 9 has a corner coordinate over 1e75"), std::string::npos) << exact;
  EXPECT_EQ (sampled, "MeshSurfaceDistance: triangle 9 has a corner coordinate over 1e75 (distances to it overflow)");
  TriangleMesh nan_corner = makeIcosphere (2);
  moveCorner (nan_corner, 0, 2, Eigen::Vector3d (std::nan (""), 0.0, 0.0));
  EXPECT_EQ (errorMessage ([&] { MeshSurfaceDistance distance (nan_corner, MeshSurfaceDistance::Sampling {1000}); }),
             "MeshSurfaceDistance: triangle 0 has a non-finite corner");
}
