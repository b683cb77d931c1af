/// bench_encode: the paper-style table (N_V, M, rho, nnz, RMSE, RMSE / diag, CR, seconds) of the sparse
/// surface encoder for meshes at several rho, as Markdown on stdout.
///
///   bench_encode [-rho R1,R2,...] [-threads N] [-repeat K] MESH...
///
/// Seconds are the encoder's wall clock (patches + coding; load and statistics excluded), best of K runs.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl_sparse;

int
main (int argc, char** argv)
{
  std::vector<double> rhos = {0.005, 0.001, 0.0002};
  int threads = 0, repeat = 1;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-rho" && i + 1 < argc)
    {
      rhos.clear ();
      std::stringstream list (argv[++i]);
      std::string item;
      while (std::getline (list, item, ','))
        rhos.push_back (std::atof (item.c_str ()));
    }
    else if (arg == "-threads" && i + 1 < argc)
      threads = std::atoi (argv[++i]);
    else if (arg == "-repeat" && i + 1 < argc)
      repeat = std::max (1, std::atoi (argv[++i]));
    else
      meshes.push_back (arg);
  }

  std::printf ("| mesh | N_V | rho | M | nnz | RMSE | RMSE/diag | CR | uncovered | patches s | coding s | total s |\n");
  std::printf ("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& path : meshes)
  {
    TriangleMesh::ConstPtr mesh;
    try
    {
      mesh = std::make_shared<const TriangleMesh> (loadTriangleMesh (path));
    }
    catch (const Error& e)
    {
      std::fprintf (stderr, "bench_encode: %s\n", e.what ());
      continue;
    }
    const std::string name = std::filesystem::path (path).filename ().string ();
    for (double rho : rhos)
    {
      SparseSurfaceEncoderOptions options;
      options.patches.rho = rho;
      SparseSurfaceEncoder encoder;
      encoder.setInputMesh (mesh);
      encoder.setOptions (options);
      encoder.setNumberOfThreads (threads);
      SparseSurfaceModel model;
      EncoderTimings best;
      best.total = 1e300;
      try
      {
        for (int r = 0; r < repeat; ++r)
        {
          encoder.compute (model);
          if (encoder.getTimings ().total < best.total)
            best = encoder.getTimings ();
        }
      }
      catch (const Error& e)
      {
        std::fprintf (stderr, "bench_encode: %s at rho %g: %s\n", name.c_str (), rho, e.what ());
        continue;
      }
      const ModelStatistics s = model.statistics (mesh->vertices);
      std::printf ("| %s | %zu | %g | %zu | %zu | %.3e | %.2e | %.3f | %zu | %.3f | %.3f | %.3f |\n", name.c_str (),
                   s.num_vertices, rho, s.num_patches, s.num_nonzeros, s.rmse, s.rmse_over_diagonal,
                   s.compression_ratio, s.uncovered, best.patches, best.coding, best.total);
      std::fflush (stdout);
    }
  }
  return 0;
}
