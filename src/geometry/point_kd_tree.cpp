#include <pcl_sparse/geometry/point_kd_tree.h>

#include <pcl_sparse/common/error.h>

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <flann/util/matrix.h>
#include <flann/util/params.h>
#include <flann/util/result_set.h>

#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// FLANN's result set for one neighbour nearer than a bound: KNNSimpleResultSet's rule for k 1 (the first
    /// point found at the least distance is kept), with the bound as its starting worst distance.
    class NearestWithinResultSet : public flann::ResultSet<float>
    {
    public:
      explicit NearestWithinResultSet (float bound_squared) : worst_ (bound_squared) {}
      bool full () const override { return found_; }
      void
      addPoint (float dist, std::size_t index) override
      {
        if (dist >= worst_)
          return;
        worst_ = dist;
        index_ = index;
        found_ = true;
      }
      float worstDist () const override { return worst_; }
      bool found () const { return found_; }
      std::size_t index () const { return index_; }

    private:
      float worst_;
      std::size_t index_ = 0;
      bool found_ = false;
    };
  } // namespace

  struct PointKdTree::Impl
  {
    using Tree = flann::KDTreeSingleIndex<flann::L2_Simple<float>>;

    std::vector<float> coordinates;  // x y z per point; the tree keeps its own reordered copy
    std::unique_ptr<Tree> tree;
    flann::SearchParams params{-1, 0.0f};  // exact, as pcl::KdTreeFLANN's (epsilon 0)
  };

  PointKdTree::PointKdTree (const pcl::PointCloud<pcl::PointXYZ>& points) : impl_ (std::make_unique<Impl> ()), size_ (points.size ())
  {
    impl_->coordinates.reserve (3 * points.size ());
    for (const pcl::PointXYZ& p : points)
    {
      if (!std::isfinite (p.x) || !std::isfinite (p.y) || !std::isfinite (p.z))
        throw Error ("PointKdTree: a point is not finite");
      impl_->coordinates.insert (impl_->coordinates.end (), {p.x, p.y, p.z});
    }
    if (size_ == 0)
      return;
    // Leaf size 15, as pcl::KdTreeFLANN builds its index: the same tree, so the same ties.
    impl_->tree = std::make_unique<Impl::Tree> (flann::Matrix<float> (impl_->coordinates.data (), size_, 3),
                                                flann::KDTreeSingleIndexParams (15));
    impl_->tree->buildIndex ();
  }

  PointKdTree::~PointKdTree () = default;

  void
  PointKdTree::nearestK (const pcl::PointXYZ& query, int k, std::vector<int>& indices, std::vector<float>& squared) const
  {
    indices.clear ();
    squared.clear ();
    const std::size_t wanted = std::min (size_, static_cast<std::size_t> (std::max (k, 0)));
    if (wanted == 0)
      return;
    // FLANN's own choice for k <= 250 (KNN_HEAP_THRESHOLD), kept sorted as it goes.
    flann::KNNSimpleResultSet<float> found (wanted);
    const float q[3] = {query.x, query.y, query.z};
    impl_->tree->findNeighbors (found, q, impl_->params);
    const std::size_t n = std::min (found.size (), wanted);
    std::vector<std::size_t> numbers (n);
    squared.resize (n);
    if (n > 0)
      found.copy (numbers.data (), squared.data (), n, true);
    indices.assign (numbers.begin (), numbers.end ());
  }

  bool
  PointKdTree::nearestWithin (const pcl::PointXYZ& query, float bound_squared, int& index, float& squared) const
  {
    if (size_ == 0)
      return false;
    NearestWithinResultSet found (bound_squared);
    const float q[3] = {query.x, query.y, query.z};
    impl_->tree->findNeighbors (found, q, impl_->params);
    if (!found.found ())
      return false;
    index = static_cast<int> (found.index ());
    squared = found.worstDist ();
    return true;
  }

  void
  PointKdTree::radius (const pcl::PointXYZ& query, double radius, std::vector<int>& indices, std::vector<float>& squared,
                       bool sorted) const
  {
    indices.clear ();
    squared.clear ();
    if (size_ == 0)
      return;
    flann::RadiusResultSet<float> found (static_cast<float> (radius * radius));
    const float q[3] = {query.x, query.y, query.z};
    impl_->tree->findNeighbors (found, q, impl_->params);
    const std::size_t n = found.size ();
    std::vector<std::size_t> numbers (n);
    squared.resize (n);
    if (n > 0)
      found.copy (numbers.data (), squared.data (), n, sorted);
    indices.assign (numbers.begin (), numbers.end ());
  }
} // namespace pcl_sparse
