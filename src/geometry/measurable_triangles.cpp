#include <pcl_sparse/geometry/measurable_triangles.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/thread_count.h>

#include <limits>

namespace pcl_sparse
{
  namespace
  {
    std::string
    flawDescription (TriangleFlaw flaw)
    {
      switch (flaw)
      {
        case TriangleFlaw::kCornerOutOfRange:
          return " has a corner index out of range";
        case TriangleFlaw::kCornerNotFinite:
          return " has a non-finite corner";
        default:
          return " has a corner coordinate over 1e75 (distances to it overflow)";
      }
    }
  } // namespace

  TriangleFlaw
  triangleFlaw (const TriangleMesh& mesh, std::size_t f)
  {
    const Eigen::Vector3i& t = mesh.triangles[f];
    const int vertices = static_cast<int> (mesh.vertices.size ());
    for (int c = 0; c < 3; ++c)
    {
      if (t[c] < 0 || t[c] >= vertices)
        return TriangleFlaw::kCornerOutOfRange;
      const Eigen::Vector3d& corner = mesh.vertices[t[c]];
      if (!corner.allFinite ())
        return TriangleFlaw::kCornerNotFinite;
      if (corner.cwiseAbs ().maxCoeff () > kLargestMeasurableCoordinate)
        return TriangleFlaw::kCornerTooLarge;
    }
    return TriangleFlaw::kNone;
  }

  void
  requireMeasurableTriangles (const TriangleMesh& mesh, const std::string& who, int num_threads)
  {
    if (mesh.triangles.empty ())
      throw Error (who + ": the mesh has no triangle");
    const int threads = resolveThreadCount (num_threads);
    const auto count = static_cast<std::ptrdiff_t> (mesh.triangles.size ());
    // The smallest flawed index, whatever the threads: the message names the same triangle on any count.
    std::ptrdiff_t first = std::numeric_limits<std::ptrdiff_t>::max ();
#pragma omp parallel for num_threads(threads) schedule(static) reduction(min : first)
    for (std::ptrdiff_t f = 0; f < count; ++f)
      if (f < first && triangleFlaw (mesh, static_cast<std::size_t> (f)) != TriangleFlaw::kNone)
        first = f;
    if (first < count)
      throw Error (who + ": triangle " + std::to_string (first) +
                   flawDescription (triangleFlaw (mesh, static_cast<std::size_t> (first))));
  }
} // namespace pcl_sparse
