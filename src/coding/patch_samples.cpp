#include <pcl_sparse/coding/patch_samples.h>
#include <pcl_sparse/common/splitmix64.h>

#include "patch_local_index.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

namespace pcl_sparse
{
  std::uint64_t
  mixSeed (std::uint64_t seed, std::uint64_t index)
  {
    return splitmix64 (splitmix64 (seed) ^ (index * 0xd1b54a32d192ed03ULL + 1));
  }

  namespace
  {
    /// Mean length of the edges from \a v to its 1-ring; 0 for a vertex without edges.
    double
    meanRingEdgeLength (const TriangleMesh& mesh, const MeshTopology& topology, int v)
    {
      const IndexRange ring = topology.neighborsOf (v);
      if (ring.size () == 0)
        return 0.0;
      double sum = 0.0;
      for (int u : ring)
        sum += (mesh.vertices[u] - mesh.vertices[v]).norm ();
      return sum / ring.size ();
    }

    /// Median of the positive \a lengths, in units of \a radius (0 when there is none).
    double
    medianSpacing (std::vector<double>& lengths, double radius)
    {
      if (lengths.empty () || !(radius > 0.0))
        return 0.0;
      const std::size_t half = lengths.size () / 2;
      std::nth_element (lengths.begin (), lengths.begin () + half, lengths.end ());
      double median = lengths[half];
      if (lengths.size () % 2 == 0)
        median = 0.5 * (median + *std::max_element (lengths.begin (), lengths.begin () + half));
      return median / radius;
    }
  } // namespace

  double
  patchSampleSpacing (const Patch& patch, const TriangleMesh& mesh, const MeshTopology& topology)
  {
    std::vector<double> means;
    means.reserve (patch.vertices.size ());
    for (int v : patch.vertices)
    {
      const double mean = meanRingEdgeLength (mesh, topology, v);
      if (mean > 0.0)
        means.push_back (mean);
    }
    return medianSpacing (means, patch.radius);
  }

  std::vector<double>
  meanRingEdgeLengths (const TriangleMesh& mesh, const MeshTopology& topology)
  {
    std::vector<double> lengths (mesh.vertices.size (), 0.0);
    for (std::size_t v = 0; v < lengths.size () && v < topology.numVertices (); ++v)
      lengths[v] = meanRingEdgeLength (mesh, topology, static_cast<int> (v));
    return lengths;
  }

  double
  patchSampleSpacing (const Patch& patch, const std::vector<double>& mean_ring_edge_lengths)
  {
    std::vector<double> means;
    means.reserve (patch.vertices.size ());
    for (int v : patch.vertices)
      if (v >= 0 && static_cast<std::size_t> (v) < mean_ring_edge_lengths.size () && mean_ring_edge_lengths[v] > 0.0)
        means.push_back (mean_ring_edge_lengths[v]);
    return medianSpacing (means, patch.radius);
  }

  std::vector<PatchSurfacePoint>
  drawPatchSurfacePoints (const Patch& patch, const TriangleMesh& mesh, int count, std::uint64_t seed)
  {
    std::vector<PatchSurfacePoint> samples;
    if (count <= 0 || patch.triangles.empty () || patch.local.size () != patch.vertices.size ())
      return samples;

    // Local index of each patch vertex (faces hold mesh vertex ids).
    const PatchLocalIndex local_index (patch.vertices, patch.vertices.size (), mesh.vertices.size ());

    // Corners as local indices and the cumulative area (local units: same ratios as world ones).
    std::vector<Eigen::Vector3i> corners;
    std::vector<double> cumulative;
    corners.reserve (patch.triangles.size ());
    cumulative.reserve (patch.triangles.size ());
    double total = 0.0;
    for (int f : patch.triangles)
    {
      if (f < 0 || static_cast<std::size_t> (f) >= mesh.triangles.size ())
        continue;
      const Eigen::Vector3i& t = mesh.triangles[f];
      const Eigen::Vector3i c (local_index (t[0]), local_index (t[1]), local_index (t[2]));
      if (c.minCoeff () < 0)
        continue;
      const double area =
          0.5 * (patch.local[c[1]] - patch.local[c[0]]).cross (patch.local[c[2]] - patch.local[c[0]]).norm ();
      if (!(area > 0.0))
        continue;
      total += area;
      corners.push_back (c);
      cumulative.push_back (total);
    }
    if (corners.empty ())
      return samples;

    // A splitmix64 stream: explicit seed, same numbers on every platform, and no 2.5 KB state to seed
    // per patch (std::mt19937_64 seeding was the largest cost of this function).
    std::uint64_t state = seed;
    auto uniform = [&state] () { return static_cast<double> (splitmix64 (state++) >> 11) * 0x1.0p-53; };
    samples.reserve (count);
    for (int s = 0; s < count; ++s)
    {
      const double pick = uniform () * total;
      const std::size_t t = std::min<std::size_t> (
          std::upper_bound (cumulative.begin (), cumulative.end (), pick) - cumulative.begin (), corners.size () - 1);
      // Uniform point in a triangle: (1 - sqrt(u), sqrt(u) (1 - v), sqrt(u) v).
      const double su = std::sqrt (uniform ());
      const double v = uniform ();
      samples.push_back ({corners[t], Eigen::Vector3d (1.0 - su, su * (1.0 - v), su * v)});
    }
    return samples;
  }

  std::vector<Eigen::Vector3d>
  drawPatchSurfaceSamples (const Patch& patch, const TriangleMesh& mesh, int count, std::uint64_t seed)
  {
    std::vector<Eigen::Vector3d> samples;
    for (const PatchSurfacePoint& point : drawPatchSurfacePoints (patch, mesh, count, seed))
      samples.push_back (point.interpolate (patch.local));
    return samples;
  }
} // namespace pcl_sparse
