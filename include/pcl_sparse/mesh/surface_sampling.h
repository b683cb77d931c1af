#pragma once
/// \file surface_sampling.h
/// Points drawn uniformly by area on a triangle mesh: the probes of evaluateCloudQuality, the samples of the
/// Chamfer distance (resampling/model_mesh_distance.h) and the tests' scans. One loop, the random engine
/// chosen by the caller (each keeps the draws it always made).

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross: the faces' areas

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace pcl_sparse
{
  /// \brief The face a draw by area falls on: the first index whose cumulative area reaches x, exactly as
  /// std::lower_bound over the cumulative areas finds it (the last face if none does), but through a guide
  /// table (Chen and Asau 1974): guide[j] is the first face reaching j total / T, so a draw searches its
  /// own bucket, a face or two on most meshes, where a binary search over all T faces takes a cache miss
  /// per step on large meshes. O(T) to build, O(1) expected per draw, O(log T) at worst.
  class CumulativeAreaSearch
  {
  public:
    /// \param[in] cumulative  the faces' areas summed in order (non-empty, non-decreasing); kept by reference
    explicit CumulativeAreaSearch (const std::vector<double>& cumulative)
      : cumulative_ (cumulative), guide_ (cumulative.size ())
    {
      const std::size_t count = cumulative.size ();
      std::size_t t = 0;
      for (std::size_t j = 0; j < count; ++j)
      {
        const double threshold = total () * (static_cast<double> (j) / static_cast<double> (count));
        while (t + 1 < count && cumulative[t] < threshold)
          ++t;
        guide_[j] = static_cast<std::uint32_t> (t);
      }
    }

    /// \return the first face whose cumulative area is at least \a x, the last face if none is
    std::size_t
    find (double x) const
    {
      const std::size_t count = cumulative_.size ();
      // Clamped in double: a NaN or an x far past the total (an infinite bucket) must not reach the cast.
      const double bucket = x / total () * static_cast<double> (count);
      const std::size_t j = !(bucket > 0.0) ? 0 : bucket < static_cast<double> (count - 1) ? static_cast<std::size_t> (bucket) : count - 1;
      const auto begin = cumulative_.begin ();
      std::size_t first = guide_[j];
      if (first > 0 && cumulative_[first - 1] >= x)  // rounding put x in an earlier bucket than its face's
        first = 0;
      const std::size_t last = j + 1 < count ? guide_[j + 1] + 1 : count;
      auto found = std::lower_bound (begin + static_cast<std::ptrdiff_t> (first), begin + static_cast<std::ptrdiff_t> (last), x);
      if (found == begin + static_cast<std::ptrdiff_t> (last))  // rounding put x past its bucket
        found = std::lower_bound (found, cumulative_.end (), x);
      return std::min<std::size_t> (static_cast<std::size_t> (found - begin), count - 1);
    }

  private:
    double
    total () const
    {
      return cumulative_.back ();
    }

    const std::vector<double>& cumulative_;
    std::vector<std::uint32_t> guide_;  ///< face indices fit: a mesh's faces are indexed by int
  };

  /// \brief \a n points drawn uniformly by area on \a mesh with \a engine (per point: a face by area, then
  /// two uniforms folded into the triangle), and the face each lies on when \a triangles is given. A mesh
  /// without triangles gives no point. O(T + n) expected (CumulativeAreaSearch).
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
    const CumulativeAreaSearch face_of (cumulative);
    points.resize (n);
    if (triangles)
      triangles->resize (n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::size_t t = face_of.find (uniform (engine) * total);
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
