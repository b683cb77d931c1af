/// bench_patch_cost: where the values of the compression ratio go (issue 13 point 2). For each mesh and rho,
/// the CR split into frames (13 M) and coefficients (nnz), the patches' vertex counts, atoms, the vertices
/// each patch alone covers and how many patches cover a vertex, as Markdown on stdout.
///
///   bench_patch_cost [-rho R1,R2,...] [-preset default|paper] [-bound CR] [-floor N] [-sigma S] [-L N]
///                    [-threads N] MESH...
///
/// -bound sets SparseSurfaceEncoderOptions::max_compression_ratio (0: none; default: the preset's), -floor
/// PatchOptions::min_growth_vertices, -sigma the overlap control, -L the atoms per patch. Columns: "patches
/// per vertex" counts the patches holding a vertex; "vertex share" is a patch's sum over its vertices of
/// 1 / that count (what its 13 + atoms values stand for: a patch costs more than its share when
/// 13 + atoms > 3 share); "covering no vertex alone" are patches every vertex of which another patch holds.

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

namespace
{
  double
  percentile (std::vector<double> values, double q)
  {
    if (values.empty ())
      return 0.0;
    std::sort (values.begin (), values.end ());
    return values[static_cast<std::size_t> (q * (values.size () - 1) + 0.5)];
  }

  void
  report (const std::string& name, double rho, const TriangleMesh& mesh, const SparseSurfaceModel& model, int max_atoms)
  {
    const std::size_t nv = mesh.vertices.size ();
    std::vector<int> multiplicity (nv, 0);
    for (const PatchCode& p : model.patches)
      for (int v : p.vertices)
        ++multiplicity[v];
    std::vector<double> sizes, atoms, unique, share;
    std::size_t full_atoms = 0, redundant = 0, small = 0, over_budget = 0;
    for (std::size_t i = 0; i < model.patches.size (); ++i)
    {
      const PatchCode& p = model.patches[i];
      sizes.push_back (static_cast<double> (p.vertices.size ()));
      atoms.push_back (static_cast<double> (p.atoms.size ()));
      full_atoms += static_cast<int> (p.atoms.size ()) >= max_atoms;
      int alone = 0;
      double s = 0.0;
      for (int v : p.vertices)
      {
        alone += multiplicity[v] == 1;
        s += 1.0 / multiplicity[v];
      }
      unique.push_back (alone);
      share.push_back (s);
      redundant += alone == 0;
      small += p.vertices.size () < 7;
      over_budget += 13.0 + p.atoms.size () > 3.0 * s;
    }
    std::vector<double> mult (multiplicity.begin (), multiplicity.end ());
    const ModelStatistics st = model.statistics (mesh.vertices);
    const double denominator = 3.0 * nv;
    std::printf ("| %s | %zu | %g | %zu | %zu | %.3f | %.3f | %.3f | %.2e | %.0f/%.0f/%.0f | %.1f (%.0f%% at L) | %.2f | %.1f/%.1f | %zu | %zu | %zu |\n",
                 name.c_str (), nv, rho, st.num_patches, st.num_nonzeros, st.compression_ratio,
                 13.0 * st.num_patches / denominator, st.num_nonzeros / denominator, st.rmse_over_diagonal,
                 percentile (sizes, 0.1), percentile (sizes, 0.5), percentile (sizes, 0.9),
                 st.num_nonzeros / std::max<double> (1.0, st.num_patches), 100.0 * full_atoms / std::max<std::size_t> (1, st.num_patches),
                 percentile (mult, 0.5), percentile (share, 0.5), static_cast<double> (nv) / std::max<std::size_t> (1, st.num_patches),
                 redundant, small, over_budget);
    std::fflush (stdout);
  }
} // namespace

int
main (int argc, char** argv)
{
  std::vector<double> rhos = {0.001};
  int threads = 0;
  int floor_vertices = -1, max_atoms = -1;
  double sigma = -1.0, bound = -1.0;
  EncoderPreset preset = EncoderPreset::Default;
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
    else if (arg == "-floor" && i + 1 < argc)
      floor_vertices = std::atoi (argv[++i]);
    else if (arg == "-bound" && i + 1 < argc)
      bound = std::atof (argv[++i]);
    else if (arg == "-sigma" && i + 1 < argc)
      sigma = std::atof (argv[++i]);
    else if (arg == "-L" && i + 1 < argc)
      max_atoms = std::atoi (argv[++i]);
    else if (arg == "-threads" && i + 1 < argc)
      threads = std::atoi (argv[++i]);
    else if (arg == "-preset" && i + 1 < argc)
      preset = encoderPresetFromName (argv[++i]);
    else
      meshes.push_back (arg);
  }
  std::printf ("| mesh | N_V | rho | M | nnz | CR | 13M/3N_V | nnz/3N_V | RMSE/diag | patch vertices p10/p50/p90 | atoms per patch | "
               "patches per vertex p50 | vertex share p50 / N_V/M | patches covering no vertex alone | patches < 7 vertices | "
               "patches costing more than their share |\n");
  std::printf ("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|---|---:|---:|---:|\n");
  for (const std::string& path : meshes)
  {
    TriangleMesh::ConstPtr mesh;
    try
    {
      mesh = std::make_shared<const TriangleMesh> (loadTriangleMesh (path));
    }
    catch (const Error& e)
    {
      std::fprintf (stderr, "bench_patch_cost: %s\n", e.what ());
      continue;
    }
    const std::string name = std::filesystem::path (path).stem ().string ();
    for (double rho : rhos)
    {
      SparseSurfaceEncoderOptions options = encoderPresetOptions (preset);
      options.patches.rho = rho;
      if (floor_vertices >= 0)
        options.patches.min_growth_vertices = floor_vertices;
      if (max_atoms > 0)
        options.coding.max_atoms = max_atoms;
      if (sigma >= 0.0)
        options.patches.sigma = sigma;
      if (bound >= 0.0)
        options.max_compression_ratio = bound;
      SparseSurfaceEncoder<pcl::PointXYZ> encoder;
      encoder.setInputMesh (mesh);
      encoder.setOptions (options);
      encoder.setNumberOfThreads (threads);
      SparseSurfaceModel model;
      encoder.compute (model);
      report (name, rho, *mesh, model, options.coding.max_atoms);
    }
  }
  return 0;
}
