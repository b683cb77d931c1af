#include <pcl_sparse/geometry/triangle_tree.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/geometry/measurable_triangles.h>
#include <pcl_sparse/geometry/point_triangle_distance.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

namespace pcl_sparse
{
  namespace
  {
    constexpr int kLeafSize = 4;
    /// Halves with more triangles are built as tasks of their own.
    constexpr int kTaskTriangles = 20000;

    /// Squared distance from \a p to the box [lo, hi] (0 inside).
    double
    boxSquaredDistance (const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
    {
      return (lo - p).cwiseMax (p - hi).cwiseMax (0.0).squaredNorm ();
    }
  } // namespace

  TriangleTree::TriangleTree (const TriangleMesh& mesh, int num_threads)
  {
    // Every corner in range, finite and small enough to measure, before anything is copied.
    requireMeasurableTriangles (mesh, "TriangleTree", num_threads);
    const std::size_t count = mesh.triangles.size ();
    if (count > static_cast<std::size_t> (std::numeric_limits<int>::max () / 2))
      throw Error ("TriangleTree: too many triangles");
    const int threads = resolveThreadCount (num_threads);
    corners_.resize (count);
    std::vector<Eigen::Vector3d> centroids (count);
    // In parallel: the copy and the tree's build are serial passes of 0.05-0.17 s over 400k triangles otherwise.
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t f = 0; f < static_cast<std::ptrdiff_t> (count); ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      for (int c = 0; c < 3; ++c)
        corners_[f][c] = mesh.vertices[t[c]];
      centroids[f] = (corners_[f][0] + corners_[f][1] + corners_[f][2]) / 3.0;
    }
    std::vector<int> order (count);
    std::iota (order.begin (), order.end (), 0);
    // The nodes laid out as a depth-first build allocates them (both children next to each other, a left
    // subtree's nodes before its right sibling's children): the same tree whatever the threads.
    std::map<int, int> below;
    nodesBelow (static_cast<int> (count), below);
    nodes_.resize (1 + static_cast<std::size_t> (below.at (static_cast<int> (count))));
#pragma omp parallel num_threads(threads)
#pragma omp single
    build (0, 0, static_cast<int> (count), 1, centroids, below, order);
    // The triangles in leaf order, so that a leaf reads consecutive corners.
    std::vector<std::array<Eigen::Vector3d, 3>> ordered (count);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (count); ++i)
      ordered[i] = corners_[order[i]];
    corners_ = std::move (ordered);
    triangle_ = std::move (order);
  }

  int
  TriangleTree::nodesBelow (int triangles, std::map<int, int>& below)
  {
    const auto known = below.find (triangles);
    if (known != below.end ())
      return known->second;
    const int half = triangles / 2;
    const int n = triangles <= kLeafSize ? 0 : 2 + nodesBelow (half, below) + nodesBelow (triangles - half, below);
    below[triangles] = n;
    return n;
  }

  void
  TriangleTree::build (int node, int begin, int end, int first_free, const std::vector<Eigen::Vector3d>& centroids,
                       const std::map<int, int>& below, std::vector<int>& order)
  {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant (std::numeric_limits<double>::infinity ());
    Eigen::Vector3d hi = -lo, centre_lo = lo, centre_hi = hi;
    for (int i = begin; i < end; ++i)
    {
      for (const Eigen::Vector3d& corner : corners_[order[i]])
      {
        lo = lo.cwiseMin (corner);
        hi = hi.cwiseMax (corner);
      }
      centre_lo = centre_lo.cwiseMin (centroids[order[i]]);
      centre_hi = centre_hi.cwiseMax (centroids[order[i]]);
    }
    nodes_[node].lo = lo;
    nodes_[node].hi = hi;
    if (end - begin <= kLeafSize)
    {
      nodes_[node].first = begin;
      nodes_[node].count = end - begin;
      return;
    }
    // Halves by the median centroid along the longest side (ties by triangle index: the same tree every time).
    int axis = 0;
    (centre_hi - centre_lo).maxCoeff (&axis);
    const int middle = begin + (end - begin) / 2;
    std::nth_element (order.begin () + begin, order.begin () + middle, order.begin () + end, [&] (int a, int b) {
      return centroids[a][axis] < centroids[b][axis] || (centroids[a][axis] == centroids[b][axis] && a < b);
    });
    const int first = first_free;  // both children next to each other
    nodes_[node].first = first;
    const int left_free = first + 2, right_free = left_free + below.at (middle - begin);
    // The halves touch disjoint parts of order and of nodes_: large ones are built as tasks (on the threads of
    // the constructor's parallel region; undeferred, so in turn, on one thread).
#pragma omp task default(shared) if (end - begin > kTaskTriangles)
    build (first, begin, middle, left_free, centroids, below, order);
    build (first + 1, middle, end, right_free, centroids, below, order);
#pragma omp taskwait
  }

  void
  TriangleTree::pushChildren (const Node& node, const Eigen::Vector3d& p, std::array<std::pair<int, double>, 64>& stack,
                              int& size) const
  {
    const double a = boxSquaredDistance (p, nodes_[node.first].lo, nodes_[node.first].hi);
    const double b = boxSquaredDistance (p, nodes_[node.first + 1].lo, nodes_[node.first + 1].hi);
    if (a <= b)
    {
      stack[size++] = {node.first + 1, b};
      stack[size++] = {node.first, a};
    }
    else
    {
      stack[size++] = {node.first, a};
      stack[size++] = {node.first + 1, b};
    }
  }

  TriangleTree::Nearest
  TriangleTree::nearest (const Eigen::Vector3d& p) const
  {
    Nearest best;
    best.distance = std::numeric_limits<double>::infinity ();
    double best_squared = best.distance;
    // Nodes still to visit and their squared box distances; the tree is at most 31 levels deep (median
    // splits of fewer than 2^31 triangles) and a level pushes at most 2.
    std::array<std::pair<int, double>, 64> stack;
    int size = 0;
    stack[size++] = {0, boxSquaredDistance (p, nodes_[0].lo, nodes_[0].hi)};
    while (size > 0)
    {
      const auto [index, squared] = stack[--size];
      if (squared >= best_squared)
        continue;
      const Node& node = nodes_[index];
      if (node.count > 0)
      {
        for (int i = node.first; i < node.first + node.count; ++i)
        {
          const double d = pointTriangleDistance (p, corners_[i][0], corners_[i][1], corners_[i][2]);
          if (d < best.distance)
          {
            best.distance = d;
            best.triangle = triangle_[i];
            best_squared = d * d;
          }
        }
        continue;
      }
      pushChildren (node, p, stack, size);
    }
    return best;
  }

  TriangleTree::Nearest
  TriangleTree::nearestAndTied (const Eigen::Vector3d& p, double margin, std::vector<Nearest>& tied) const
  {
    tied.clear ();
    Nearest best;
    best.distance = std::numeric_limits<double>::infinity ();
    double reach = best.distance;  // best + margin: every triangle as near is kept, every box as near searched
    // As nearest: nearest box first, at most 31 levels pushing at most 2 each.
    std::array<std::pair<int, double>, 64> stack;
    int size = 0;
    stack[size++] = {0, boxSquaredDistance (p, nodes_[0].lo, nodes_[0].hi)};
    while (size > 0)
    {
      const auto [index, squared] = stack[--size];
      if (squared > reach * reach)
        continue;
      const Node& node = nodes_[index];
      if (node.count > 0)
      {
        for (int i = node.first; i < node.first + node.count; ++i)
        {
          const double d = pointTriangleDistance (p, corners_[i][0], corners_[i][1], corners_[i][2]);
          if (!(d <= reach))
            continue;
          tied.push_back ({d, triangle_[i]});
          if (d < best.distance)
          {
            best.distance = d;
            best.triangle = triangle_[i];
            reach = d + margin;
          }
        }
        continue;
      }
      pushChildren (node, p, stack, size);
    }
    // Kept while the nearest was farther: only those within the final reach stay (within's test, d <= radius).
    tied.erase (std::remove_if (tied.begin (), tied.end (), [&] (const Nearest& t) { return !(t.distance <= reach); }),
                tied.end ());
    return best;
  }

  void
  TriangleTree::within (const Eigen::Vector3d& p, double radius, std::vector<Nearest>& found) const
  {
    found.clear ();
    const double radius_squared = radius * radius;
    if (!(radius >= 0.0) || boxSquaredDistance (p, nodes_[0].lo, nodes_[0].hi) > radius_squared)
      return;
    // As in nearest: at most 31 levels, each pushing at most 2.
    std::array<int, 64> stack;
    int size = 0;
    stack[size++] = 0;
    while (size > 0)
    {
      const Node& node = nodes_[stack[--size]];
      if (node.count > 0)
      {
        for (int i = node.first; i < node.first + node.count; ++i)
        {
          const double d = pointTriangleDistance (p, corners_[i][0], corners_[i][1], corners_[i][2]);
          if (d <= radius)
            found.push_back ({d, triangle_[i]});
        }
        continue;
      }
      for (int child = node.first; child < node.first + 2; ++child)
        if (boxSquaredDistance (p, nodes_[child].lo, nodes_[child].hi) <= radius_squared)
          stack[size++] = child;
    }
  }
} // namespace pcl_sparse
