/// bench_format: the measurements behind bench/rate_distortion.sh.
///
///   bench_format convert IN OUT                 re-save a mesh (positions and faces only) for draco_encoder
///   bench_format mesh ORIGINAL DECODED [-n N]    symmetric surface distance of a decoded mesh (Draco)
///   bench_format model ORIGINAL MODEL.psm [-n N] same for a .psm model file, plus its load + resample time
///   bench_format requantise IN.psm OUT.psm T [EXTENT_BITS [ANGLES [REFINE_STEPS]]]   re-save a (lossless) model at
///                                               tolerance T (ModelWriteOptions' extent_bits, max_footprint_angles,
///                                               footprint_refine_steps);
///                                               prints the encode seconds
///
/// Distance: A = N points drawn uniformly by area on the decoded surface, B = N points on the original
/// mesh. d(a, original) is the exact point-to-triangle distance (candidate triangles from a dense sampling
/// of the original); d(b, decoded) is the exact point-to-triangle distance for a decoded mesh, and for a
/// model the distance to the nearest patch whose footprint holds b's projection, |z - h(x, y)| r /
/// sqrt(1 + |grad h|^2) (first order), falling back to the nearest resampled point. Prints one JSON line:
/// chamfer = (mean_A d + mean_B d) / 2 / diagonal (diagonal of the original's bounding box), both means,
/// and the largest distance (Hausdorff estimate), all / diagonal.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
  Eigen::Vector3d
  closestOnTriangle (const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
  {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot (ap), d2 = ac.dot (ap);
    if (d1 <= 0 && d2 <= 0)
      return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot (bp), d4 = ac.dot (bp);
    if (d3 >= 0 && d4 <= d3)
      return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
      return a + d1 / (d1 - d3) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot (cp), d6 = ac.dot (cp);
    if (d6 >= 0 && d5 <= d6)
      return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
      return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
      return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
  }

  /// \a n points uniformly by area on \a mesh, with the triangle each lies on.
  void
  sampleMesh (const TriangleMesh& mesh, std::size_t n, unsigned seed, std::vector<Eigen::Vector3d>& points,
              std::vector<int>* triangles = nullptr)
  {
    std::vector<double> cumulative (mesh.triangles.size ());
    double total = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size (); ++t)
    {
      const auto& f = mesh.triangles[t];
      total += 0.5 * (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross (mesh.vertices[f[2]] - mesh.vertices[f[0]]).norm ();
      cumulative[t] = total;
    }
    std::mt19937 rng (seed);
    std::uniform_real_distribution<double> uniform (0.0, 1.0);
    points.resize (n);
    if (triangles)
      triangles->resize (n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const int t = static_cast<int> (std::lower_bound (cumulative.begin (), cumulative.end (), uniform (rng) * total) -
                                      cumulative.begin ());
      const auto& f = mesh.triangles[std::min<std::size_t> (t, mesh.triangles.size () - 1)];
      double u = uniform (rng), v = uniform (rng);
      if (u + v > 1.0)
      {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      points[i] = mesh.vertices[f[0]] + u * (mesh.vertices[f[1]] - mesh.vertices[f[0]]) +
                  v * (mesh.vertices[f[2]] - mesh.vertices[f[0]]);
      if (triangles)
        (*triangles)[i] = t;
    }
  }

  pcl::PointCloud<pcl::PointXYZ>::Ptr
  toCloud (const std::vector<Eigen::Vector3d>& points)
  {
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud (new pcl::PointCloud<pcl::PointXYZ>);
    for (const auto& p : points)
      cloud->push_back (pcl::PointXYZ (static_cast<float> (p.x ()), static_cast<float> (p.y ()), static_cast<float> (p.z ())));
    return cloud;
  }

  /// Exact point-to-mesh distance, candidate triangles from the k nearest of a dense sampling.
  class MeshDistance
  {
  public:
    explicit MeshDistance (const TriangleMesh& mesh) : mesh_ (mesh)
    {
      std::vector<Eigen::Vector3d> points;
      sampleMesh (mesh, 10 * mesh.triangles.size () + 200000, 7, points, &sample_triangle_);
      tree_.setInputCloud (toCloud (points));
    }

    double
    operator() (const Eigen::Vector3d& p) const
    {
      std::vector<int> indices (16);
      std::vector<float> distances (16);
      tree_.nearestKSearch (pcl::PointXYZ (static_cast<float> (p.x ()), static_cast<float> (p.y ()), static_cast<float> (p.z ())),
                            16, indices, distances);
      double best = std::numeric_limits<double>::infinity ();
      for (int i : indices)
      {
        const auto& f = mesh_.triangles[sample_triangle_[i]];
        best = std::min (best, (p - closestOnTriangle (p, mesh_.vertices[f[0]], mesh_.vertices[f[1]], mesh_.vertices[f[2]])).norm ());
      }
      return best;
    }

  private:
    const TriangleMesh& mesh_;
    std::vector<int> sample_triangle_;
    pcl::KdTreeFLANN<pcl::PointXYZ> tree_;
  };

  /// Distance to the surface of a model: nearest patch holding the projection (first order).
  class ModelDistance
  {
  public:
    ModelDistance (const SparseSurfaceModel& model, const std::vector<Eigen::Vector3d>& resampled) : model_ (model)
    {
      std::vector<Eigen::Vector3d> seeds;
      for (const PatchCode& patch : model.patches)
      {
        seeds.push_back (patch.origin);
        double e = 1.0;
        for (float x : patch.footprint.extent)
          e = std::max (e, static_cast<double> (x));
        reach_ = std::max (reach_, 1.5 * patch.radius * e);
      }
      seeds_.setInputCloud (toCloud (seeds));
      points_ = resampled;
      cloud_.setInputCloud (toCloud (resampled));
    }

    double
    operator() (const Eigen::Vector3d& p) const
    {
      std::vector<int> indices;
      std::vector<float> distances;
      const pcl::PointXYZ q (static_cast<float> (p.x ()), static_cast<float> (p.y ()), static_cast<float> (p.z ()));
      seeds_.radiusSearch (q, reach_, indices, distances);
      double best = std::numeric_limits<double>::infinity ();
      for (int i : indices)
      {
        const PatchCode& patch = model_.patches[i];
        const Eigen::Vector3d local = patch.frame.transpose () * (p - patch.origin) / patch.radius;
        if (!patch.footprint.contains (local.x (), local.y ()))
          continue;
        const HeightSample h = model_.evaluate (i, local.x (), local.y ());
        best = std::min (best, std::abs (local.z () - h.value) * patch.radius / std::sqrt (1.0 + h.gradient.squaredNorm ()));
      }
      // A patch across a thin part can contain the projection of p and report the part's thickness, so
      // the nearest resampled point (an upper bound: it lies on the decoded surface) always caps it.
      std::vector<int> nearest (1);
      std::vector<float> squared (1);
      cloud_.nearestKSearch (q, 1, nearest, squared);
      return std::min (best, (p - points_[nearest[0]]).norm ());
    }

  private:
    const SparseSurfaceModel& model_;
    double reach_ = 0.0;
    pcl::KdTreeFLANN<pcl::PointXYZ> seeds_;
    pcl::KdTreeFLANN<pcl::PointXYZ> cloud_;
    std::vector<Eigen::Vector3d> points_;
  };

  double
  diagonal (const TriangleMesh& mesh)
  {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant (std::numeric_limits<double>::infinity ()), hi = -lo;
    for (const auto& f : mesh.triangles)
      for (int k = 0; k < 3; ++k)
      {
        lo = lo.cwiseMin (mesh.vertices[f[k]]);
        hi = hi.cwiseMax (mesh.vertices[f[k]]);
      }
    return (hi - lo).norm ();
  }

  template <typename Distance>
  void
  meanAndMax (const std::vector<Eigen::Vector3d>& points, const Distance& distance, double& mean, double& max)
  {
    std::vector<double> d (points.size ());
#pragma omp parallel for schedule(dynamic, 1024)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (points.size ()); ++i)
      d[i] = distance (points[i]);
    mean = 0.0;
    max = 0.0;
    for (double x : d)
    {
      mean += x;
      max = std::max (max, x);
    }
    mean /= std::max<std::size_t> (d.size (), 1);
  }

  std::size_t
  pointCount (int argc, char** argv)
  {
    for (int i = 1; i + 1 < argc; ++i)
      if (std::string (argv[i]) == "-n")
        return static_cast<std::size_t> (std::stod (argv[i + 1]));
    return 200000;
  }
} // namespace

int
main (int argc, char** argv)
{
  try
  {
    if (argc >= 4 && std::string (argv[1]) == "convert")
    {
      saveTriangleMesh (argv[3], loadTriangleMesh (argv[2]));
      return 0;
    }
    if (argc >= 5 && std::string (argv[1]) == "requantise")
    {
      const SparseSurfaceModel model = loadModel (argv[2]);
      ModelWriteOptions options;
      options.tolerance = std::stod (argv[4]);
      if (argc >= 6)
        options.extent_bits = std::stoi (argv[5]);
      if (argc >= 7)
        options.max_footprint_angles = std::stoi (argv[6]);
      if (argc >= 8)
        options.footprint_refine_steps = std::stod (argv[7]);
      const auto start = std::chrono::steady_clock::now ();
      saveModel (argv[3], model, options);
      std::printf ("%.4f\n", std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ());
      return 0;
    }
    if (argc < 4 || (std::string (argv[1]) != "mesh" && std::string (argv[1]) != "model"))
    {
      std::fprintf (stderr, "usage: %s convert IN OUT | mesh ORIGINAL DECODED [-n N] | model ORIGINAL MODEL.psm [-n N]\n", argv[0]);
      return 1;
    }
    const std::size_t n = pointCount (argc, argv);
    const TriangleMesh original = loadTriangleMesh (argv[2]);
    const double diag = diagonal (original);
    std::vector<Eigen::Vector3d> on_original;
    sampleMesh (original, n, 11, on_original);
    const MeshDistance to_original (original);

    std::vector<Eigen::Vector3d> on_decoded;
    double decoded_to_original = 0, original_to_decoded = 0, max_a = 0, max_b = 0, decode_seconds = 0;
    if (std::string (argv[1]) == "mesh")
    {
      const TriangleMesh decoded = loadTriangleMesh (argv[3]);
      sampleMesh (decoded, n, 13, on_decoded);
      const MeshDistance to_decoded (decoded);
      meanAndMax (on_decoded, to_original, decoded_to_original, max_a);
      meanAndMax (on_original, to_decoded, original_to_decoded, max_b);
    }
    else
    {
      const auto start = std::chrono::steady_clock::now ();
      const auto model = std::make_shared<const SparseSurfaceModel> (loadModel (argv[3]));
      SparseSurfaceResampling<pcl::PointNormal> resampling;
      resampling.setInputModel (model);
      resampling.setPointCount (n);
      pcl::PointCloud<pcl::PointNormal> cloud;
      resampling.compute (cloud);
      decode_seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      for (const auto& p : cloud)
        on_decoded.emplace_back (p.x, p.y, p.z);
      const ModelDistance to_decoded (*model, on_decoded);
      meanAndMax (on_decoded, to_original, decoded_to_original, max_a);
      meanAndMax (on_original, to_decoded, original_to_decoded, max_b);
    }
    std::printf ("{\"points\": %zu, \"diagonal\": %.9g, \"chamfer\": %.6e, \"decoded_to_original\": %.6e, "
                 "\"original_to_decoded\": %.6e, \"hausdorff\": %.6e, \"decode_seconds\": %.4f}\n",
                 on_decoded.size (), diag, 0.5 * (decoded_to_original + original_to_decoded) / diag,
                 decoded_to_original / diag, original_to_decoded / diag, std::max (max_a, max_b) / diag, decode_seconds);
  }
  catch (const std::exception& e)
  {
    std::fprintf (stderr, "bench_format: %s\n", e.what ());
    return 1;
  }
  return 0;
}
