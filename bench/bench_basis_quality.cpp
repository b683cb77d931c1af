/// bench_basis_quality: the surface between the vertices for the paper's cosine dictionary and the
/// half-period (DCT-like) basis: encode (rho 0.001, 64 footprint angles as pcl_sparse_resample), resample
/// 4 N_V points, measure the cloud against the mesh (cloud_quality.h). Markdown rows on stdout.
///
///   bench_basis_quality MESH...
#include "bench_main.h"

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

using namespace pcl_sparse;

static int
run (int argc, char** argv)
{
  std::printf ("| mesh | basis | vertex RMSE/diag | cloud RMS distance/diag | max/diag | normal error mean (deg) | p90 | flipped | completeness | resample s |\n");
  std::printf ("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int a = 1; a < argc; ++a)
  {
    auto mesh = std::make_shared<const TriangleMesh> (loadTriangleMesh (argv[a]));
    for (int kind = 0; kind < 2; ++kind)
    {
      SparseSurfaceEncoderOptions o;
      o.basis = kind ? CosineBasisKind::Dct : CosineBasisKind::Paper;
      o.coding.footprint_angles = 64;
      SparseSurfaceEncoder<pcl::PointXYZ> e;
      e.setInputMesh (mesh);
      e.setOptions (o);
      auto model = std::make_shared<SparseSurfaceModel> ();
      e.compute (*model);
      const ModelStatistics s = model->statistics (mesh->vertices);
      SparseSurfaceResampling<pcl::PointNormal> r;
      r.setInputModel (model);
      r.setPointCount (4 * mesh->vertices.size ());
      SparseSurfaceResampling<pcl::PointNormal>::PointCloud cloud;
      r.setNumberOfThreads (1);
      const auto t0 = std::chrono::steady_clock::now ();
      r.compute (cloud);
      const double sec = std::chrono::duration<double> (std::chrono::steady_clock::now () - t0).count ();
      const CloudQuality q = evaluateCloudQuality (*mesh, cloud);
      std::printf ("| %s | %s | %.2e | %.2e | %.2e | %.2f | %.2f | %zu | %.4f | %.2f |\n",
                   std::filesystem::path (argv[a]).filename ().string ().c_str (), cosineBasisKindName (o.basis), s.rmse_over_diagonal, q.rms_distance / q.bbox_diagonal,
                   q.max_distance / q.bbox_diagonal, q.mean_normal_angle, q.p90_normal_angle, q.flipped, q.completeness, sec);
    }
  }
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
