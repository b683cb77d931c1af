/// bench_unreferenced: what a scan's points in no triangle cost and give when each gets a patch of its own
/// (PatchOptions::unreferenced_patch_spacings). For each scan and setting: the model's patches and default
/// file bytes (derivedWriteOptions, as pcl_sparse_encode -o writes), its statistics, and the clouds resampled
/// at 1x and 4x the kept points: completeness (input points with an output point within 3 of their local
/// spacings, the mean distance to their 6 nearest input points), as bench/results/scans.md measures it.
///
///   bench_unreferenced SPACINGS SCAN...   one Markdown row per scan (SPACINGS: the option's value)

#include "bench_main.h"
#include "cloud_measures.h"

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/file_tolerance.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/kdtree/kdtree_flann.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
  using namespace pcl_sparse;

  pcl::PointCloud<pcl::PointXYZ>::Ptr
  toCloud (const std::vector<Eigen::Vector3d>& points)
  {
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud (new pcl::PointCloud<pcl::PointXYZ>);
    for (const Eigen::Vector3d& p : points)
      cloud->push_back (pcl::PointXYZ (static_cast<float> (p.x ()), static_cast<float> (p.y ()), static_cast<float> (p.z ())));
    return cloud;
  }

  /// Completeness (cloud_measures.h) of \a model resampled to \a count points.
  double
  completenessAt (const SparseSurfaceModel::ConstPtr& model, std::size_t count, const pcl::PointCloud<pcl::PointXYZ>& input,
                  const std::vector<float>& spacing)
  {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (count);
    pcl::PointCloud<pcl::PointNormal> out;
    resampling.compute (out);
    pcl::PointCloud<pcl::PointXYZ>::Ptr points (new pcl::PointCloud<pcl::PointXYZ>);
    for (const pcl::PointNormal& p : out)
      points->push_back (pcl::PointXYZ (p.x, p.y, p.z));
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud (points);
    return pcl_sparse_bench::completeness (input, spacing, tree);
  }

  int
  run (int argc, char** argv)
  {
    if (argc < 3)
    {
      std::fprintf (stderr, "usage: %s SPACINGS SCAN...\n", argv[0]);
      return 1;
    }
    SparseSurfaceEncoderOptions options;
    options.patches.unreferenced_patch_spacings = std::stod (argv[1]);
    for (int a = 2; a < argc; ++a)
    {
      auto scan = std::make_shared<ScanCloud> ();
      loadScanCloud (argv[a], *scan);
      const auto start = std::chrono::steady_clock::now ();
      SparseSurfaceEncoder<pcl::PointXYZ> encoder;
      encoder.setInputScan (scan);
      encoder.setOptions (options);
      auto model = std::make_shared<SparseSurfaceModel> ();
      encoder.compute (*model);
      const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      std::vector<Eigen::Vector3d> positions;
      for (std::size_t i = 0; i < scan->size (); ++i)
        positions.push_back (scan->worldPosition (i));
      std::vector<double> errors;
      const ModelStatistics stats = model->statistics (positions, &errors);
      const std::size_t bytes = encodeModel (*model, derivedWriteOptions (stats, errors, model->bbox_diagonal)).size ();
      std::size_t unreferenced = 0;
      for (const Patch& patch : encoder.getPatches ())
        unreferenced += patch.triangles.empty () ? 1 : 0;
      const pcl::PointCloud<pcl::PointXYZ>::Ptr input = toCloud (positions);
      pcl::KdTreeFLANN<pcl::PointXYZ> input_tree;
      input_tree.setInputCloud (input);
      const std::vector<float> spacing = pcl_sparse_bench::localSpacings (*input, input_tree);
      const std::string name = std::string (argv[a]).substr (std::string (argv[a]).find_last_of ('/') + 1);
      std::printf ("| %s | %g | %zu | %zu | %zu | %zu | %zu | %.4e | %.4f | %.4f | %.2f |\n", name.c_str (),
                   options.patches.unreferenced_patch_spacings, scan->size (), stats.num_patches, unreferenced,
                   stats.uncovered, bytes, stats.rmse, completenessAt (model, scan->size (), *input, spacing),
                   completenessAt (model, 4 * scan->size (), *input, spacing), seconds);
      std::fflush (stdout);
    }
    return 0;
  }
} // namespace

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
