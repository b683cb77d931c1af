// Where flipped normals come from (issue 13): encodes MESH with default options, resamples 4 x its vertex
// count in memory (the points pcl_sparse_resample gives for the same count) and, for every flipped point
// (evaluateCloudQuality: over 120 degrees from its nearest face's normal), tells the patch that emitted it
// and what is special there, then counts the points per cause.
//
//   bench_flips MESH [-n COUNT] [-v]
//
// -v prints every flipped point: patch, radius and vertex count, local (x, y), centrality c, height h, the
// slope angle of the code, the distance to the nearest face (exact, every face) in spacings, the distance to
// the nearest face on the point's side (normal within 90 degrees of the point's), the point's angle to
// both faces and the angle between the two faces, the angle between the patch's frame normal N and the
// nearest face, whether that face's corners are the patch's own vertices, and the local distance
// (fraction of r_P) to the patch's nearest own vertex.
// Causes, first that applies:
//   tie        a face on the point's side within 3 mean point distances: the point lies on its side of a
//              knife edge or thin part within the coding error, and the other side is nearer by a hair
//   near tie   ... within 1/4 spacing
//   1 spacing  ... within 1 spacing: the point is off its surface by a fraction of a spacing
//   the others are farther: the code normal points away from a surface facing N (the code oscillates), or
//   the point lies on a surface facing away from N (the patch reaches across a thin part)
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_normals.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace pcl_sparse;

int
main (int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf (stderr, "usage: %s MESH [-n COUNT] [-v]\n", argv[0]);
    return 2;
  }
  std::size_t count = 0;
  bool verbose = false;
  for (int i = 2; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "-n" && i + 1 < argc)
      count = std::stoul (argv[++i]);
    else if (a == "-v")
      verbose = true;
  }
  auto mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (argv[1]));
  SparseSurfaceEncoder<pcl::PointXYZ> encoder;
  encoder.setInputMesh (mesh);
  encoder.setOptions (encoderPresetOptions (EncoderPreset::Default));
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  SparseSurfaceResampling<pcl::PointNormal> resampling;
  resampling.setInputModel (model);
  resampling.setPointCount (count > 0 ? count : 4 * mesh->vertices.size ());
  pcl::PointCloud<pcl::PointNormal> cloud;
  resampling.compute (cloud);
  const std::vector<int>& owner = resampling.getPointPatches ();

  CloudQualityOptions qo;
  qo.keep_per_point = true;
  const CloudQuality quality = evaluateCloudQuality (*mesh, cloud, qo);
  const std::vector<Eigen::Vector3d> face_normals = computeFaceNormals (*mesh);
  const PatchEvaluator evaluator (*model);
  std::printf ("%s: %zu patches, %zu points, spacing %.4g, flipped %zu, mean distance/diag %.4g\n", argv[1],
               model->numPatches (), cloud.size (), quality.spacing, quality.flipped,
               quality.mean_distance / quality.bbox_diagonal);

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
    double best = 1e300, best_agree = 1e300;
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
    const std::set<int> own (code.vertices.begin (), code.vertices.end ());
    const Eigen::Vector3i& t = mesh->triangles[face];
    const bool own_face = own.count (t[0]) && own.count (t[1]) && own.count (t[2]);
    double nearest_vertex = 1e300;
    for (const Eigen::Vector2d& v : code.vertex_xy)
      nearest_vertex = std::min (nearest_vertex, (v - local.head<2> ()).norm ());
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
    ++causes[cause];
    if (verbose)
      std::printf ("  pt %zu patch %d r %.3g verts %zu: xy (%.3f %.3f) c %.3f h %.3f slope %.1f | d %.2f s, agree %.2f s, "
                   "angle %.1f (side face %.1f, faces %.1f), N-face %.1f, own %d, vertex gap %.3f | %s\n",
                   i, p, code.radius, code.vertices.size (), local.x (), local.y (), c, h.value, slope, best / s,
                   best_agree / s, exact_angle, agree_angle, faces_angle, frame_angle, own_face ? 1 : 0, nearest_vertex, cause.c_str ());
  }
  for (const auto& [cause, k] : causes)
    std::printf ("  %4d  %s\n", k, cause.c_str ());
  std::printf ("  %zu patches emit flipped points:", per_patch.size ());
  for (const auto& [p, k] : per_patch)
    std::printf (" %d:%d", p, k);
  std::printf ("\n");
  return 0;
}
