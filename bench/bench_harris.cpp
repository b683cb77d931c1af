/// bench_harris: Harris 3D on meshes (ours, docs/METHOD.md step 3) timed per stage, and side by side with
/// pcl::HarrisKeypoint3D (covariance of normals in a radius) on the same vertices: time, and how many of
/// each detector's top keypoints lie near sharp edges on fandisk. Prints a markdown report on stdout.
///
///   bench_harris [BIG_MESH] [FEATURE_MESH] [REPEATS]
///   (defaults: ../shared/meshes/koala-loop1-200k.ply, ../shared/meshes/fandisk.off, 3)

#include <pcl_sparse/geometry/mesh_neighborhood.h>
#include <pcl_sparse/geometry/sharp_edges.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/keypoints/harris3d.h>
#include <pcl_sparse/mesh/bounding_box.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <pcl/keypoints/harris_3d.h>
#include <pcl/point_types.h>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  using Clock = std::chrono::steady_clock;

  double
  secondsSince (Clock::time_point start)
  {
    return std::chrono::duration<double> (Clock::now () - start).count ();
  }

  double
  processCpuSeconds ()
  {
    timespec t;
    clock_gettime (CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double> (t.tv_sec) + 1e-9 * static_cast<double> (t.tv_nsec);
  }

  /// CPU seconds (all threads) of the last call of medianSeconds: on a shared machine wall time
  /// includes waiting for the cores, CPU time does not.
  double last_cpu_seconds = 0.0;

  /// Median wall time of \a repeats runs of \a run (and the median CPU time in last_cpu_seconds).
  double
  medianSeconds (int repeats, const std::function<void ()>& run)
  {
    std::vector<double> times, cpu;
    for (int i = 0; i < repeats; ++i)
    {
      const double cpu_start = processCpuSeconds ();
      const auto start = Clock::now ();
      run ();
      times.push_back (secondsSince (start));
      cpu.push_back (processCpuSeconds () - cpu_start);
    }
    std::sort (times.begin (), times.end ());
    std::sort (cpu.begin (), cpu.end ());
    last_cpu_seconds = cpu[cpu.size () / 2];
    return times[times.size () / 2];
  }

  double
  loadAverage ()
  {
    double load[1] = {0.0};
    return getloadavg (load, 1) == 1 ? load[0] : -1.0;
  }

  /// Mean over the vertices of the radius of their adaptive ring neighbourhood (what "comparable radius"
  /// means for PCL's detector).
  double
  meanAdaptiveRadius (const TriangleMesh& mesh, const MeshTopology& topo, const Harris3DOptions& options)
  {
    AdaptiveRingOptions adaptive;
    adaptive.radius = options.adaptive_fraction * boundingBoxDiagonal (mesh);
    adaptive.min_neighbors = options.min_neighbors;
    adaptive.max_rings = options.max_rings;
    VertexMarks marks (mesh.numVertices ());
    std::vector<int> hood;
    double sum = 0.0;
    for (int v = 0; v < static_cast<int> (mesh.numVertices ()); ++v)
    {
      collectAdaptiveRing (mesh, topo, v, adaptive, marks, hood);
      double r = 0.0;
      for (int u : hood)
        r = std::max (r, (mesh.vertices[u] - mesh.vertices[v]).norm ());
      sum += r;
    }
    return sum / static_cast<double> (mesh.numVertices ());
  }

  struct PclInput
  {
    pcl::PointCloud<pcl::PointXYZ>::Ptr points;
    pcl::PointCloud<pcl::Normal>::Ptr normals;
  };

  PclInput
  toPcl (const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& normals)
  {
    PclInput in{pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>> (), pcl::make_shared<pcl::PointCloud<pcl::Normal>> ()};
    in.points->resize (mesh.numVertices ());
    in.normals->resize (mesh.numVertices ());
    for (std::size_t v = 0; v < mesh.numVertices (); ++v)
    {
      (*in.points)[v].getVector3fMap () = mesh.vertices[v].cast<float> ();
      (*in.normals)[v].getNormalVector3fMap () = normals[v].cast<float> ();
    }
    return in;
  }

  /// PCL's detector as the issue prescribes: no refinement, non-maximum suppression, mesh normals.
  /// Returns keypoint vertex indices by decreasing response (PCL's own order depends on the threads).
  std::vector<int>
  pclHarris (const PclInput& in, double radius, int threads)
  {
    pcl::HarrisKeypoint3D<pcl::PointXYZ, pcl::PointXYZI> harris;
    harris.setInputCloud (in.points);
    harris.setNormals (in.normals);
    harris.setRadius (static_cast<float> (radius));
    harris.setRefine (false);
    harris.setNonMaxSupression (true);
    harris.setNumberOfThreads (threads);
    pcl::PointCloud<pcl::PointXYZI> keypoints;
    harris.compute (keypoints);
    const auto& indices = harris.getKeypointsIndices ()->indices;
    std::vector<int> order (indices.size ());
    std::iota (order.begin (), order.end (), 0);
    std::sort (order.begin (), order.end (), [&] (int a, int b) {
      return keypoints[a].intensity != keypoints[b].intensity ? keypoints[a].intensity > keypoints[b].intensity
                                                              : indices[a] < indices[b];
    });
    std::vector<int> result;
    for (int i : order)
      result.push_back (indices[i]);
    return result;
  }

  double
  fractionNear (const std::vector<int>& keys, std::size_t top, const std::vector<bool>& near)
  {
    const std::size_t n = std::min (top, keys.size ());
    if (n == 0)
      return 0.0;
    std::size_t hits = 0;
    for (std::size_t i = 0; i < n; ++i)
      hits += near[keys[i]];
    return static_cast<double> (hits) / static_cast<double> (n);
  }
} // namespace

int
main (int argc, char** argv)
{
  // Default data folder: ../shared/meshes next to the source tree this file was compiled from.
  std::string source = __FILE__;
  source = source.substr (0, source.find_last_of ('/'));
  const std::string shared = source.substr (0, source.find_last_of ('/')) + "/../shared/meshes";
  const std::string big_path = argc > 1 ? argv[1] : shared + "/koala-loop1-200k.ply";
  const std::string feature_path = argc > 2 ? argv[2] : shared + "/fandisk.off";
  const int repeats = argc > 3 ? std::max (1, std::atoi (argv[3])) : 3;
  const int max_threads = omp_get_max_threads ();

  try
  {
    // ---- stages on the big mesh ----
    TriangleMesh mesh;
    const double load_before = loadAverage ();
    const double t_load = medianSeconds (1, [&] { mesh = loadTriangleMesh (big_path); });
    const double c_load = last_cpu_seconds;
    MeshTopology topo;
    const double t_topology = medianSeconds (repeats, [&] { topo = buildMeshTopology (mesh); });
    const double c_topology = last_cpu_seconds;
    std::vector<Eigen::Vector3d> normals;
    const double t_normals = medianSeconds (repeats, [&] { normals = computeVertexNormals (mesh, topo); });
    const double c_normals = last_cpu_seconds;
    Harris3DOptions options;
    std::vector<double> responses;
    options.num_threads = 1;
    const double t_harris1 = medianSeconds (repeats, [&] { responses = computeHarris3DResponses (mesh, topo, options); });
    const double c_harris1 = last_cpu_seconds;
    options.num_threads = std::min (2, max_threads);
    const double t_harris2 = medianSeconds (repeats, [&] { responses = computeHarris3DResponses (mesh, topo, options); });
    const double c_harris2 = last_cpu_seconds;
    std::vector<int> keys;
    const double t_select = medianSeconds (repeats, [&] { keys = selectHarris3DKeypoints (mesh, topo, responses, options, mesh.numVertices ()); });
    const double c_select = last_cpu_seconds;
    options.rings = 2;
    const double t_rings2 = medianSeconds (repeats, [&] { computeHarris3DResponses (mesh, topo, options); });
    const double c_rings2 = last_cpu_seconds;
    options.rings = 0;
    const double radius = meanAdaptiveRadius (mesh, topo, options);

    const PclInput pcl_in = toPcl (mesh, normals);
    std::vector<int> pcl_keys;
    const double t_pcl2 = medianSeconds (1, [&] { pcl_keys = pclHarris (pcl_in, radius, std::min (2, max_threads)); });
    const double c_pcl2 = last_cpu_seconds;
    const double load_after = loadAverage ();

    std::printf ("# Harris 3D benchmark\n\n");
    std::printf ("Generated by bench/harris.sh (bench/bench_harris.cpp), Release build, %d OpenMP threads available, "
                 "median of %d runs (PCL: 1 run). The machine is shared: 1-minute load average %.1f before and %.1f "
                 "after the big-mesh runs, so wall times include waiting for a core; CPU seconds (all threads) do not.\n\n",
                 max_threads, repeats, load_before, load_after);
    std::printf ("## Stages on %s (%zu vertices, %zu faces)\n\n", big_path.substr (big_path.find_last_of ('/') + 1).c_str (),
                 mesh.numVertices (), mesh.numTriangles ());
    std::printf ("| stage | wall seconds | CPU seconds |\n|---|---|---|\n");
    std::printf ("| load (loadTriangleMesh) | %.3f | %.3f |\n", t_load, c_load);
    std::printf ("| topology (buildMeshTopology) | %.3f | %.3f |\n", t_topology, c_topology);
    std::printf ("| vertex normals (area-weighted) | %.3f | %.3f |\n", t_normals, c_normals);
    std::printf ("| Harris 3D responses, adaptive 0.01 diag, 1 thread | %.3f | %.3f |\n", t_harris1, c_harris1);
    std::printf ("| Harris 3D responses, adaptive 0.01 diag, 2 threads | %.3f | %.3f |\n", t_harris2, c_harris2);
    std::printf ("| Harris 3D responses, 2 rings, 2 threads | %.3f | %.3f |\n", t_rings2, c_rings2);
    std::printf ("| keypoint selection (1-ring maxima, top 1 %%: %zu keypoints) | %.3f | %.3f |\n", keys.size (), t_select, c_select);
    std::printf ("| pcl::HarrisKeypoint3D, radius %.4g (mean adaptive-ring radius), 2 threads | %.3f | %.3f |\n", radius, t_pcl2, c_pcl2);
    std::printf ("\nTime ratio pcl::HarrisKeypoint3D / ours (2 threads, responses + selection): %.2f wall, %.2f CPU\n\n",
                 t_pcl2 / (t_harris2 + t_select), c_pcl2 / (c_harris2 + c_select));

    // ---- where the top keypoints go on a mesh with sharp features ----
    const TriangleMesh feature = loadTriangleMesh (feature_path);
    const MeshTopology ftopo = buildMeshTopology (feature);
    const std::vector<bool> near = verticesNearSharpEdges (feature, ftopo, 60.0, 2);
    const std::size_t near_count = static_cast<std::size_t> (std::count (near.begin (), near.end (), true));
    const std::size_t top = static_cast<std::size_t> (std::lround (0.01 * feature.numVertices ()));
    const std::string fname = feature_path.substr (feature_path.find_last_of ('/') + 1);
    std::printf ("## Top %zu keypoints (1 %% of #V) on %s: fraction within 2 rings of a sharp edge (> 60 degrees)\n\n",
                 top, fname.c_str ());
    std::printf ("%zu of %zu vertices (%.1f %%) are within 2 rings of a sharp edge: the fraction a detector blind to "
                 "features would get.\n\n", near_count, feature.numVertices (), 100.0 * near_count / feature.numVertices ());
    std::printf ("| detector | keypoints found | top-%zu fraction near sharp edges | seconds |\n|---|---|---|---|\n", top);
    Harris3DOptions fopt;
    for (int rings : {0, 2})
    {
      fopt.rings = rings;
      std::vector<int> fkeys;
      const double t = medianSeconds (repeats, [&] {
        const std::vector<double> r = computeHarris3DResponses (feature, ftopo, fopt);
        fkeys = selectHarris3DKeypoints (feature, ftopo, r, fopt, feature.numVertices ());
      });
      std::printf ("| ours, %s | %zu | %.3f | %.3f |\n", rings == 0 ? "adaptive 0.01 diag" : "2 rings", fkeys.size (),
                   fractionNear (fkeys, top, near), t);
    }
    fopt.rings = 0;
    const double fradius = meanAdaptiveRadius (feature, ftopo, fopt);
    const PclInput fin = toPcl (feature, computeVertexNormals (feature, ftopo));
    for (double scale : {1.0, 2.0, 4.0})
    {
      std::vector<int> fkeys;
      const double t = medianSeconds (1, [&] { fkeys = pclHarris (fin, scale * fradius, std::min (2, max_threads)); });
      std::printf ("| pcl::HarrisKeypoint3D, radius %.4g (%.0f x mean adaptive-ring radius) | %zu | %.3f | %.3f |\n",
                   scale * fradius, scale, fkeys.size (), fractionNear (fkeys, top, near), t);
    }
    std::printf ("\nNotes: pcl::HarrisKeypoint3D is a different detector (covariance of the normals in a radius); it was "
                 "run with setRefine (false), setNonMaxSupression (true), the mesh's area-weighted vertex normals, and its "
                 "keypoints sorted by response here (its own output order depends on the thread schedule).\n");
  }
  catch (const std::exception& e)
  {
    std::fprintf (stderr, "bench_harris: %s\n", e.what ());
    return 1;
  }
  return 0;
}
