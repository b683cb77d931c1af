// Face completion (patches/face_completion.h, issue 13 point 1): every face of the surface in some patch, so
// resampling leaves no hole, on generated meshes with long thin faces between patches and on the shared CAD
// meshes where faces in no patch covered most of the area (couplingdown 85 %, cheese-cgal 70 %, blade 42 %).

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/patches/face_completion.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/resampling/cloud_quality.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include "model_helpers.h"
#include "probe_gaps.h"
#include "shared_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  PatchSamplingResult
  samplePatches (const TriangleMesh& mesh, bool complete_faces)
  {
    PatchOptions options;
    options.complete_faces = complete_faces;
    return sampleFeatureAwarePatches (mesh, buildMeshTopology (mesh), options, {}, {}, 1, nullptr);
  }

  struct Coverage
  {
    double p99_spacings = 0.0;  ///< 99th percentile of probe-to-nearest-point distances, in spacings
    double within3 = 0.0;       ///< fraction of probes with a point within 3 spacings
    std::size_t flipped = 0;    ///< points more than 120 degrees from the nearest face's normal
    std::size_t points = 0;
  };

  /// Default encoder, cloud of \a points (0: 4 V), then as bench/bench_meshes: 20000 probes uniform by area (seed 1),
  /// distance to the nearest point over the spacing sqrt(area / #points).
  Coverage
  resampleAndMeasure (const TriangleMesh::ConstPtr& mesh, std::size_t points = 0)
  {
    const pcl::PointCloud<pcl::PointNormal> cloud =
      pcl_sparse_test::resampleModel (pcl_sparse_test::encodeMesh (mesh), points > 0 ? points : 4 * mesh->numVertices ());

    Coverage c;
    c.points = cloud.size ();
    const std::vector<double> gaps = pcl_sparse_test::probeGapsInSpacings (*mesh, cloud);
    c.within3 = static_cast<double> (std::count_if (gaps.begin (), gaps.end (), [] (double g) { return g <= 3.0; })) /
                gaps.size ();
    c.p99_spacings = pcl_sparse_test::percentile99 (gaps);
    CloudQualityOptions options;
    options.probes = 1000;
    c.flipped = evaluateCloudQuality (*mesh, cloud, options).flipped;
    return c;
  }

  /// \a file's path in ../shared/meshes, or else in ../shared/extra-meshes.
  std::string
  sharedMeshPath (const std::string& file)
  {
    const std::string meshes = std::string (PCL_SPARSE_SHARED_MESHES) + "/" + file;
    const std::string extra = std::string (PCL_SPARSE_SHARED_MESHES) + "/../extra-meshes/" + file;
    return std::ifstream (extra).good () ? extra : meshes;
  }
} // namespace

TEST (FaceCompletion, EveryFaceInAPatchOnLongThinFaces)
{
  // A coarse cylinder (faces 4 long, 0.2 wide, open borders) and a coarse cube (sharp edges, every face
  // touching one): the corners of most faces join different patches.
  const std::vector<std::pair<std::string, TriangleMesh>> meshes = {{"cylinder", makeCylinder (32, 1, 1.0, 2.0)},
                                                                    {"cube", makeCube (2)}};
  for (const auto& [name, mesh] : meshes)
  {
    const PatchSamplingResult without = samplePatches (mesh, false);
    const PatchSamplingResult with = samplePatches (mesh, true);
    std::cout << name << ": " << facesInNoPatch (mesh, without.patches).size () << " of " << mesh.triangles.size ()
              << " faces in no patch without completion, " << with.num_completed_faces << " completed, "
              << with.uncovered_faces.size () << " left" << std::endl;
    EXPECT_GT (facesInNoPatch (mesh, without.patches).size (), 0u) << name << ": the mesh does not test completion";
    EXPECT_EQ (facesInNoPatch (mesh, with.patches).size (), 0u) << name;
    EXPECT_TRUE (with.uncovered_faces.empty ()) << name;
    EXPECT_EQ (with.patches.size (), without.patches.size ()) << name << ": completion adds no patch";
    // Each patch stays a height field over its frame: no triangle flips in projection.
    for (const Patch& p : with.patches)
      for (int f : p.triangles)
      {
        const Eigen::Vector3i& t = mesh.triangles[f];
        const Eigen::Vector3d n = p.frame.col (2);
        const double a = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross (mesh.vertices[t[2]] - mesh.vertices[t[0]]).dot (n);
        ASSERT_GT (a, 0.0) << name << ": face " << f << " flips in the patch of seed " << p.seed;
      }

    const Coverage c = resampleAndMeasure (std::make_shared<TriangleMesh> (mesh));
    std::cout << name << ": p99 " << c.p99_spacings << " spacings, within 3 spacings " << c.within3 << ", flipped "
              << c.flipped << " of " << c.points << std::endl;
    EXPECT_EQ (c.within3, 1.0) << name << ": a hole in the cloud";
    EXPECT_LE (c.p99_spacings, 3.0) << name;
    EXPECT_EQ (c.flipped, 0u) << name;
  }
}

TEST (FaceCompletion, PresetPaperKeepsTheMethod)
{
  EXPECT_TRUE (PatchOptions ().complete_faces);
  EXPECT_FALSE (encoderPresetOptions (EncoderPreset::Paper).patches.complete_faces);
  EXPECT_TRUE (PatchOptions ().seed_patches_on_faces);
  EXPECT_FALSE (encoderPresetOptions (EncoderPreset::Paper).patches.seed_patches_on_faces);
  EXPECT_NEAR (PatchOptions ().face_steep_frame_angle, 50.0 * M_PI / 180.0, 1e-15);
  EXPECT_EQ (encoderPresetOptions (EncoderPreset::Paper).patches.face_steep_frame_angle, 0.0);
  EXPECT_EQ (authorsCodePatchOptions ().face_steep_frame_angle, 0.0);
  PatchOptions options;
  for (double angle : {-0.1, 1.6, std::nan ("")})
  {
    options.face_steep_frame_angle = angle;
    EXPECT_THROW (options.validate (), Error) << angle;
  }
}

TEST (FaceSeededPatches, CubeSidesBetweenTwoPatchesGetPatchesOfTheirOwn)
{
  // A 12-triangle cube grows 2 patches on opposite sides; the other sides' faces are outside both cones,
  // so completion cannot place them, and resampling left four sides without a point.
  const TriangleMesh cube = makeCube (1);
  PatchOptions options;
  options.seed_patches_on_faces = false;
  const PatchSamplingResult without = sampleFeatureAwarePatches (cube, buildMeshTopology (cube), options, {}, {}, 1, nullptr);
  EXPECT_EQ (facesInNoPatch (cube, without.patches).size (), 8u);
  EXPECT_EQ (without.uncovered_faces.size (), 8u);

  const PatchSamplingResult with = samplePatches (cube, true);
  EXPECT_TRUE (facesInNoPatch (cube, with.patches).empty ());
  EXPECT_TRUE (with.uncovered_faces.empty ());
  ASSERT_EQ (with.patches.size (), 6u);  // one a side: each grown side holds both its triangles
  const auto normals = computePatchGrowthGeometry (cube, buildMeshTopology (cube)).face_normals;
  int from_faces = 0;
  for (const Patch& p : with.patches)
  {
    from_faces += p.seed_face >= 0;
    ASSERT_EQ (p.triangles.size (), 2u);
    EXPECT_NEAR (normals[p.triangles[0]].dot (normals[p.triangles[1]]), 1.0, 1e-12);
  }
  EXPECT_GE (from_faces, 4);

  // Every side gets its share of the points (200 of 1200), each on its side with its side's outward normal.
  const pcl::PointCloud<pcl::PointNormal> cloud =
    pcl_sparse_test::resampleModel (pcl_sparse_test::encodeMesh (std::make_shared<TriangleMesh> (cube)), 1200);
  int per_side[6] = {0, 0, 0, 0, 0, 0};
  for (const pcl::PointNormal& q : cloud)
  {
    const Eigen::Vector3d n = q.getNormalVector3fMap ().cast<double> ();
    int axis;
    n.cwiseAbs ().maxCoeff (&axis);
    EXPECT_GT (std::abs (n[axis]), 0.99) << n.transpose ();
    const double outward = n[axis] > 0.0 ? 1.0 : -1.0;
    ++per_side[2 * axis + (outward > 0.0 ? 1 : 0)];
    EXPECT_NEAR (q.getVector3fMap ()[axis], outward, 1e-5) << "a point off its side, or an inward normal";
  }
  for (int side = 0; side < 6; ++side)
    EXPECT_GE (per_side[side], 150) << "side " << side << " of the cube has " << per_side[side] << " of 1200 points";
}

TEST (FaceCompletion, SharedCadMeshes)
{
  // Before this changes (default options, bench/results/meshes.md): p99 6.55 / 4.38 / 3.06 spacings
  // and 60 / 229 / 495 flipped normals. With completion alone p99 2.89 / 2.84 / 0.82, flipped 0 / 33 / 8, but
  // a quarter of couplingdown's and cheese-cgal's area was still a triangle of no patch (24.5 %, 27.0 %: faces
  // outside the cone of every patch holding a corner), covered only by the overshoot of the patches beside
  // them, which at 100000 points left couplingdown's p99 at 9.8 spacings. With patches seeded on those faces
  // none of couplingdown's area is left and 0.04 % of cheese-cgal's; blade's 0.16 % are fillet strips too long
  // for a star-shaped footprint (kMaxFacePatchSpread), left to their neighbours as before.
  struct Case
  {
    std::string file;
    double max_p99;  ///< spacings: 3 (issue 13), or about 1.5 x the measured value where that is far below
    std::size_t max_flipped;
    double max_area_in_no_patch;  ///< fraction of the area that is a triangle of no patch
  };
  for (const Case& entry : {Case{"couplingdown.off", 3.0, 2, 0.0}, Case{"cheese-cgal.off", 3.0, 10, 0.001},
                            Case{"blade.off", 1.2, 12, 0.002}})
  {
    const std::string& file = entry.file;
    const std::string path = sharedMeshPath (file);
    PCL_SPARSE_NEED_SHARED_FILE (path);
    const TriangleMesh::ConstPtr mesh = std::make_shared<TriangleMesh> (loadTriangleMesh (path));
    const PatchSamplingResult with = samplePatches (*mesh, true);
    EXPECT_EQ (facesInNoPatch (*mesh, with.patches).size (), with.uncovered_faces.size ()) << file;
    const double area_in_no_patch = faceCoverage (*mesh, with.patches).area_fraction;
    const Coverage c = resampleAndMeasure (mesh);
    std::cout << file << ": " << with.num_completed_faces << " faces completed, " << with.uncovered_faces.size ()
              << " left (" << 100.0 * area_in_no_patch << " % of the area); p99 " << c.p99_spacings
              << " spacings, within 3 spacings " << c.within3 << ", flipped " << c.flipped << " of " << c.points << std::endl;
    EXPECT_LE (area_in_no_patch, entry.max_area_in_no_patch) << file;
    EXPECT_LE (c.p99_spacings, entry.max_p99) << file;
    EXPECT_LE (c.flipped, entry.max_flipped) << file;
    if (file == "couplingdown.off")
    {
      // Denser than 4 V, the patches' overshoot no longer covered the faces in no patch: 9.8 spacings before.
      // With every face in a patch 3.17: patches grown from faces whose jets left triangles steeper than
      // resampling's slope bound (50 degrees) had those places left to overlapping patches, and there were
      // none; with face_steep_frame_angle 2.03 (bench_meshes' 200k probes).
      const Coverage dense = resampleAndMeasure (mesh, 100000);
      std::cout << file << " at 100000 points: p99 " << dense.p99_spacings << " spacings, within 3 spacings "
                << dense.within3 << std::endl;
      EXPECT_LE (dense.p99_spacings, 3.0) << file;
      EXPECT_GE (dense.within3, 0.99) << file;
    }
  }
}
