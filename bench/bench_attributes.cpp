/// bench_attributes: colour coding on a real RGB-D scan (issue 12 point 7).
///
///   bench_attributes CLOUD.pcd [-step S] [-L L] [-tolerance T] [-scan]
///
/// An organized PointXYZRGBA cloud (e.g. ../shared/clouds/table_scene_mug_stereo_textured.pcd) is
/// triangulated on its pixel grid (every S-th pixel, default 2; two triangles per grid cell whose corners
/// are finite and whose edges are shorter than 4 x the median grid edge), or with -scan given as a scan
/// (every S-th pixel by setIndices, no polygons: the library's cloud surface), encoded with its colours
/// (SparseSurfaceEncoder<PointXYZRGBA>), and measured:
///  - colour error at the input vertices (blended codes at their x', y' against the input, grey levels);
///  - colour error of a resampled PointXYZRGB cloud (as many points as vertices) against the colour of the
///    nearest input vertex, and for scale the difference between each vertex and its nearest other vertex;
///  - file bytes with and without the attribute sections, lossless and at tolerance 1e-4.
/// Prints one JSON line.

#include "bench_main.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl/io/pcd_io.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace pcl_sparse;

namespace
{
  using Cloud = pcl::PointCloud<pcl::PointXYZRGBA>;

  /// Grid triangles over every step-th pixel; \a used receives the points they use.
  std::vector<pcl::Vertices>
  gridTriangles (const Cloud& cloud, int step, pcl::Indices& used)
  {
    const int w = static_cast<int> (cloud.width), h = static_cast<int> (cloud.height);
    auto at = [&] (int c, int r) { return r * w + c; };
    auto finite = [&] (int i) { return std::isfinite (cloud[i].z); };
    std::vector<float> edges;
    for (int r = 0; r + step < h; r += step)
      for (int c = 0; c + step < w; c += step)
        if (finite (at (c, r)) && finite (at (c + step, r)))
          edges.push_back ((cloud[at (c, r)].getVector3fMap () - cloud[at (c + step, r)].getVector3fMap ()).norm ());
    std::nth_element (edges.begin (), edges.begin () + edges.size () / 2, edges.end ());
    const float limit = 4.0f * edges[edges.size () / 2];
    auto close = [&] (int a, int b) {
      return (cloud[a].getVector3fMap () - cloud[b].getVector3fMap ()).norm () < limit;
    };
    std::vector<pcl::Vertices> triangles;
    std::vector<char> in (cloud.size (), 0);
    auto add = [&] (int a, int b, int c) {
      if (!finite (a) || !finite (b) || !finite (c) || !close (a, b) || !close (b, c) || !close (c, a))
        return;
      pcl::Vertices t;
      t.vertices = {a, b, c};
      triangles.push_back (t);
      in[a] = in[b] = in[c] = 1;
    };
    for (int r = 0; r + step < h; r += step)
      for (int c = 0; c + step < w; c += step)
      {
        add (at (c, r), at (c, r + step), at (c + step, r));
        add (at (c + step, r), at (c, r + step), at (c + step, r + step));
      }
    for (std::size_t i = 0; i < in.size (); ++i)
      if (in[i])
        used.push_back (static_cast<int> (i));
    // Renumber the corners to positions in used (the encoder crops to the indices).
    std::vector<int> position (cloud.size (), -1);
    for (std::size_t k = 0; k < used.size (); ++k)
      position[used[k]] = static_cast<int> (k);
    for (pcl::Vertices& t : triangles)
      for (auto& v : t.vertices)
        v = position[v];
    return triangles;
  }

  double
  argument (int argc, char** argv, const std::string& name, double fallback)
  {
    for (int i = 2; i + 1 < argc; ++i)
      if (argv[i] == name)
        return std::atof (argv[i + 1]);
    return fallback;
  }
} // namespace

static int
run (int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf (stderr, "usage: %s CLOUD.pcd [-step S] [-L L] [-tolerance T]\n", argv[0]);
    return 1;
  }
  auto cloud = std::make_shared<Cloud> ();
  if (pcl::io::loadPCDFile (argv[1], *cloud) != 0 || cloud->height < 2)
  {
    std::fprintf (stderr, "%s: cannot read an organized cloud\n", argv[1]);
    return 1;
  }
  const int step = static_cast<int> (argument (argc, argv, "-step", 2));
  const bool scan = std::find_if (argv + 2, argv + argc, [] (const char* a) { return std::string (a) == "-scan"; }) != argv + argc;
  auto used = std::make_shared<pcl::Indices> ();
  std::vector<pcl::Vertices> triangles;
  if (scan)
  {
    for (int r = 0; r < static_cast<int> (cloud->height); r += step)
      for (int c = 0; c < static_cast<int> (cloud->width); c += step)
        used->push_back (r * static_cast<int> (cloud->width) + c);
  }
  else
    triangles = gridTriangles (*cloud, step, *used);
  // The encoder crops to the used points; their polygons are numbered in the whole cloud.
  auto polygons = std::make_shared<std::vector<pcl::Vertices>> (triangles);
  for (pcl::Vertices& t : *polygons)
    for (auto& v : t.vertices)
      v = (*used)[v];

  SparseSurfaceEncoder<pcl::PointXYZRGBA> encoder;
  SparseSurfaceEncoderOptions options;
  options.attributes.max_atoms = static_cast<int> (argument (argc, argv, "-L", 12));
  options.attributes.tolerance = argument (argc, argv, "-tolerance", 1.0 / 255.0);
  encoder.setOptions (options);
  encoder.setInputCloud (cloud);
  if (!scan)
    encoder.setInputPolygons (polygons);
  encoder.setIndices (used);
  auto model = std::make_shared<SparseSurfaceModel> ();
  const auto start = std::chrono::steady_clock::now ();
  encoder.compute (*model);
  const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  // The input point of each surface vertex.
  pcl::Indices vertex_points = *used;
  if (scan)
  {
    vertex_points.clear ();
    for (std::size_t i : encoder.getSurfaceInputIndices ())
      vertex_points.push_back (static_cast<int> (i));
    *used = vertex_points;
  }

  // Error at the vertices.
  const Eigen::MatrixXf at_vertices = model->reconstructVertexAttributes (used->size ());
  double sum2 = 0.0, sum1 = 0.0;
  std::size_t n = 0, nnz = 0;
  for (std::size_t k = 0; k < used->size (); ++k)
    for (int c = 0; c < 3; ++c)
    {
      const auto& p = (*cloud)[vertex_points[k]];
      const double input = c == 0 ? p.r : c == 1 ? p.g : p.b;
      const double e = at_vertices (static_cast<Eigen::Index> (k), c) - input;
      if (!std::isfinite (e))
        continue;
      sum2 += e * e;
      sum1 += std::abs (e);
      ++n;
    }
  for (const PatchCode& patch : model->patches)
    for (const SparseCode& code : patch.attributes)
      nnz += code.atoms.size ();

  // Error of a resampled cloud against the nearest input vertex.
  SparseSurfaceResampling<pcl::PointXYZRGB> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (used->size ());
  pcl::PointCloud<pcl::PointXYZRGB> out;
  resampling.compute (out);
  pcl::KdTreeFLANN<pcl::PointXYZRGBA> tree;
  tree.setInputCloud (cloud, used);
  double resampled = 0.0;
  pcl::Indices nearest (1);
  std::vector<float> distance (1);
  for (const auto& q : out)
  {
    pcl::PointXYZRGBA query;
    query.getVector3fMap () = q.getVector3fMap ();
    tree.nearestKSearch (query, 1, nearest, distance);
    const auto& p = (*cloud)[nearest[0]];
    resampled += (std::abs (q.r - p.r) + std::abs (q.g - p.g) + std::abs (q.b - p.b)) / (3.0 * out.size ());
  }

  // For scale: the colour difference between each vertex and its nearest other vertex.
  double neighbour = 0.0;
  pcl::Indices two (2);
  std::vector<float> two_distances (2);
  for (int i : *used)
  {
    tree.nearestKSearch ((*cloud)[i], 2, two, two_distances);
    const auto& p = (*cloud)[i];
    const auto& q = (*cloud)[two[0] == i ? two[1] : two[0]];
    neighbour += (std::abs (q.r - p.r) + std::abs (q.g - p.g) + std::abs (q.b - p.b)) / (3.0 * used->size ());
  }

  SparseSurfaceModel geometry = *model;
  geometry.attribute_channels.clear ();
  geometry.attribute_basis.reset ();
  for (PatchCode& patch : geometry.patches)
    patch.attributes.clear ();
  ModelWriteOptions quantised;
  quantised.tolerance = 1e-4;
  const double m = static_cast<double> (model->numPatches ());
  const double lossless_bytes = encodeModel (*model).size (), lossless_geometry = encodeModel (geometry).size ();
  const double quantised_bytes = encodeModel (*model, quantised).size (), quantised_geometry = encodeModel (geometry, quantised).size ();
  std::printf ("{\"mode\": \"%s\", \"vertices\": %zu, \"triangles\": %zu, \"patches\": %zu, \"attribute_nnz_per_patch_channel\": %.2f, "
               "\"vertex_rmse\": %.3f, \"vertex_mae\": %.3f, \"resampled_mae_vs_nearest\": %.3f, \"neighbour_mae\": %.3f, \"encode_seconds\": %.2f, "
               "\"lossless_bytes\": %.0f, \"lossless_attribute_bytes_per_patch\": %.1f, \"quantised_bytes\": %.0f, "
               "\"quantised_attribute_bytes_per_patch\": %.1f}\n",
               scan ? "scan" : "grid", used->size (), triangles.size (), model->numPatches (), nnz / (static_cast<double> (model->attribute_channels.size ()) * m), std::sqrt (sum2 / n), sum1 / n,
               resampled, neighbour, seconds, lossless_bytes, (lossless_bytes - lossless_geometry) / m, quantised_bytes,
               (quantised_bytes - quantised_geometry) / m);
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
