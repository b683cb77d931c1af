#pragma once
/// \file surface_sampling.h
/// Points drawn uniformly by area on a triangle mesh: the probes of evaluateCloudQuality, the samples of the
/// Chamfer distance (resampling/model_mesh_distance.h) and the tests' scans. One loop, the random engine
/// chosen by the caller (each keeps the draws it always made).

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <random>
#include <vector>

namespace pcl_sparse
{
  /// \brief \a n points drawn uniformly by area on \a mesh with \a engine (per point: a face by area, then
  /// two uniforms folded into the triangle), and the face each lies on when \a triangles is given. A mesh
  /// without triangles gives no point. O(T + n log T).
  /// \param[in]     mesh       the surface
  /// \param[in]     n          points to draw
  /// \param[in,out] engine     a uniform random bit generator (std::mt19937, std::mt19937_64, ...)
  /// \param[out]    points     the points
  /// \param[out]    triangles  if given, the face of each point
  /// \param[out]    area       if given, the mesh's area (the faces' areas summed in order)
  template <typename Engine>
  void
  sampleMeshSurfaceWith (const TriangleMesh& mesh, std::size_t n, Engine& engine, std::vector<Eigen::Vector3d>& points,
                         std::vector<int>* triangles = nullptr, double* area = nullptr)
  {
    points.clear ();
    if (triangles)
      triangles->clear ();
    std::vector<double> cumulative (mesh.triangles.size ());
    double total = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size (); ++t)
    {
      const Eigen::Vector3i& f = mesh.triangles[t];
      total += 0.5 * (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross (mesh.vertices[f[2]] - mesh.vertices[f[0]]).norm ();
      cumulative[t] = total;
    }
    if (area)
      *area = total;
    if (mesh.triangles.empty ())
      return;
    std::uniform_real_distribution<double> uniform (0.0, 1.0);
    points.resize (n);
    if (triangles)
      triangles->resize (n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::size_t t = std::min<std::size_t> (
        std::lower_bound (cumulative.begin (), cumulative.end (), uniform (engine) * total) - cumulative.begin (),
        mesh.triangles.size () - 1);
      double u = uniform (engine), v = uniform (engine);
      if (u + v > 1.0)
      {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      const Eigen::Vector3i& f = mesh.triangles[t];
      points[i] = mesh.vertices[f[0]] + u * (mesh.vertices[f[1]] - mesh.vertices[f[0]]) +
                  v * (mesh.vertices[f[2]] - mesh.vertices[f[0]]);
      if (triangles)
        (*triangles)[i] = static_cast<int> (t);
    }
  }

  /// sampleMeshSurfaceWith a std::mt19937 seeded with \a seed (bench/bench_format's samples).
  inline void
  sampleMeshSurface (const TriangleMesh& mesh, std::size_t n, unsigned seed, std::vector<Eigen::Vector3d>& points,
                     std::vector<int>* triangles = nullptr)
  {
    std::mt19937 engine (seed);
    sampleMeshSurfaceWith (mesh, n, engine, points, triangles);
  }
} // namespace pcl_sparse
