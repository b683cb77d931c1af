/// bench_encode: the paper-style table (N_V, M, rho, nnz, RMSE, RMSE / diag, CR, seconds) of the sparse
/// surface encoder for meshes at several rho, as Markdown on stdout.
///
///   bench_encode [-preset paper|default] [-rho R1,R2,...] [-f F] [-L N] [-min-samples N] [-authors-nyquist]
///                [-basis paper|dct] [-cone DEG] [-threads N] [-repeat K] [-header 0|1] MESH...
/// Options start from the paper's configuration (EncoderPreset::Paper) unless -preset default comes first.
///   bench_encode -evaluate [dct] (throughput of evaluateCode / evaluateCodeValue of the cosine basis, one thread)
///
/// Seconds are the encoder's wall clock (patches + coding; load and statistics excluded), best of K runs;
/// CPU s is the process CPU time of compute() summed over threads (best of K), which other jobs on the
/// machine inflate less than the wall clock.

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <random>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// Evaluations per second of a random 10-atom code at random points (value + gradient + Hessian, and
  /// value only).
  void
  benchEvaluate (CosineBasisKind kind)
  {
    const CosineAtoms::ConstPtr basis = makeCosineBasis (kind, 12);
    const CosineAtoms& dictionary = *basis;
    std::mt19937 rng (1);
    std::uniform_real_distribution<double> u (-1.0, 1.0);
    std::uniform_int_distribution<int> atom (0, 143);
    std::vector<int> atoms;
    std::vector<double> coefficients;
    for (int k = 0; k < 10; ++k)
    {
      atoms.push_back (atom (rng));
      coefficients.push_back (u (rng));
    }
    std::vector<Eigen::Vector2d> points (1 << 20);
    for (Eigen::Vector2d& p : points)
      p = Eigen::Vector2d (u (rng), u (rng));
    for (int mode = 0; mode < 2; ++mode)
    {
      double sink = 0.0;
      const std::clock_t cpu_start = std::clock ();
      const auto start = std::chrono::steady_clock::now ();
      for (int repeat = 0; repeat < 8; ++repeat)
        for (const Eigen::Vector2d& p : points)
          sink += mode == 0 ? dictionary.evaluateCode (atoms, coefficients, p.x (), p.y ()).hessian (0, 1)
                            : dictionary.evaluateCodeValue (atoms, coefficients, p.x (), p.y ());
      const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      const double cpu_seconds = static_cast<double> (std::clock () - cpu_start) / CLOCKS_PER_SEC;
      std::printf ("%s %s: %.1f million evaluations per CPU second, %.1f per wall second (10-atom code, one "
                   "thread; checksum %.3g)\n",
                   cosineBasisKindName (kind), mode == 0 ? "evaluateCode (value, gradient, Hessian)" : "evaluateCodeValue",
                   8.0 * points.size () / cpu_seconds / 1e6, 8.0 * points.size () / seconds / 1e6, sink);
    }
  }
} // namespace

int
main (int argc, char** argv)
{
  if ((argc == 2 || argc == 3) && std::string (argv[1]) == "-evaluate")
  {
    benchEvaluate (argc == 3 && std::string (argv[2]) == "dct" ? CosineBasisKind::Dct : CosineBasisKind::Paper);
    return 0;
  }
  std::vector<double> rhos = {0.005, 0.001, 0.0002};
  int threads = 0, repeat = 1;
  bool header = true;
  SparseSurfaceEncoderOptions base = encoderPresetOptions (EncoderPreset::Paper);
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-preset" && i + 1 < argc)
      base = encoderPresetOptions (encoderPresetFromName (argv[++i]));
    else if (arg == "-rho" && i + 1 < argc)
    {
      rhos.clear ();
      std::stringstream list (argv[++i]);
      std::string item;
      while (std::getline (list, item, ','))
        rhos.push_back (std::atof (item.c_str ()));
    }
    else if (arg == "-threads" && i + 1 < argc)
      threads = std::atoi (argv[++i]);
    else if (arg == "-f" && i + 1 < argc)
      base.coding.nyquist_factor = std::atof (argv[++i]);
    else if (arg == "-L" && i + 1 < argc)
      base.coding.max_atoms = std::atoi (argv[++i]);
    else if (arg == "-min-samples" && i + 1 < argc)
      base.coding.min_samples = std::atoi (argv[++i]);
    else if (arg == "-cone" && i + 1 < argc)
      base.patches.cone_angle = std::atof (argv[++i]) * M_PI / 180.0;  // degrees on the command line
    else if (arg == "-authors-nyquist")
      base.coding.nyquist_rule = NyquistRule::AuthorsCode;
    else if (arg == "-basis" && i + 1 < argc)
      base.basis = std::string (argv[++i]) == "dct" ? CosineBasisKind::Dct : CosineBasisKind::Paper;
    else if (arg == "-header" && i + 1 < argc)
      header = std::atoi (argv[++i]) != 0;
    else if (arg == "-repeat" && i + 1 < argc)
      repeat = std::max (1, std::atoi (argv[++i]));
    else
      meshes.push_back (arg);
  }

  if (header)
  {
    std::printf ("| mesh | N_V | rho | f (rule) | L | m_min | M | nnz | RMSE | RMSE/diag | CR | uncovered | patches s | coding s | total s | CPU s | basis |\n");
    std::printf ("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  }
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
      SparseSurfaceEncoderOptions options = base;
      options.patches.rho = rho;
      SparseSurfaceEncoder<pcl::PointXYZ> encoder;
      encoder.setInputMesh (mesh);
      encoder.setOptions (options);
      encoder.setNumberOfThreads (threads);
      SparseSurfaceModel model;
      EncoderTimings best;
      best.total = 1e300;
      double best_cpu = 1e300;
      try
      {
        for (int r = 0; r < repeat; ++r)
        {
          const std::clock_t cpu_start = std::clock ();
          encoder.compute (model);
          best_cpu = std::min (best_cpu, static_cast<double> (std::clock () - cpu_start) / CLOCKS_PER_SEC);
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
      std::printf ("| %s | %zu | %g | %g (%s) | %d | %d | %zu | %zu | %.3e | %.2e | %.3f | %zu | %.3f | %.3f | %.3f | %.3f | %s |\n",
                   name.c_str (), s.num_vertices, rho, options.coding.nyquist_factor,
                   options.coding.nyquist_rule == NyquistRule::Paper ? "paper" : "authors", options.coding.max_atoms,
                   options.coding.min_samples, s.num_patches, s.num_nonzeros, s.rmse, s.rmse_over_diagonal,
                   s.compression_ratio, s.uncovered, best.patches, best.coding, best.total, best_cpu,
                   cosineBasisKindName (options.basis));
      std::fflush (stdout);
    }
  }
  return 0;
}
