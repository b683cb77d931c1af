// Where flipped normals come from (issue 13): encodes MESH with default options, resamples 4 x its vertex
// count in memory (the points pcl_sparse_resample gives for the same count) and, for every flipped point
// (evaluateCloudQuality: over 120 degrees from its nearest face's normal), tells the patch that emitted it
// and what is special there, then counts the points per cause.
//
//   bench_flips MESH [-n COUNT] [-seed S] [-clearance C] [-max-cr R] [-keep-redundant] [-keep-flipped] [-hidden-gap G] [-merge K] [-basis B] [-file] [-psm FILE] [-v] [-far]
//               [-patch P] [-o CLOUD.pcd]
//
// -keep-flipped encodes with the footprints as coded (SparseSurfaceEncoderOptions::trim_flipped_places false:
// the flipped places the encoder would draw them in at are kept); -keep-redundant encodes with every patch kept
// (PatchOptions::drop_redundant_patches false); -hidden-gap G
// releases hidden triangles at gap G (PatchOptions::hidden_triangle_gap; 0: none); -merge K merges
// the patches with at most K elements of their own (PatchOptions::merge_own_elements; 0: none); -basis B encodes
// with that basis (paper, dct, quadric; default: the library's).
// -file resamples the model as the default `-o` file holds it (quantised at derivedWriteOptions, decoded), as
// pcl_sparse_resample FILE.psm does, instead of the lossless model in memory; -psm FILE resamples that file
// (pcl_sparse_encode MESH -o FILE, measured write options), and -v then also gives each flipped point's
// centrality in the same patch of the model in memory and whether the nearest angle there is a trim cut.
// -max-cr R encodes with that compression bound (SparseSurfaceEncoderOptions::max_compression_ratio, default
// 1; 0: none), to tell the flipped points the bound's trimmed codes cause.
// -seed S and -clearance C resample with that seed and knife-edge clearance (defaults: the library's, as
// pcl_sparse_resample). Every run also prints how many points lie farther than 1/4, 1/2, 1 and 2 spacings
// from the mesh and the share of the mean distance those beyond 1/2 spacing make. -far lists the points
// farther than a spacing (patch, local x, y, centrality, distance to the patch's nearest own vertex);
// -patch P prints patch P: its coding figures, vertices (local coordinates and the code's height there),
// projected triangles and footprint. -o writes the cloud (for bench_meshes: its 99th-percentile holes).
// -v prints every flipped point: patch, radius and vertex count, local (x, y), centrality c, height h, the
// slope angle of the code, the distance to the nearest face (exact, every face) in spacings, the distance to
// the nearest face on the point's side (normal within 90 degrees of the point's), the point's angle to
// both faces and the angle between the two faces, the angle between the patch's frame normal N and the
// nearest face, whether that face's corners are the patch's own vertices, and the local distance
// (fraction of r_P) to the patch's nearest own vertex; then every other patch that holds the nearest face
// or whose footprint nearly holds the point (centrality <= 1.5): the angle between the two frames, the
// point's centrality and its height above that patch's code in that patch's local units (the knife-edge
// clearance drops points within 0.03 of a facing-away patch's code), and the code's slope there.
// "fold": the sharpest turn between a face within a spacing of the point and a face across one of its
// edges; over 150 degrees the input folds back on itself there (a crumpled scan), and the cause gets
// ", on a fold of the input".
// Causes, first that applies:
//   tie        a face on the point's side within 3 mean point distances: the point lies on its side of a
//              knife edge or thin part within the coding error, and the other side is nearer by a hair
//   near tie   ... within 1/4 spacing
//   1 spacing  ... within 1 spacing: the point is off its surface by a fraction of a spacing
//   the others are farther: the code normal points away from a surface facing N (the code oscillates), or
//   the point lies on a surface facing away from N (the patch reaches across a thin part)
#include "bench_main.h"

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/file_tolerance.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// Local distance (fraction of r_P) from \a local to the patch's nearest own vertex.
  double
  vertexGap (const PatchCode& code, const Eigen::Vector3d& local)
  {
    double gap = 1e300;
    for (const Eigen::Vector2d& v : code.vertex_xy)
      gap = std::min (gap, (v - local.head<2> ()).norm ());
    return gap;
  }

  /// Whether every corner of triangle \a t is one of the patch's vertices.
  bool
  holdsTriangle (const PatchCode& code, const Eigen::Vector3i& t)
  {
    return std::all_of (t.data (), t.data () + 3, [&] (int v) {
      return std::find (code.vertices.begin (), code.vertices.end (), v) != code.vertices.end ();
    });
  }

  /// -patch P: the patch's coding figures, its vertices (local x', y', z' and the code's height there), its
  /// triangles projected and its footprint's extents.
  void
  printPatch (const TriangleMesh& mesh, const SparseSurfaceModel& model, const PatchCodingInfo& info,
              const PatchEvaluator& evaluator, int p)
  {
    const PatchCode& code = model.patches[p];
    std::printf ("patch %d: N (%.3f %.3f %.3f) r %.4g, %zu atoms, %d samples, spacing %.3f, %d atoms allowed, "
                 "relative residual %.4f, residual after each atom",
                 p, code.frame (0, 2), code.frame (1, 2), code.frame (2, 2), code.radius, code.atoms.size (),
                 info.num_samples, info.spacing, info.allowed_atoms, info.relative_residual);
    for (double r : info.residual_norms)
      std::printf (" %.4f", r);
    std::printf ("\n");
    for (int v : code.vertices)
    {
      const Eigen::Vector3d l = code.toLocal (mesh.vertices[v]);
      std::printf ("  vertex %d local (%.3f %.3f %.4f) code %.4f\n", v, l.x (), l.y (), l.z (),
                   evaluator.sample (p, l.x (), l.y (), false).value);
    }
    for (const Eigen::Vector3i& t : mesh.triangles)
      if (holdsTriangle (code, t))
      {
        std::printf ("  triangle");
        for (int j = 0; j < 3; ++j)
        {
          const Eigen::Vector3d l = code.toLocal (mesh.vertices[t[j]]);
          std::printf (" (%.3f %.3f)", l.x (), l.y ());
        }
        std::printf ("\n");
      }
    std::printf ("  footprint extents:");
    for (float e : code.footprint.extent)
      std::printf (" %.2f", e);
    std::printf ("\n");
  }

  /// How many points lie farther than 1/4, 1/2, 1 and 2 spacings from the mesh, and the share of the mean
  /// distance that the points farther than 1/2 spacing make.
  void
  printDistanceShares (const CloudQuality& quality)
  {
    const double limits[4] = {0.25, 0.5, 1.0, 2.0};
    std::size_t over[4] = {0, 0, 0, 0};
    double sum = 0.0, sum_over_half = 0.0;
    for (double d : quality.point_distances)
    {
      sum += d;
      for (int j = 0; j < 4; ++j)
        over[j] += d > limits[j] * quality.spacing;
      if (d > 0.5 * quality.spacing)
        sum_over_half += d;
    }
    std::printf ("  points farther than 1/4, 1/2, 1, 2 spacings: %zu %zu %zu %zu; share of the mean distance from "
                 "those over 1/2: %.3f\n",
                 over[0], over[1], over[2], over[3], sum > 0.0 ? sum_over_half / sum : 0.0);
  }
} // namespace

static int
run (int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf (stderr, "usage: %s MESH [-n COUNT] [-seed S] [-clearance C] [-max-cr R] [-keep-redundant] [-keep-flipped] [-hidden-gap G] [-merge K] [-basis B] [-file] [-psm FILE] [-v] [-far] [-patch P] [-o CLOUD.pcd]\n", argv[0]);
    return 2;
  }
  std::size_t count = 0;
  bool verbose = false;
  int dump_patch = -1;
  bool far = false;
  bool through_file = false;
  std::string psm_path;    // -psm: resample this model file
  std::string cloud_path;  // -o: the cloud, for bench_meshes (p99 holes)
  SparseSurfaceResamplingOptions resampling_options;
  SparseSurfaceEncoderOptions encoder_options = encoderPresetOptions (EncoderPreset::Default);
  for (int i = 2; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "-n" && i + 1 < argc)
      count = std::stoul (argv[++i]);
    else if (a == "-v")
      verbose = true;
    else if (a == "-patch" && i + 1 < argc)
      dump_patch = std::stoi (argv[++i]);
    else if (a == "-seed" && i + 1 < argc)
      resampling_options.seed = std::stoull (argv[++i]);
    else if (a == "-clearance" && i + 1 < argc)
      resampling_options.ownership.opposite_clearance = std::stod (argv[++i]);
    else if (a == "-o" && i + 1 < argc)
      cloud_path = argv[++i];
    else if (a == "-far")
      far = true;
    else if (a == "-file")
      through_file = true;
    else if (a == "-psm" && i + 1 < argc)
      psm_path = argv[++i];
    else if (a == "-keep-redundant")
      encoder_options.patches.drop_redundant_patches = false;
    else if (a == "-keep-flipped")
      encoder_options.trim_flipped_places = false;
    else if (a == "-hidden-gap" && i + 1 < argc)
      encoder_options.patches.hidden_triangle_gap = std::stod (argv[++i]);
    else if (a == "-merge" && i + 1 < argc)
      encoder_options.patches.merge_own_elements = std::stoi (argv[++i]);
    else if (a == "-basis" && i + 1 < argc)
      encoder_options.basis = cosineBasisKindFromName (argv[++i]);
    else if (a == "-max-cr" && i + 1 < argc)
      encoder_options.max_compression_ratio = std::stod (argv[++i]);
  }
  auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (argv[1]));
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (mesh);
  encoder.setOptions (encoder_options);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  if (through_file)
  {
    std::vector<double> errors;
    const ModelStatistics stats = model->statistics (mesh->vertices, &errors);
    const ModelWriteOptions write_options = derivedWriteOptions (stats, errors, model->bbox_diagonal);
    const std::vector<std::uint8_t> bytes = encodeModel (*model, write_options);
    *model = decodeModel (bytes.data (), bytes.size ());
    std::printf ("through the default file: tolerance %.4g of the diagonal\n", write_options.tolerance);
  }
  const SparseSurfaceModel in_memory = *model;
  if (!psm_path.empty ())
    *model = loadModel (psm_path);
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (count > 0 ? count : 4 * mesh->vertices.size ());
  resampling.setOptions (resampling_options);
  pcl::PointCloud<pcl::PointNormal> cloud;
  resampling.compute (cloud);
  const std::vector<int>& owner = resampling.getPointPatches ();
  if (!cloud_path.empty ())
    savePointNormalCloud (cloud_path, cloud);

  CloudQualityOptions qo;
  qo.keep_per_point = true;
  const CloudQuality quality = evaluateCloudQuality (*mesh, cloud, qo);
  const std::vector<Eigen::Vector3d> face_normals = computeFaceNormals (*mesh);
  const PatchEvaluator evaluator (*model);
  const MeshTopology topology = buildMeshTopology (*mesh);
  // The sharpest turn between face f and a face across one of its edges (degrees); over 150 the input
  // folds back on itself there, and a point on the fold has no one side.
  const auto sharpestTurn = [&] (std::size_t f) {
    double turn = 0.0;
    for (int k = 0; k < 3; ++k)
      if (const int g = topology.face_neighbors[f][k]; g >= 0)
        turn = std::max (turn, std::acos (std::clamp (face_normals[f].dot (face_normals[g]), -1.0, 1.0)) * 180.0 / M_PI);
    return turn;
  };
  std::printf ("%s: %zu patches, %zu points, spacing %.4g, flipped %zu, mean distance/diag %.4g\n", argv[1],
               model->numPatches (), cloud.size (), quality.spacing, quality.flipped,
               quality.mean_distance / quality.bbox_diagonal);

  if (dump_patch >= 0 && static_cast<std::size_t> (dump_patch) < model->numPatches ())
    printPatch (*mesh, *model, encoder.getCodingInfo ()[dump_patch], evaluator, dump_patch);
  printDistanceShares (quality);
  if (far)
  {
    std::map<int, int> far_patches;
    for (std::size_t i = 0; i < cloud.size (); ++i)
      if (quality.point_distances[i] > quality.spacing)
      {
        const int p = owner[i];
        ++far_patches[p];
        const PatchCode& code = model->patches[p];
        const Eigen::Vector3d local = code.toLocal (cloud[i].getVector3fMap ().cast<double> ());
        std::printf ("  far pt %zu patch %d verts %zu: d %.2f s, xy (%.3f %.3f) c %.3f, vertex gap %.3f\n", i, p,
                     code.vertices.size (), quality.point_distances[i] / quality.spacing, local.x (), local.y (),
                     evaluator.centrality (p, local.x (), local.y ()), vertexGap (code, local));
      }
    std::printf ("  %zu patches emit far points:", far_patches.size ());
    for (const auto& [p, k] : far_patches)
      std::printf (" %d:%d", p, k);
    std::printf ("\n");
  }
  std::map<std::string, int> causes;
  std::map<int, int> per_patch;
  for (std::size_t i = 0; i < cloud.size (); ++i)
  {
    if (!(quality.point_normal_angles[i] > 120.0))
      continue;
    const int p = owner[i];
    ++per_patch[p];
    const PatchCode& code = model->patches[p];
    const Eigen::Vector3d q = cloud[i].getVector3fMap ().cast<double> ();
    const Eigen::Vector3d n = cloud[i].getNormalVector3fMap ().cast<double> ().normalized ();
    const Eigen::Vector3d local = code.frame.transpose () * (q - code.origin) / code.radius;
    const HeightSample h = evaluator.sample (p, local.x (), local.y (), false);
    const double c = evaluator.centrality (p, local.x (), local.y ());
    const double slope = std::atan (h.gradient.norm ()) * 180.0 / M_PI;
    // Exact nearest face, and nearest face on the point's side.
    double best = 1e300, best_agree = 1e300, fold = 0.0;
    std::size_t face = 0, agree_face = 0;
    for (std::size_t f = 0; f < mesh->numTriangles (); ++f)
    {
      const Eigen::Vector3i& t = mesh->triangles[f];
      const double d = pointTriangleDistance (q, mesh->vertices[t[0]], mesh->vertices[t[1]], mesh->vertices[t[2]]);
      if (d < best)
      {
        best = d;
        face = f;
      }
      if (d <= quality.spacing)
        fold = std::max (fold, sharpestTurn (f));
      if (face_normals[f].dot (n) > 0.0 && d < best_agree)
      {
        best_agree = d;
        agree_face = f;
      }
    }
    const double exact_angle = std::acos (std::clamp (n.dot (face_normals[face]), -1.0, 1.0)) * 180.0 / M_PI;
    // The dihedral between the nearest face and the nearest on the point's side: over 120 degrees at a
    // knife edge or across a thin part.
    const double agree_angle = std::acos (std::clamp (n.dot (face_normals[agree_face]), -1.0, 1.0)) * 180.0 / M_PI;
    const double faces_angle =
      std::acos (std::clamp (face_normals[face].dot (face_normals[agree_face]), -1.0, 1.0)) * 180.0 / M_PI;
    const double frame_angle =
      std::acos (std::clamp (code.frame.col (2).dot (face_normals[face]), -1.0, 1.0)) * 180.0 / M_PI;
    const Eigen::Vector3i& t = mesh->triangles[face];
    const bool own_face = holdsTriangle (code, t);
    const double nearest_vertex = vertexGap (code, local);
    const double s = quality.spacing;
    std::string cause;
    if (exact_angle <= 120.0)
      cause = "yardstick: 16-centroid search missed the nearest face";
    else if (best_agree <= 3.0 * quality.mean_distance)
      cause = "tie: a face on the point's side within 3 mean distances";
    else if (best_agree <= 0.25 * s)
      cause = "near tie: a face on the point's side within 1/4 spacing";
    else if (best_agree <= 1.0 * s)
      cause = "a face on the point's side within 1 spacing";
    else if (frame_angle > 90.0)
      cause = own_face ? "own face faces away from N" : "other surface facing away from N";
    else
      cause = "code normal flipped on a surface facing N";
    if (fold > 150.0)
      cause += ", on a fold of the input";
    ++causes[cause];
    if (verbose)
      std::printf ("  pt %zu patch %d r %.3g verts %zu: xy (%.3f %.3f) c %.3f h %.3f slope %.1f | d %.2f s, agree %.2f s, "
                   "angle %.1f (side face %.1f, faces %.1f), N-face %.1f, own %d, vertex gap %.3f, fold %.1f | %s\n",
                   i, p, code.radius, code.vertices.size (), local.x (), local.y (), c, h.value, slope, best / s,
                   best_agree / s, exact_angle, agree_angle, faces_angle, frame_angle, own_face ? 1 : 0, nearest_vertex, fold, cause.c_str ());
    if (verbose && !psm_path.empty () && in_memory.numPatches () == model->numPatches ())
    {
      const PatchCode& there = in_memory.patches[p];
      const Eigen::Vector3d l = there.toLocal (q);
      const std::size_t k = there.footprint.extent.size ();
      const double turn = std::atan2 (l.y (), l.x ()) / (2.0 * M_PI);
      const std::size_t angle = k == 0 ? 0 : static_cast<std::size_t> (std::lround ((turn < 0 ? turn + 1.0 : turn) * k)) % k;
      std::printf ("      in memory: c %.3f, nearest angle %zu %s\n", PatchEvaluator (in_memory).centrality (p, l.x (), l.y ()),
                   angle, there.footprint.trimmed.size () == k && k > 0 && there.footprint.trimmed[angle] ? "trimmed" : "not trimmed");
    }
    if (verbose)
      for (std::size_t o = 0; o < model->numPatches (); ++o)
      {
        if (static_cast<int> (o) == p)
          continue;
        const PatchCode& other = model->patches[o];
        const Eigen::Vector3d l = other.toLocal (q);
        const double co = evaluator.centrality (o, l.x (), l.y ());
        const bool holds_face = holdsTriangle (other, t);
        if (!(co <= 1.5) && !holds_face)
          continue;
        const HeightSample ho = evaluator.sample (o, l.x (), l.y (), false);
        std::printf ("      %spatch %zu: frames %.1f degrees apart, c %.3f, z - h %.4f, slope %.1f\n", holds_face ? "holds the nearest face, " : "", o,
                     std::acos (std::clamp (other.frame.col (2).dot (code.frame.col (2)), -1.0, 1.0)) * 180.0 / M_PI,
                     co, l.z () - ho.value,
                     std::atan (ho.gradient.norm ()) * 180.0 / M_PI);
      }
  }
  for (const auto& [cause, k] : causes)
    std::printf ("  %4d  %s\n", k, cause.c_str ());
  std::printf ("  %zu patches emit flipped points:", per_patch.size ());
  for (const auto& [p, k] : per_patch)
    std::printf (" %d:%d", p, k);
  std::printf ("\n");
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
