#include <pcl_sparse/cloud/sensor_evidence.h>

#include <pcl_sparse/geometry/point_kd_tree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_sparse
{
  namespace
  {
    constexpr std::size_t kMaxSample = 4096;
    constexpr double kMinRangeRatio = 2.0;
    constexpr double kMinCorrelation = 0.3;

    /// Ranks of \a values (0 .. n-1; ties broken by position, which a stride sample makes rare).
    std::vector<double>
    ranks (const std::vector<double>& values)
    {
      std::vector<std::size_t> order (values.size ());
      std::iota (order.begin (), order.end (), std::size_t (0));
      std::stable_sort (order.begin (), order.end (), [&] (std::size_t a, std::size_t b) { return values[a] < values[b]; });
      std::vector<double> rank (values.size ());
      for (std::size_t k = 0; k < order.size (); ++k)
        rank[order[k]] = static_cast<double> (k);
      return rank;
    }

    double
    rankCorrelation (const std::vector<double>& a, const std::vector<double>& b)
    {
      const std::vector<double> ra = ranks (a), rb = ranks (b);
      const double mean = 0.5 * static_cast<double> (a.size () - 1);
      double covariance = 0.0, variance = 0.0;
      for (std::size_t i = 0; i < a.size (); ++i)
      {
        covariance += (ra[i] - mean) * (rb[i] - mean);
        variance += (ra[i] - mean) * (ra[i] - mean);
      }
      return variance > 0.0 ? covariance / variance : 0.0;
    }
  } // namespace

  SensorSpacingEvidence
  sensorSpacingEvidence (const std::vector<Eigen::Vector3d>& points, const std::vector<std::uint8_t>& finite,
                         const Eigen::Vector3d& place)
  {
    SensorSpacingEvidence evidence;
    std::vector<std::size_t> usable;
    for (std::size_t i = 0; i < points.size () && i < finite.size (); ++i)
      if (finite[i])
        usable.push_back (i);
    const std::size_t stride = std::max<std::size_t> (1, (usable.size () + kMaxSample - 1) / kMaxSample);
    pcl::PointCloud<pcl::PointXYZ> sample;
    std::vector<double> distance;
    for (std::size_t k = 0; k < usable.size (); k += stride)
    {
      const Eigen::Vector3d& p = points[usable[k]];
      sample.push_back (pcl::PointXYZ (static_cast<float> (p.x ()), static_cast<float> (p.y ()), static_cast<float> (p.z ())));
      distance.push_back ((p - place).norm ());
    }
    if (sample.size () < 16)
      return evidence;  // too few to tell
    const PointKdTree tree (sample);
    std::vector<double> range, spacing;
    std::vector<int> nearest;
    std::vector<float> squared;
    for (std::size_t i = 0; i < sample.size (); ++i)
    {
      tree.nearestK (sample[i], 2, nearest, squared);
      // The nearest other point: a duplicate (0) says nothing about the spacing.
      if (nearest.size () == 2 && squared[1] > 0.0f)
      {
        range.push_back (distance[i]);
        spacing.push_back (std::sqrt (static_cast<double> (squared[1])));
      }
    }
    evidence.sampled = range.size ();
    if (range.size () < 16)
      return evidence;
    std::vector<double> sorted = range;
    std::sort (sorted.begin (), sorted.end ());
    const double low = sorted[sorted.size () / 20], high = sorted[sorted.size () - 1 - sorted.size () / 20];
    evidence.range_ratio = low > 0.0 ? high / low : std::numeric_limits<double>::infinity ();
    evidence.correlation = rankCorrelation (range, spacing);
    evidence.consistent = !(evidence.range_ratio >= kMinRangeRatio && evidence.correlation < kMinCorrelation);
    return evidence;
  }

  bool
  defaultPoseIsUnsupported (const ScanCloud& scan, const std::vector<std::uint8_t>& finite)
  {
    const bool default_pose =
      scan.sensor_origin.isZero (0.0) && scan.sensor_orientation.coeffs () == Eigen::Quaterniond::Identity ().coeffs ();
    if (!scan.has_sensor_pose || scan.sensor_pose_checked || !default_pose || scan.isOrganized ())
      return false;
    return !sensorSpacingEvidence (scan.positions, finite, scan.sensor_origin - scan.origin).consistent;
  }
} // namespace pcl_sparse
