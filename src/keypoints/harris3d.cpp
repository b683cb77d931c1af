#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/geometry/morton_order.h>
#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/mesh/bounding_box.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>

namespace pcl_sparse
{
  namespace
  {
    constexpr double kNoResponse = std::numeric_limits<double>::quiet_NaN ();

    /// Per-thread scratch: reused across the vertices a thread handles.
    struct ResponseScratch
    {
      VertexMarks marks;
      std::vector<int> neighborhood;
      std::vector<Eigen::Vector3d> local;
    };

    double
    responseOfVertex (const TriangleMesh& mesh, const MeshTopology& topology, int v, const Harris3DOptions& options,
                      const AdaptiveRingOptions& adaptive, ResponseScratch& scratch)
    {
      if (options.rings > 0)
        collectKRing (topology, v, options.rings, scratch.marks, scratch.neighborhood);
      else
        collectAdaptiveRing (mesh, topology, v, adaptive, scratch.marks, scratch.neighborhood);
      const auto& hood = scratch.neighborhood;
      if (static_cast<int> (hood.size ()) - 1 < options.min_neighbors || hood.size () < 6)
        return kNoResponse;

      Eigen::Vector3d centroid = Eigen::Vector3d::Zero ();
      for (int u : hood)
        centroid += mesh.vertices[u];
      centroid /= static_cast<double> (hood.size ());
      if (!centroid.allFinite ())
        return kNoResponse;
      Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero ();
      for (int u : hood)
      {
        const Eigen::Vector3d d = mesh.vertices[u] - centroid;
        covariance.noalias () += d * d.transpose ();
      }
      // Eigenvalues ascending: column 0 (smallest) becomes z, the two others span the fitting plane.
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca (covariance);
      if (pca.info () != Eigen::Success)
        return kNoResponse;
      Eigen::Matrix3d axes;
      axes << pca.eigenvectors ().col (2), pca.eigenvectors ().col (1), pca.eigenvectors ().col (0);
      const Eigen::Vector3d v_local = axes.transpose () * (mesh.vertices[v] - centroid);

      scratch.local.clear ();
      for (int u : hood)
      {
        Eigen::Vector3d p = axes.transpose () * (mesh.vertices[u] - centroid);
        p.x () -= v_local.x ();
        p.y () -= v_local.y ();
        scratch.local.push_back (p);
      }
      HeightQuadric quadric;
      if (!fitHeightQuadric (scratch.local, quadric))
        return kNoResponse;
      return harris3DResponseOfQuadric (quadric, options.k);
    }

    /// The vertices to process, sorted along a Morton (Z-order) curve: consecutive vertices then share
    /// most of their neighbourhoods in cache, which matters on meshes whose vertex order is not spatial
    /// (e.g. after subdivision). Only the processing order changes; each response is written to its own
    /// index, so the result does not depend on it. Repeated indices are computed once (two threads must
    /// never write the same entry).
    std::vector<int>
    spatialOrder (const TriangleMesh& mesh, const std::vector<int>* indices)
    {
      return indices ? mortonOrder (mesh.vertices, *indices) : mortonOrder (mesh.vertices);
    }

    std::vector<double>
    computeResponses (const TriangleMesh& mesh, const MeshTopology& topology, const Harris3DOptions& options,
                      const std::vector<int>* indices)
    {
      validateHarris3DOptions (options);
      const std::size_t num_vertices = mesh.numVertices ();
      if (topology.numVertices () != num_vertices)
        throw Error ("computeHarris3DResponses: the topology does not belong to the mesh (vertex counts differ)");
      if (indices)
        for (int v : *indices)
          if (v < 0 || static_cast<std::size_t> (v) >= num_vertices)
            throw Error ("computeHarris3DResponses: vertex index " + std::to_string (v) + " out of range");

      AdaptiveRingOptions adaptive;
      adaptive.radius = options.adaptive_fraction * boundingBoxDiagonal (mesh);
      adaptive.min_neighbors = options.min_neighbors;
      adaptive.max_rings = options.max_rings;

      std::vector<double> responses (num_vertices, kNoResponse);
      const std::vector<int> order = spatialOrder (mesh, indices);
      const std::int64_t count = static_cast<std::int64_t> (order.size ());
      const int threads = resolveThreadCount (options.num_threads);
#pragma omp parallel num_threads(threads)
      {
        ResponseScratch scratch;
        scratch.marks.resize (num_vertices);
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t i = 0; i < count; ++i)
        {
          const int v = order[i];
          responses[v] = responseOfVertex (mesh, topology, v, options, adaptive, scratch);
        }
      }
      return responses;
    }

  } // namespace

  bool
  harris3DRanksBefore (const std::vector<double>& responses, int a, int b)
  {
    const double ra = responses[a], rb = responses[b];
    const bool fa = std::isfinite (ra), fb = std::isfinite (rb);
    if (fa != fb)
      return fa;
    if (fa && ra != rb)
      return ra > rb;
    return a < b;
  }

  void
  validateHarris3DOptions (const Harris3DOptions& options)
  {
    auto fail = [] (const std::string& field, double value, const std::string& range) {
      throwOutOfRange ("Harris3DOptions", field, value, range);
    };
    // Outside [0, 1/4] the response det E - k (tr E)^2 is no longer a corner measure (k > 1/4: never positive)
    // and a large k overflows it to -inf.
    if (!(options.k >= 0.0 && options.k <= 0.25))
      fail ("k", options.k, "0 <= k <= 0.25");
    if (options.rings < 0)
      fail ("rings", options.rings, "rings >= 0, 0 = adaptive");
    if (options.rings == 0 && !(options.adaptive_fraction > 0.0 && std::isfinite (options.adaptive_fraction)))
      fail ("adaptive_fraction", options.adaptive_fraction, "adaptive_fraction > 0, finite");
    if (options.max_rings < 1)
      fail ("max_rings", options.max_rings, "max_rings >= 1");
    if (options.min_neighbors < 0)
      fail ("min_neighbors", options.min_neighbors, "min_neighbors >= 0");
    if (!(options.selection_fraction > 0.0 && options.selection_fraction <= 1.0))
      fail ("selection_fraction", options.selection_fraction, "0 < selection_fraction <= 1");
    if (!(options.cluster_fraction >= 0.0 && std::isfinite (options.cluster_fraction)))
      fail ("cluster_fraction", options.cluster_fraction, "cluster_fraction >= 0, finite");
    if (options.num_threads < 0)
      fail ("num_threads", options.num_threads, "num_threads >= 0");
  }

  double
  harris3DResponseOfQuadric (const HeightQuadric& quadric, double k)
  {
    const double p1 = quadric.c[3], p2 = quadric.c[4], p3 = quadric.c[5], p4 = quadric.c[1], p5 = quadric.c[2];
    const double A = p4 * p4 + 2.0 * p1 * p1 + 2.0 * p2 * p2;
    const double B = p5 * p5 + 2.0 * p2 * p2 + 2.0 * p3 * p3;
    const double C = p4 * p5 + 2.0 * p1 * p2 + 2.0 * p2 * p3;
    const double trace = A + B;
    return A * B - C * C - k * trace * trace;
  }

  std::vector<double>
  computeHarris3DResponses (const TriangleMesh& mesh, const MeshTopology& topology, const Harris3DOptions& options)
  {
    return computeResponses (mesh, topology, options, nullptr);
  }

  std::vector<double>
  computeHarris3DResponses (const TriangleMesh& mesh, const MeshTopology& topology, const Harris3DOptions& options,
                            const std::vector<int>& indices)
  {
    return computeResponses (mesh, topology, options, &indices);
  }

  void
  sortByHarris3DRank (const std::vector<double>& responses, std::vector<int>& vertices, int num_threads)
  {
    // harris3DRanksBefore on keys read once, (-response or +inf for none, index), instead of a call and two
    // scattered reads per comparison. A strict total order: the halves sorted on two threads and merged
    // are the same order.
    std::vector<std::pair<double, int>> keyed (vertices.size ());
    for (std::size_t i = 0; i < vertices.size (); ++i)
    {
      const double r = responses[vertices[i]];
      keyed[i] = {std::isfinite (r) ? -r : std::numeric_limits<double>::infinity (), vertices[i]};
    }
    const auto middle = keyed.begin () + static_cast<std::ptrdiff_t> (keyed.size () / 2);
#pragma omp parallel sections num_threads(std::min (2, resolveThreadCount (num_threads))) if(keyed.size () > 65536)
    {
#pragma omp section
      std::sort (keyed.begin (), middle);
#pragma omp section
      std::sort (middle, keyed.end ());
    }
    std::inplace_merge (keyed.begin (), middle, keyed.end ());
    for (std::size_t i = 0; i < vertices.size (); ++i)
      vertices[i] = keyed[i].second;
  }

  std::vector<int>
  orderVerticesByResponse (const std::vector<double>& responses)
  {
    std::vector<int> order (responses.size ());
    for (std::size_t i = 0; i < order.size (); ++i)
      order[i] = static_cast<int> (i);
    sortByHarris3DRank (responses, order);
    return order;
  }

  bool
  isHarris3DLocalMaximum (const MeshTopology& topology, const std::vector<double>& responses, int v)
  {
    if (!std::isfinite (responses[v]))
      return false;
    for (int u : topology.neighborsOf (v))
      if (!harris3DRanksBefore (responses, v, u))
        return false;
    return true;
  }

  std::vector<int>
  selectHarris3DKeypoints (const TriangleMesh& mesh, const MeshTopology& topology, const std::vector<double>& responses,
                           const Harris3DOptions& options, std::size_t num_candidates)
  {
    validateHarris3DOptions (options);
    if (responses.size () != mesh.numVertices () || topology.numVertices () != mesh.numVertices ())
      throw Error ("selectHarris3DKeypoints: responses, topology and mesh disagree on the vertex count");
    std::vector<int> maxima;
    for (int v = 0; v < static_cast<int> (responses.size ()); ++v)
      if (isHarris3DLocalMaximum (topology, responses, v))
        maxima.push_back (v);
    sortByHarris3DRank (responses, maxima, options.num_threads);

    if (options.selection == Harris3DSelection::Fraction)
    {
      const long wanted = std::max (1L, std::lround (options.selection_fraction * static_cast<double> (num_candidates)));
      if (static_cast<long> (maxima.size ()) > wanted)
        maxima.resize (static_cast<std::size_t> (wanted));
      return maxima;
    }

    // Clustering: a uniform grid with cells of the cluster radius; a candidate is dropped if a kept
    // keypoint lies within the radius (only the 27 surrounding cells can hold one).
    const double radius = options.cluster_fraction * boundingBoxDiagonal (mesh);
    if (!(radius > 0.0))
      return maxima;
    // Cells counted from the box's corner in 64 bits, capped at 2^40: a tiny fraction made int cells
    // overflow (undefined behaviour). Cells 2^21 apart share a key, which only adds candidates to check.
    using Cell = Eigen::Matrix<std::int64_t, 3, 1>;
    const Eigen::Vector3d low = finiteBoundingBox (mesh.vertices).min ();
    auto cellOf = [radius, &low] (const Eigen::Vector3d& p) {
      const Eigen::Vector3d c = ((p - low) / radius).array ().floor ().min (0x1p40).max (0.0);
      return Cell (static_cast<std::int64_t> (c.x ()), static_cast<std::int64_t> (c.y ()), static_cast<std::int64_t> (c.z ()));
    };
    auto key = [] (const Cell& c) {
      return (static_cast<std::uint64_t> (c.x () & 0x1fffff) << 42) | (static_cast<std::uint64_t> (c.y () & 0x1fffff) << 21) |
             static_cast<std::uint64_t> (c.z () & 0x1fffff);
    };
    std::unordered_map<std::uint64_t, std::vector<int>> grid;
    std::vector<int> kept;
    const double radius_squared = radius * radius;
    for (int v : maxima)
    {
      const Eigen::Vector3d& p = mesh.vertices[v];
      if (!p.allFinite ())
        continue;
      const Cell c = cellOf (p);
      bool near = false;
      for (int dx = -1; dx <= 1 && !near; ++dx)
        for (int dy = -1; dy <= 1 && !near; ++dy)
          for (int dz = -1; dz <= 1 && !near; ++dz)
          {
            const auto it = grid.find (key (c + Cell (dx, dy, dz)));
            if (it == grid.end ())
              continue;
            for (int u : it->second)
              if ((mesh.vertices[u] - p).squaredNorm () < radius_squared)
              {
                near = true;
                break;
              }
          }
      if (near)
        continue;
      kept.push_back (v);
      grid[key (c)].push_back (v);
    }
    return kept;
  }
} // namespace pcl_sparse
