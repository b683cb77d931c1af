// Load time of real meshes: our loaders against PCL's (pcl::io::loadPLYFile / loadOBJFile and the VTK-based
// pcl::io::loadPolygonFile), several repetitions, median, in one run. Also prints the vertex/face counts
// each loader returns, since a fast loader that gets the counts wrong is no use to us.
//
// usage: bench_load [--reps N] [--output results.md] mesh [mesh ...]

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/io/obj_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/io/vtk_lib_io.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace
{
  struct Result
  {
    std::string loader;
    double median_ms = 0.0;
    std::size_t vertices = 0, faces = 0;
    bool failed = false;
  };

  /// Runs \a load \a reps times (after one warm-up run that also fills the page cache) and returns the median.
  Result
  measure (const std::string& loader, int reps, const std::function<bool (std::size_t&, std::size_t&)>& load)
  {
    Result result;
    result.loader = loader;
    std::vector<double> times;
    result.failed = !load (result.vertices, result.faces);
    for (int r = 0; r < reps && !result.failed; ++r)
    {
      const auto start = std::chrono::steady_clock::now ();
      load (result.vertices, result.faces);
      times.push_back (std::chrono::duration<double, std::milli> (std::chrono::steady_clock::now () - start).count ());
    }
    if (!times.empty ())
    {
      std::sort (times.begin (), times.end ());
      result.median_ms = times[times.size () / 2];
    }
    return result;
  }

  std::string
  baseName (const std::string& path)
  {
    const std::size_t slash = path.find_last_of ('/');
    return slash == std::string::npos ? path : path.substr (slash + 1);
  }

  bool
  endsWith (const std::string& text, const std::string& suffix)
  {
    return text.size () >= suffix.size () && text.compare (text.size () - suffix.size (), suffix.size (), suffix) == 0;
  }
} // namespace

int
main (int argc, char** argv)
{
  int reps = 7;
  std::string output;
  pcl::console::parse_argument (argc, argv, "--reps", reps);
  pcl::console::parse_argument (argc, argv, "--output", output);
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--reps" || arg == "--output")
      ++i;
    else
      files.push_back (arg);
  }
  if (files.empty () || reps < 1)
  {
    std::fprintf (stderr, "usage: %s [--reps N] [--output results.md] mesh [mesh ...]\n", argv[0]);
    return 1;
  }
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);  // PCL's readers print warnings per file

  std::string table = "| file | loader | vertices | faces | median ms | time / ours |\n|---|---|---|---|---|---|\n";
  for (const std::string& file : files)
  {
    std::vector<Result> results;
    try
    {
      results.push_back (measure ("pcl_sparse::loadTriangleMesh", reps, [&] (std::size_t& v, std::size_t& f) {
        const pcl_sparse::TriangleMesh mesh = pcl_sparse::loadTriangleMesh (file);
        v = mesh.numVertices ();
        f = mesh.numTriangles ();
        return true;
      }));
      results.push_back (measure ("pcl_sparse::loadPolygonMesh", reps, [&] (std::size_t& v, std::size_t& f) {
        pcl::PolygonMesh mesh;
        pcl_sparse::loadPolygonMesh (file, mesh);
        v = mesh.cloud.width * mesh.cloud.height;
        f = mesh.polygons.size ();
        return true;
      }));
    }
    catch (const pcl_sparse::Error& e)
    {
      std::fprintf (stderr, "%s\n", e.what ());
      return 1;
    }
    const bool ply = endsWith (file, ".ply") || endsWith (file, ".PLY");
    const bool obj = endsWith (file, ".obj") || endsWith (file, ".OBJ");
    if (ply || obj)
      results.push_back (measure (ply ? "pcl::io::loadPLYFile" : "pcl::io::loadOBJFile", reps,
                                  [&] (std::size_t& v, std::size_t& f) {
                                    pcl::PolygonMesh mesh;
                                    const int status = ply ? pcl::io::loadPLYFile (file, mesh) : pcl::io::loadOBJFile (file, mesh);
                                    v = mesh.cloud.width * mesh.cloud.height;
                                    f = mesh.polygons.size ();
                                    return status >= 0;
                                  }));
    results.push_back (measure ("pcl::io::loadPolygonFile (VTK)", reps, [&] (std::size_t& v, std::size_t& f) {
      pcl::PolygonMesh mesh;
      const int status = pcl::io::loadPolygonFile (file, mesh);
      v = mesh.cloud.width * mesh.cloud.height;
      f = mesh.polygons.size ();
      return status > 0;
    }));

    const double ours = results.front ().median_ms;
    for (const Result& r : results)
    {
      char row[512];
      if (r.failed)
        std::snprintf (row, sizeof (row), "| %s | %s | - | - | failed | - |\n", baseName (file).c_str (), r.loader.c_str ());
      else
        std::snprintf (row, sizeof (row), "| %s | %s | %zu | %zu | %.1f | %.1f |\n", baseName (file).c_str (),
                       r.loader.c_str (), r.vertices, r.faces, r.median_ms, ours > 0 ? r.median_ms / ours : 0.0);
      table += row;
    }
  }
  std::printf ("%s", table.c_str ());
  if (!output.empty ())
  {
    // The machine's load matters on shared build machines: record it next to the numbers.
    std::string load_average = "?";
    if (std::FILE* file = std::fopen ("/proc/loadavg", "r"))
    {
      char text[64] = {0};
      if (std::fgets (text, sizeof (text), file))
        load_average = std::string (text).substr (0, std::string (text).find (' '));
      std::fclose (file);
    }
    const std::string text = "# Mesh load time\n\nMedian of " + std::to_string (reps) +
                             " runs after one warm-up run (file in the page cache), Release build, produced by "
                             "bench/load.sh; " + std::to_string (std::thread::hardware_concurrency ()) +
                             " hardware threads, 1-minute load average " + load_average +
                             " when measured (the ratios are steadier than the absolute times). `time / ours` is "
                             "relative to pcl_sparse::loadTriangleMesh; loadPolygonMesh includes the conversion to "
                             "pcl::PolygonMesh (one std::vector per polygon), which is most of its time.\n\n" +
                             table;
    pcl_sparse::writeBytesAtomically (output, text.data (), text.size ());
  }
  return 0;
}
