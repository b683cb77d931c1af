#include <pcl_sparse/cloud/knn_neighborhoods.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/common/upper_median.h>
#include <pcl_sparse/geometry/point_kd_tree.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    /// Spacing of a point from its sorted neighbour distances (-1 padded): mean of the first 6.
    double
    spacingFromDistances (const double* distances, int k)
    {
      double sum = 0.0;
      int count = 0;
      for (int m = 0; m < k && count < 6; ++m)
        if (distances[m] >= 0.0)
        {
          sum += distances[m];
          ++count;
        }
      return count > 0 ? sum / count : 0.0;
    }

  } // namespace

  KnnGraph
  findKNearestNeighbors (const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& searched,
                         int k, int num_threads)
  {
    KnnGraph graph;
    graph.k = k;
    const std::size_t n = positions.size ();
    graph.neighbors.assign (n * k, -1);
    graph.distances.assign (n * k, -1.0);

    // The tree works in float on squared distances, which overflow past 1.8e19 and underflow under 1e-19
    // (a grid of spacing 1e20 found no neighbour, one of 1e-30 took every point for a duplicate): it gets
    // the points scaled by a power of two, to an extent in [1, 2). A power of two scales every float
    // exactly, so the tree ranks as it did on the unscaled points wherever those fit; neighbours are ranked
    // and measured on the double positions below. Positions far off the origin (map coordinates given
    // through the API; the loaders centre such scans) are moved to their local frame first: scaling keeps a
    // float's relative precision, and 5e6 m away a float holds 0.5 m, so the tree ranked at random.
    Eigen::AlignedBox3d box;
    for (std::size_t i = 0; i < n; ++i)
      if (searched[i] && positions[i].allFinite ())
        box.extend (positions[i]);
    const Eigen::Vector3d shift = localFrameOriginOfBox (box);  // 0 near the origin
    box.translate (-shift);
    double scale = 1.0;
    if (!box.isEmpty ())
    {
      const double extent = (box.max () - box.min ()).maxCoeff ();
      if (extent > 0.0 && std::isfinite (extent))
        scale = std::ldexp (1.0, -std::ilogb (extent));
    }
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    std::vector<int> original;  // cloud index -> point index
    for (std::size_t i = 0; i < n; ++i)
      if (searched[i])
      {
        const Eigen::Vector3f p = ((positions[i] - shift) * scale).cast<float> ();
        cloud->push_back (pcl::PointXYZ (p.x (), p.y (), p.z ()));
        original.push_back (static_cast<int> (i));
      }
    if (original.size () < 2)
      return graph;
    const PointKdTree tree (*cloud);
    const int wanted = std::min<int> (k + 1, static_cast<int> (original.size ()));

    const int threads = resolveThreadCount (num_threads);
#pragma omp parallel num_threads(threads)
    {
      std::vector<int> found;
      std::vector<float> squared;
      std::vector<std::pair<double, int>> sorted;
#pragma omp for schedule(dynamic, 512)
      for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t> (original.size ()); ++c)
      {
        const int i = original[c];
        tree.nearestK ((*cloud)[c], wanted, found, squared);
        sorted.clear ();
        for (const auto f : found)
        {
          const int j = original[f];
          if (j != i)
            sorted.emplace_back ((positions[j] - positions[i]).norm (), j);
        }
        std::sort (sorted.begin (), sorted.end ());
        const std::size_t m = std::min<std::size_t> (sorted.size (), static_cast<std::size_t> (k));
        for (std::size_t q = 0; q < m; ++q)
        {
          graph.neighbors[static_cast<std::size_t> (i) * k + q] = sorted[q].second;
          graph.distances[static_cast<std::size_t> (i) * k + q] = sorted[q].first;
        }
      }
    }
    return graph;
  }

  PointNeighborhoods
  acceptKnnEdges (const std::vector<Eigen::Vector3d>& positions, const KnnGraph& graph, double gap_factor,
                  const ShadowRule& shadow, KnnEdgeCounts& counts, int num_threads)
  {
    const std::ptrdiff_t n = static_cast<std::ptrdiff_t> (positions.size ());
    const int k = graph.k;
    const int threads = resolveThreadCount (num_threads);
    PointNeighborhoods hoods;
    std::vector<double> raw (n);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i)
      raw[i] = spacingFromDistances (graph.distances.data () + i * k, k);
    // Smoothed: the median over the point and its k nearest, so that a tight cluster of two or three points
    // in a random sampling does not cut its own edges.
    hoods.spacing.resize (n);
#pragma omp parallel num_threads(threads)
    {
      std::vector<double> values;
#pragma omp for schedule(static)
      for (std::ptrdiff_t i = 0; i < n; ++i)
      {
        values.assign (1, raw[i]);
        for (int m = 0; m < k; ++m)
          if (graph.neighbors[i * k + m] >= 0)
            values.push_back (raw[graph.neighbors[i * k + m]]);
        hoods.spacing[i] = upperMedian (values);
      }
    }
    // Accepted neighbours per point in place (k slots), then compacted in point order.
    const std::unique_ptr<int[]> kept =
      uninitialisedNeighborSlots (static_cast<std::size_t> (n), static_cast<std::size_t> (k));
    std::vector<int> count (n, 0);
    std::size_t candidates = 0, refused = 0, shadowed = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024) reduction(+ : candidates, refused, shadowed)
    for (std::ptrdiff_t i = 0; i < n; ++i)
      for (int m = 0; m < k; ++m)
      {
        const int j = graph.neighbors[i * k + m];
        if (j < 0)
          break;
        const double limit = gap_factor * std::min (hoods.spacing[i], hoods.spacing[j]);
        const bool gap_ok = graph.distances[i * k + m] <= limit;
        const bool shadow_ok = !shadow.shadowed (i, positions[i], positions[j]);
        ++candidates;
        refused += (gap_ok && shadow_ok) ? 0 : 1;
        shadowed += (gap_ok && !shadow_ok) ? 1 : 0;
        if (gap_ok && shadow_ok)
          kept[i * k + count[i]++] = j;
      }
    counts.candidates = candidates;
    counts.refused = refused;
    counts.shadowed = shadowed;
    packNeighborSlots (kept.get (), static_cast<std::size_t> (k), count, hoods, threads);
    return hoods;
  }
} // namespace pcl_sparse
