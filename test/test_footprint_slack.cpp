/// The footprint slack a quantised file may use (resampling/footprint_slack.h): borders through same-side
/// neighbours may move, open borders may not, and the writer's files stay as near the surface.

#include "knife_mesh.h"
#include "model_helpers.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/resampling/footprint_slack.h>
#include <pcl_sparse/resampling/patch_evaluator.h>
#include <pcl_sparse/resampling/patch_geometry.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <iostream>

using namespace pcl_sparse;

namespace
{
  SparseSurfaceModel
  encode (const TriangleMesh& mesh, double rho)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (std::make_shared<TriangleMesh> (mesh));
    SparseSurfaceEncoderOptions options;
    options.patches.rho = rho;
    encoder.setOptions (options);
    SparseSurfaceModel model;
    encoder.compute (model);
    return model;
  }

  /// World point of patch p's surface at angle index i of its footprint, at t times the extent.
  Eigen::Vector3d
  borderPoint (const PatchEvaluator& evaluator, std::size_t p, std::size_t i, double t)
  {
    const PatchCode& code = evaluator.model ().patches[p];
    const double angle = 2.0 * M_PI * static_cast<double> (i) / static_cast<double> (code.footprint.extent.size ());
    const double x = t * code.footprint.extent[i] * std::cos (angle), y = t * code.footprint.extent[i] * std::sin (angle);
    return patchPoint (code, x, y, evaluator.sample (p, x, y, false));
  }

  /// The smallest centrality at which a patch other than \a skip holds the world point \a q on its surface
  /// (within a tenth of its radius of it); infinity when none does.
  double
  heldCentrality (const PatchEvaluator& evaluator, const Eigen::Vector3d& q, std::size_t skip = std::size_t (-1))
  {
    double best = std::numeric_limits<double>::infinity ();
    for (std::size_t p = 0; p < evaluator.model ().patches.size (); ++p)
    {
      const PatchCode& code = evaluator.model ().patches[p];
      const Eigen::Vector3d local = code.frame.transpose () * (q - code.origin) / code.radius;
      const double c = evaluator.centrality (p, local.x (), local.y ());
      if (p != skip && c < best && std::abs (local.z () - evaluator.height (p, local.x (), local.y ())) <= 0.1)
        best = c;
    }
    return best;
  }

  /// The model with every footprint drawn at the slack's lower extents: the least a file may cover.
  SparseSurfaceModel
  atLowerExtents (SparseSurfaceModel model, const std::vector<FootprintSlack>& slack)
  {
    for (std::size_t p = 0; p < model.patches.size (); ++p)
      model.patches[p].footprint.extent = slack[p].lower;
    return model;
  }

  /// Every vertex and face centroid of \a mesh held by a footprint of \a model is still held with every
  /// footprint drawn at its lower slack; the number of those lost.
  std::size_t
  placesLostAtLowerExtents (const TriangleMesh& mesh, const SparseSurfaceModel& model, const std::vector<FootprintSlack>& slack)
  {
    const PatchEvaluator exact (model);
    const SparseSurfaceModel lower_model = atLowerExtents (model, slack);
    const PatchEvaluator lower (lower_model);
    std::vector<Eigen::Vector3d> probes (mesh.vertices.begin (), mesh.vertices.end ());
    for (const Eigen::Vector3i& face : mesh.triangles)
      probes.push_back ((mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]) / 3.0);
    std::size_t lost = 0;
    for (const Eigen::Vector3d& q : probes)
      lost += heldCentrality (exact, q) <= 1.0 && heldCentrality (lower, q) > 1.0;
    return lost;
  }
} // namespace

// An open, gently waved sheet over [-1, 1]^2. Where a border place of a patch lies in no other footprint (at
// the sheet's edge), its extent keeps no slack; inside, nearly every border runs through neighbours and may
// move. However every footprint is drawn within its slack, the places the footprints held stay held.
TEST (FootprintSlack, OnlyBordersThroughNeighboursMoveAndNoPlaceIsLost)
{
  const TriangleMesh sheet =
    makeHeightFieldGrid (48, 48, 1.0, 1.0, [] (double x, double y) { return 0.1 * std::sin (3.0 * x) * std::cos (2.0 * y); });
  const SparseSurfaceModel model = encode (sheet, 0.001);
  ASSERT_GE (model.patches.size (), 8u);  // 9 with the small patches merged into their neighbours
  const std::vector<FootprintSlack> slack = footprintSlack (model);
  ASSERT_EQ (slack.size (), model.patches.size ());
  const PatchEvaluator evaluator (model);
  std::size_t alone = 0, alone_moved = 0, inside = 0, inside_moved = 0;
  for (std::size_t p = 0; p < model.patches.size (); ++p)
  {
    const std::vector<float>& extent = model.patches[p].footprint.extent;
    ASSERT_EQ (slack[p].lower.size (), extent.size ());
    ASSERT_EQ (slack[p].upper.size (), extent.size ());
    for (std::size_t i = 0; i < extent.size (); ++i)
    {
      EXPECT_LE (slack[p].lower[i], extent[i]);
      EXPECT_GE (slack[p].lower[i], 0.7f * extent[i] - 1e-6f);
      EXPECT_GE (slack[p].upper[i], extent[i]);
      EXPECT_LE (slack[p].upper[i], 1.3f * extent[i] + 1e-6f);
      const Eigen::Vector3d b = borderPoint (evaluator, p, i, 1.0);
      const bool moved = slack[p].lower[i] < extent[i] || slack[p].upper[i] > extent[i];
      if (heldCentrality (evaluator, b, p) > 1.0)
      {
        ++alone;
        alone_moved += moved;
      }
      else if (1.0 - std::max (std::abs (b.x ()), std::abs (b.y ())) > 0.3)
      {
        ++inside;
        inside_moved += moved;
      }
    }
  }
  const std::size_t lost = placesLostAtLowerExtents (sheet, model, slack);
  std::cout << "  " << model.patches.size () << " patches; " << alone_moved << " of " << alone
            << " extents whose border place no other footprint holds have slack, " << inside_moved << " of " << inside
            << " inside; places lost at the lower extents: " << lost << std::endl;
  ASSERT_GT (alone, 40u);
  EXPECT_EQ (alone_moved, 0u);
  ASSERT_GT (inside, 200u);
  EXPECT_GT (inside_moved, inside * 9 / 10);
  EXPECT_EQ (lost, 0u);
}

// Past a trim cut (PatchFootprint::trimmed) the code's normal points away from the surface: the border may
// still be drawn in there, never out; the other angles keep their slack.
TEST (FootprintSlack, NoOutwardSlackAtATrimCut)
{
  const TriangleMesh sheet =
    makeHeightFieldGrid (48, 48, 1.0, 1.0, [] (double x, double y) { return 0.1 * std::sin (3.0 * x) * std::cos (2.0 * y); });
  SparseSurfaceModel model = encode (sheet, 0.001);
  const std::vector<FootprintSlack> before = footprintSlack (model);
  std::size_t marked = 0;
  for (std::size_t p = 0; p < model.patches.size (); ++p)
  {
    PatchFootprint& footprint = model.patches[p].footprint;
    footprint.trimmed.assign (footprint.extent.size (), 0);
    for (std::size_t i = 0; i < footprint.extent.size (); i += 2)
      if (before[p].upper[i] > footprint.extent[i])
      {
        footprint.trimmed[i] = 1;
        ++marked;
      }
  }
  ASSERT_GT (marked, 100u);
  const std::vector<FootprintSlack> after = footprintSlack (model);
  for (std::size_t p = 0; p < model.patches.size (); ++p)
  {
    const PatchFootprint& footprint = model.patches[p].footprint;
    EXPECT_EQ (after[p].lower, before[p].lower) << p;
    for (std::size_t i = 0; i < footprint.extent.size (); ++i)
      EXPECT_EQ (after[p].upper[i], footprint.trimmed[i] ? footprint.extent[i] : before[p].upper[i]) << p << " angle " << i;
  }
}

// A 20-degree knife (two bent sheets welded along x = 1): the borders at the edge, where each side's places
// are left unsampled only within the other side's footprint, are knife edges; no other border is, and an open
// sheet has none.
TEST (FootprintSlack, KnifeEdgesAreFoundAtTheEdgeOnly)
{
  const TriangleMesh knife = pcl_sparse_test::makeKnife (40, 20.0);
  const SparseSurfaceModel model = encode (knife, 0.001);
  const std::vector<FootprintSlack> slack = footprintSlack (model);
  const PatchEvaluator evaluator (model);
  std::size_t flagged = 0, flagged_far = 0, patches = 0;
  for (std::size_t p = 0; p < model.patches.size (); ++p)
  {
    if (slack[p].knife_edge.empty ())
      continue;
    ASSERT_EQ (slack[p].knife_edge.size (), model.patches[p].footprint.extent.size ());
    ++patches;
    for (std::size_t i = 0; i < slack[p].knife_edge.size (); ++i)
      if (slack[p].knife_edge[i])
      {
        ++flagged;
        EXPECT_EQ (slack[p].lower[i], model.patches[p].footprint.extent[i]) << "no slack at a knife edge";
        flagged_far += borderPoint (evaluator, p, i, 1.0).x () < 0.8;
      }
  }
  std::cout << "  " << model.patches.size () << " patches, " << patches << " with knife-edge angles, " << flagged
            << " angles (" << flagged_far << " with their border place at x < 0.8)" << std::endl;
  EXPECT_GE (patches, 10u);  // the edge is 2 long, patches there about 0.2 across on each side
  EXPECT_EQ (flagged_far, 0u);

  const TriangleMesh sheet =
    makeHeightFieldGrid (48, 48, 1.0, 1.0, [] (double x, double y) { return 0.1 * std::sin (3.0 * x) * std::cos (2.0 * y); });
  for (const FootprintSlack& s : footprintSlack (encode (sheet, 0.001)))
    EXPECT_TRUE (s.knife_edge.empty ());
}

TEST (FootprintSlack, SameForAnyThreadCountAndAnyRunAndRejectsBadOptions)
{
  const SparseSurfaceModel model = encode (makeTorus (48, 24, 1.0, 0.35), 0.001);
  const std::vector<FootprintSlack> one = footprintSlack (model, FootprintSlackOptions (), 1);
  const std::vector<FootprintSlack> three = footprintSlack (model, FootprintSlackOptions (), 3);
  ASSERT_EQ (one.size (), three.size ());
  for (std::size_t p = 0; p < one.size (); ++p)
  {
    EXPECT_EQ (one[p].lower, three[p].lower) << p;
    EXPECT_EQ (one[p].upper, three[p].upper) << p;
    EXPECT_EQ (one[p].knife_edge, three[p].knife_edge) << p;
  }
  // A run of the patches (a tiled file's tile) gets the slack the whole model gives it, found among the
  // patches near it only.
  const std::size_t first = one.size () / 3, count = one.size () / 4;
  const std::vector<FootprintSlack> run = footprintSlack (model, first, count);
  ASSERT_EQ (run.size (), count);
  for (std::size_t k = 0; k < count; ++k)
  {
    EXPECT_EQ (run[k].lower, one[first + k].lower) << first + k;
    EXPECT_EQ (run[k].upper, one[first + k].upper) << first + k;
    EXPECT_EQ (run[k].knife_edge, one[first + k].knife_edge) << first + k;
  }
  EXPECT_THROW (footprintSlack (model, one.size (), 1), Error);
  using Change = void (*) (FootprintSlackOptions&);
  for (Change bad : {Change ([] (FootprintSlackOptions& o) { o.max_centrality = 0.0; }),
                     Change ([] (FootprintSlackOptions& o) { o.max_centrality = 1.5; }),
                     Change ([] (FootprintSlackOptions& o) { o.inward = 1.0; }),
                     Change ([] (FootprintSlackOptions& o) { o.outward = -0.1; })})
  {
    FootprintSlackOptions options;
    bad (options);
    EXPECT_THROW (footprintSlack (model, options), Error);
  }
}

TEST (FootprintSlack, TheSameInMapCoordinates)
{
  // The model moved to map coordinates (UTM-like, where floats are 0.5 m apart) has the slack it has at the
  // origin: the ownership's float search for overlapping patches ran on world seeds and lost most pairs there
  // (a torus 0.5 m across, about the float spacing).
  const SparseSurfaceModel model = encode (makeTorus (48, 24, 0.2, 0.07), 0.001);
  SparseSurfaceModel moved = model;
  const Eigen::Vector3d offset (512000.25, 5403000.5, 101.0);
  for (PatchCode& patch : moved.patches)
    patch.origin += offset;
  const std::vector<FootprintSlack> here = footprintSlack (model), there = footprintSlack (moved);
  ASSERT_EQ (here.size (), there.size ());
  std::size_t different = 0, moving = 0;
  for (std::size_t p = 0; p < here.size (); ++p)
    for (std::size_t i = 0; i < here[p].lower.size (); ++i)
    {
      moving += here[p].lower[i] < here[p].upper[i];
      different += std::abs (here[p].lower[i] - there[p].lower[i]) > 1e-4f * here[p].upper[i] ||
                   std::abs (here[p].upper[i] - there[p].upper[i]) > 1e-4f * here[p].upper[i];
    }
  EXPECT_GT (moving, here.size ());  // the torus' borders do move
  EXPECT_EQ (different, 0u);
}

// A torus is all inside: the file with the slack spends far fewer FOOT bytes, draws every extent within two
// extent steps of its slack, and resamples as near the torus as the file without it.
TEST (FootprintSlack, SmallerFilesAsNearTheSurface)
{
  const double major = 1.0, minor = 0.35;
  const TriangleMesh torus = makeTorus (96, 48, major, minor);
  const SparseSurfaceModel model = encode (torus, 0.001);
  const std::vector<FootprintSlack> slack = footprintSlack (model);
  EXPECT_EQ (placesLostAtLowerExtents (torus, model, slack), 0u);
  ModelWriteOptions options;
  options.tolerance = 1e-4;
  const std::vector<std::uint8_t> with = encodeModel (model, options);
  // The slack found beforehand (a writer trying several options finds it once) gives the same bytes; one that is
  // not the model's is refused.
  EXPECT_EQ (encodeModel (model, options, slack), with);
  std::vector<FootprintSlack> short_slack (slack.begin (), slack.end () - 1);
  EXPECT_THROW (encodeModel (model, options, short_slack), Error);
  std::vector<FootprintSlack> wrong_angles = slack;
  wrong_angles[0].upper.pop_back ();
  EXPECT_THROW (encodeModel (model, options, wrong_angles), Error);
  options.footprint_slack = false;
  const std::vector<std::uint8_t> without = encodeModel (model, options);
  const SparseSurfaceModel a = decodeModel (with.data (), with.size ()), b = decodeModel (without.data (), without.size ());
  const ModelFileInfo info_a = inspectModel (with.data (), with.size ()), info_b = inspectModel (without.data (), without.size ());
  auto footBytes = [] (const ModelFileInfo& info) { return pcl_sparse_test::fileSection (info, "FOOT").stored_bytes; };
  std::cout << "  " << model.patches.size () << " patches: " << with.size () << " bytes (FOOT " << footBytes (info_a)
            << ") with the slack, " << without.size () << " (FOOT " << footBytes (info_b) << ") without" << std::endl;
  EXPECT_LT (footBytes (info_a), 0.8 * footBytes (info_b));
  EXPECT_LT (with.size (), without.size ());

  // The drawn extents: within 2 steps (the refinement's bound on an interval's summed deviation) of the slack.
  double extent_max = 0.0;
  for (const PatchCode& patch : model.patches)
    for (float e : patch.footprint.extent)
      extent_max = std::max (extent_max, static_cast<double> (e));
  const double step = extent_max / 15.0;
  std::size_t outside_exact = 0, angles = 0;
  for (std::size_t p = 0; p < model.patches.size (); ++p)
  {
    const std::vector<float>& exact = model.patches[p].footprint.extent;
    const std::size_t k = exact.size ();
    for (std::size_t i = 0; i < k; ++i)
    {
      const double drawn = a.patches[p].footprint.extentAt (2.0 * M_PI * static_cast<double> (i) / static_cast<double> (k));
      EXPECT_GE (drawn, slack[p].lower[i] - 2.0 * step - 1e-6) << p << " " << i;
      EXPECT_LE (drawn, slack[p].upper[i] + 2.0 * step + 1e-6) << p << " " << i;
      outside_exact += std::abs (drawn - exact[i]) > 2.0 * step;
      ++angles;
    }
  }
  std::cout << "  " << outside_exact << " of " << angles << " drawn extents more than 2 steps from the exact one" << std::endl;
  EXPECT_GT (outside_exact, 0u);  // the slack is used

  auto meanDistance = [&] (const SparseSurfaceModel& m) {
    SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (std::make_shared<const SparseSurfaceModel> (m));
    resampling.setPointCount (40000);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    double sum = 0.0;
    for (const pcl::PointNormal& q : cloud)
    {
      const double ring = std::hypot (q.x, q.y) - major;
      sum += std::abs (std::hypot (ring, static_cast<double> (q.z)) - minor);
    }
    return sum / static_cast<double> (cloud.size ());
  };
  const double distance_a = meanDistance (a), distance_b = meanDistance (b);
  std::cout << "  mean distance to the torus " << distance_a << " with the slack, " << distance_b << " without" << std::endl;
  EXPECT_LT (distance_a, 1.02 * distance_b);
}
