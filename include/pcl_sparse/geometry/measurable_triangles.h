#pragma once
/// \file measurable_triangles.h
/// Whether exact point-to-triangle distances can be measured on a mesh's triangles: every corner index in
/// range, every corner finite and small enough that pointTriangleDistance does not overflow. TriangleTree
/// and MeshSurfaceDistance's sampled surface refuse the same triangles with the same words.

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace pcl_sparse
{
  /// pointTriangleDistance multiplies four coordinate differences (Ericson's barycentric tests): under this
  /// magnitude their products stay under about 2e301; a triangle with corners 1e78 out measures NaN.
  constexpr double kLargestMeasurableCoordinate = 1e75;

  /// What keeps a triangle's distances from being measured.
  enum class TriangleFlaw : std::uint8_t
  {
    kNone = 0,
    kCornerOutOfRange,  ///< a corner index outside the vertices
    kCornerNotFinite,   ///< a corner with a NaN or infinite coordinate
    kCornerTooLarge     ///< a corner coordinate over kLargestMeasurableCoordinate in magnitude
  };

  /// The flaw of triangle \a f of \a mesh (its first flawed corner's), kNone if it is measurable.
  TriangleFlaw
  triangleFlaw (const TriangleMesh& mesh, std::size_t f);

  /// \brief Throws pcl_sparse::Error "<who>: triangle <index> has ..." naming the first flawed triangle of
  /// \a mesh (the same whatever the threads), or "<who>: the mesh has no triangle". O(T) on \a num_threads.
  /// \param[in] mesh         the surface
  /// \param[in] who          the caller's name, the message's first word
  /// \param[in] num_threads  OpenMP threads (0: all, resolveThreadCount)
  void
  requireMeasurableTriangles (const TriangleMesh& mesh, const std::string& who, int num_threads = 1);
} // namespace pcl_sparse
