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
/// mesh. d(a, original) is the exact point-to-triangle distance (the nearest triangle of the original, found
/// in a TriangleTree); d(b, decoded) is the exact point-to-triangle distance for a decoded mesh, and for a
/// model the distance to the nearest patch whose footprint holds b's projection, |z - h(x, y)| r /
/// sqrt(1 + |grad h|^2) (first order), falling back to the nearest resampled point. Prints one JSON line:
/// chamfer = (mean_A d + mean_B d) / 2 / diagonal (diagonal of the original's bounding box), both means,
/// and the largest distance (Hausdorff estimate), all / diagonal.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/model_mesh_distance.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
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
    sampleMeshSurface (original, n, 11, on_original);
    const MeshSurfaceDistance to_original (original);

    std::size_t decoded_points = 0;
    double decoded_to_original = 0, original_to_decoded = 0, largest = 0, decode_seconds = 0;
    if (std::string (argv[1]) == "mesh")
    {
      const TriangleMesh decoded = loadTriangleMesh (argv[3]);
      std::vector<Eigen::Vector3d> on_decoded;
      sampleMeshSurface (decoded, n, 13, on_decoded);
      decoded_points = on_decoded.size ();
      const MeshSurfaceDistance to_decoded (decoded);
      double max_a = 0, max_b = 0;
      meanAndLargestDistance (on_decoded, to_original, decoded_to_original, max_a);
      meanAndLargestDistance (on_original, to_decoded, original_to_decoded, max_b);
      largest = std::max (max_a, max_b);
    }
    else
    {
      const auto start = std::chrono::steady_clock::now ();
      const auto model = std::make_shared<const SparseSurfaceModel> (loadModel (argv[3]));
      const double load_seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      const ChamferDistance chamfer = modelChamferDistance (model, to_original, on_original, n);
      decoded_points = chamfer.model_points;
      decoded_to_original = chamfer.model_to_mesh;
      original_to_decoded = chamfer.mesh_to_model;
      largest = chamfer.largest;
      decode_seconds = load_seconds + chamfer.resample_seconds;
    }
    std::printf ("{\"points\": %zu, \"diagonal\": %.9g, \"chamfer\": %.6e, \"decoded_to_original\": %.6e, "
                 "\"original_to_decoded\": %.6e, \"hausdorff\": %.6e, \"decode_seconds\": %.4f}\n",
                 decoded_points, diag, 0.5 * (decoded_to_original + original_to_decoded) / diag,
                 decoded_to_original / diag, original_to_decoded / diag, largest / diag, decode_seconds);
  }
  catch (const std::exception& e)
  {
    std::fprintf (stderr, "bench_format: %s\n", e.what ());
    return 1;
  }
  return 0;
}
