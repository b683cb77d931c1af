#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/coding/patch_coder.h>
#include <pcl_sparse/coding/patch_footprint.h>
#include <pcl_sparse/coding/patch_samples.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/splitmix64.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_topology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// The whole mesh as one patch with the identity frame at the origin and the given radius.
  Patch
  wholeMeshPatch (const TriangleMesh& mesh, double radius)
  {
    Patch patch;
    patch.seed = 0;
    patch.radius = radius;
    for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
    {
      patch.vertices.push_back (static_cast<int> (v));
      patch.local.push_back (patch.toLocal (mesh.vertices[v]));
    }
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
      patch.triangles.push_back (static_cast<int> (f));
    return patch;
  }

  /// makePlaneGrid (20) ([-1, 1]^2) without the triangles whose centroid has x0 < x < x1, |y| < y_max.
  TriangleMesh
  gridWithHole (double x0, double x1, double y_max)
  {
    const TriangleMesh grid = makePlaneGrid (20, 1.0);
    TriangleMesh mesh;
    mesh.vertices = grid.vertices;
    for (const Eigen::Vector3i& t : grid.triangles)
    {
      const Eigen::Vector3d c = (grid.vertices[t[0]] + grid.vertices[t[1]] + grid.vertices[t[2]]) / 3.0;
      if (!(c.x () > x0 && c.x () < x1 && std::abs (c.y ()) < y_max))
        mesh.triangles.push_back (t);
    }
    EXPECT_LT (mesh.triangles.size (), grid.triangles.size ());
    return mesh;
  }

  double
  paraboloid (double x, double y)
  {
    return 0.3 * x * x - 0.2 * y * y + 0.1 * x * y;
  }
} // namespace

TEST (PatchSamples, SpacingOfRegularGrid)
{
  // 10 x 10 cells on [-1, 1]^2: edges 0.2 (axis) and 0.2 sqrt 2 (diagonals); radius 2 halves them. mu is
  // the median over the vertices of their mean ring-edge length: 60 of the 121 vertices have axis edges
  // only (0.2), and the median one, the 61st, is a corner with two axis edges and a diagonal.
  const TriangleMesh mesh = makePlaneGrid (10, 1.0);
  const MeshTopology topology = buildMeshTopology (mesh);
  const Patch patch = wholeMeshPatch (mesh, 2.0);
  const double mu = patchSampleSpacing (patch, mesh, topology);
  EXPECT_DOUBLE_EQ (patchSampleSpacing (patch, meanRingEdgeLengths (mesh, topology)), mu);
  EXPECT_NEAR (mu, (0.2 + 0.2 + 0.2 * std::sqrt (2.0)) / 3.0 / 2.0, 1e-12);
}

TEST (PatchSamples, ExtraSamplesLieOnTheSurfaceAndAreDeterministic)
{
  const TriangleMesh mesh = makeHeightFieldGrid (6, 6, 1.0, 1.0, paraboloid);
  const Patch patch = wholeMeshPatch (mesh, 1.0);
  const std::vector<Eigen::Vector3d> a = drawPatchSurfaceSamples (patch, mesh, 500, 7);
  const std::vector<Eigen::Vector3d> b = drawPatchSurfaceSamples (patch, mesh, 500, 7);
  const std::vector<Eigen::Vector3d> c = drawPatchSurfaceSamples (patch, mesh, 500, 8);
  ASSERT_EQ (a.size (), 500u);
  EXPECT_EQ (a, b);
  EXPECT_NE (a, c);
  // Uniform by area over [-1, 1]^2: mean near 0, every point inside, heights close to the surface
  // (the piecewise-linear interpolant of a quadric on a 1/3 grid: error < h^2 max|curvature| / 8).
  Eigen::Vector2d mean = Eigen::Vector2d::Zero ();
  for (const Eigen::Vector3d& p : a)
  {
    EXPECT_LE (std::abs (p.x ()), 1.0 + 1e-12);
    EXPECT_LE (std::abs (p.y ()), 1.0 + 1e-12);
    EXPECT_NEAR (p.z (), paraboloid (p.x (), p.y ()), 0.05);
    mean += p.head<2> () / 500.0;
  }
  EXPECT_LT (mean.norm (), 0.1);
  EXPECT_TRUE (drawPatchSurfaceSamples (patch, mesh, 0, 1).empty ());
  EXPECT_NE (mixSeed (1, 2), mixSeed (1, 3));
  EXPECT_NE (mixSeed (1, 2), mixSeed (2, 2));
}

TEST (Splitmix64, ReferenceStream)
{
  // splitmix64's published stream from state 0 (the state steps by the golden gamma before each output):
  // the library's seeded random numbers are these on every platform.
  constexpr std::uint64_t gamma = 0x9e3779b97f4a7c15ULL;
  EXPECT_EQ (splitmix64 (0), 0xe220a8397b1dcdafULL);
  EXPECT_EQ (splitmix64 (gamma), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ (splitmix64 (2 * gamma), 0x06c45d188009454fULL);
  static_assert (splitmix64 (0) == 0xe220a8397b1dcdafULL, "usable in constant expressions");
}

TEST (PatchFootprint, CoversEveryProjectedTriangle)
{
  // An off-centre, irregular patch: a disk shifted so the seed is not at the centre.
  TriangleMesh mesh = makeDisk (6, 1.0);
  for (Eigen::Vector3d& v : mesh.vertices)
    v += Eigen::Vector3d (0.35, -0.2, 0.0);
  const Patch patch = wholeMeshPatch (mesh, 1.5);
  const PatchFootprint footprint = computePatchFootprint (patch, mesh, 16);
  ASSERT_EQ (footprint.extent.size (), 16u);
  std::mt19937 rng (3);
  std::uniform_real_distribution<double> u (0.0, 1.0);
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int s = 0; s < 30; ++s)
    {
      double a = u (rng), b = u (rng);
      if (a + b > 1.0)
      {
        a = 1.0 - a;
        b = 1.0 - b;
      }
      const Eigen::Vector3d p =
          (1.0 - a - b) * patch.local[t[0]] + a * patch.local[t[1]] + b * patch.local[t[2]];
      EXPECT_TRUE (footprint.contains (p.x (), p.y ()));
    }
  for (const Eigen::Vector3d& p : patch.local)
    EXPECT_TRUE (footprint.contains (p.x (), p.y ()));
  // Tight: the disk of radius 1 / 1.5 centred at (0.35, -0.2) / 1.5 has extent at angle 0 about
  // 0.233 + sqrt(0.444 - 0.0178) = 0.886; and points well outside are refused.
  EXPECT_NEAR (footprint.extentAt (0.0), 0.886, 0.05);
  EXPECT_FALSE (footprint.contains (-0.9, 0.0));
  EXPECT_FALSE (footprint.contains (0.0, 0.9));
}

// Scans: a patch that grew around a hole must not cover it (clip_at_first_exit).
TEST (PatchFootprint, FirstExitClipsAHoleBesideTheSeed)
{
  const TriangleMesh mesh = gridWithHole (0.4, 0.8, 0.25);  // a hole on the +x side of the seed
  const Patch patch = wholeMeshPatch (mesh, 1.5);  // seed at the origin, inside the triangles
  const PatchFootprint exact = computePatchFootprint (patch, mesh, 64);
  const PatchFootprint clipped = computePatchFootprint (patch, mesh, 64, true);
  // Along +x the triangles resume beyond the hole (the square ends at 1): the exact cover reaches
  // 1 / 1.5, the clipped one stops at the hole's near rim, x = 0.4 / 1.5 = 0.267.
  EXPECT_NEAR (exact.extentAt (0.0), 1.0 / 1.5, 0.01);
  EXPECT_NEAR (clipped.extentAt (0.0), 0.4 / 1.5, 0.01);
  EXPECT_FALSE (clipped.contains (0.6 / 1.5, 0.0));  // the hole
  EXPECT_TRUE (exact.contains (0.6 / 1.5, 0.0));
  // Where no hole lies between the seed and the border, only the exact cover's margin between two rays
  // goes (the exit is taken on the rays themselves: 0.6667 against 0.6699 here).
  EXPECT_NEAR (clipped.extentAt (M_PI / 2.0), exact.extentAt (M_PI / 2.0), 0.005);
  EXPECT_NEAR (clipped.extentAt (M_PI), exact.extentAt (M_PI), 0.005);
}

// A gap narrower than 3 edge lengths (a missing triangle of a scan's triangulation) does not cut the
// footprint: clipping there would open holes between patches.
TEST (PatchFootprint, FirstExitCrossesAMissingTriangle)
{
  const TriangleMesh mesh = gridWithHole (0.4, 0.5, 0.1);
  const Patch patch = wholeMeshPatch (mesh, 1.5);
  EXPECT_NEAR (computePatchFootprint (patch, mesh, 64, true).extentAt (0.0), 1.0 / 1.5, 0.01);
}

TEST (PatchCoder, CodesAParaboloidPatch)
{
  // Principal axes along x and y, as in a patch's jet frame: the even cosines fit it closely.
  const auto even = [] (double x, double y) { return 0.3 * x * x - 0.2 * y * y; };
  const TriangleMesh mesh = makeHeightFieldGrid (8, 8, 1.0, 1.0, even);
  const MeshTopology topology = buildMeshTopology (mesh);
  const Patch patch = wholeMeshPatch (mesh, 1.5);
  const CosineDictionary dictionary (12);
  SparseCodingOptions options;
  options.radius_on_grid = false;  // the patch's radius, 1.5 (on the grid 1.509: a relative residual of 1.05 %)
  PatchCodingInfo info;
  const PatchCode code = codePatch (patch, 0, mesh, meanRingEdgeLengths (mesh, topology), dictionary, options, &info);
  // 81 vertices, and 0.5 extra samples per triangle (128 triangles: triangle_samples) inside them.
  EXPECT_EQ (info.num_samples, 81 + 64);
  EXPECT_LE (code.atoms.size (), 12u);
  EXPECT_EQ (code.atoms.size (), code.coefficients.size ());
  EXPECT_LE (info.relative_residual, options.tolerance);
  EXPECT_EQ (code.vertices.size (), 81u);
  EXPECT_EQ (code.vertex_xy.size (), 81u);
  ASSERT_GE (code.atoms.size (), 2u);  // a saddle: the constant alone does not fit it
  // The code itself, evaluated at each vertex's place and mapped to the world, lands on the vertex: the
  // heights are 0.3 at most and the tolerance 1 % of their norm (measured 1.3e-3).
  double worst = 0.0;
  for (std::size_t i = 0; i < code.vertices.size (); ++i)
  {
    const Eigen::Vector2d& xy = code.vertex_xy[i];
    const double h = dictionary.evaluateCodeValue (code.atoms, code.coefficients, xy.x (), xy.y ());
    worst = std::max (worst, (code.toWorld (Eigen::Vector3d (xy.x (), xy.y (), h)) - mesh.vertices[code.vertices[i]]).norm ());
  }
  EXPECT_LT (worst, 3e-3);
  // Cap: mu ~ 0.25 / 1.5 (mean of 0.25 and 0.35 edges), so with f = 0.5 no atom above max(i, j) ~ 23;
  // every selected atom satisfies it.
  for (int a : code.atoms)
    EXPECT_GT (dictionary.wavelength (a) / 2.0, 0.5 * info.spacing);
  // Small patch: extra samples up to m_min.
  const TriangleMesh small = makeHeightFieldGrid (2, 2, 1.0, 1.0, even);
  const MeshTopology small_topology = buildMeshTopology (small);
  codePatch (wholeMeshPatch (small, 1.5), 3, small, meanRingEdgeLengths (small, small_topology), dictionary, options, &info);
  EXPECT_EQ (info.num_samples, 64);
  options.min_samples = 128;
  codePatch (wholeMeshPatch (small, 1.5), 3, small, meanRingEdgeLengths (small, small_topology), dictionary, options, &info);
  EXPECT_EQ (info.num_samples, 128);
}

// A seed on the patch's border (a corner here, as at a crease or an open border): the rays pointing away
// from the patch cross no border edge, and clip_at_border must pull them in like the others. They kept the
// sector maxima: the footprint reached a whole sector beyond the border (area 0.58 for this 0.5 triangle).
TEST (PatchFootprint, BorderClipPullsInTheRaysOutsideTheTriangles)
{
  TriangleMesh mesh;
  mesh.vertices = {Eigen::Vector3d (0.0, 0.0, 0.0), Eigen::Vector3d (1.0, 0.0, 0.0), Eigen::Vector3d (0.0, 1.0, 0.0)};
  mesh.triangles = {Eigen::Vector3i (0, 1, 2)};
  const Patch patch = wholeMeshPatch (mesh, 1.0);  // seed at the corner (0, 0)
  const PatchFootprint footprint = computePatchFootprint (patch, mesh, 64, false, true);
  EXPECT_FALSE (footprint.contains (-0.03, 0.9));  // beyond the edge x = 0
  EXPECT_FALSE (footprint.contains (0.9, -0.03));  // beyond the edge y = 0
  double area = 0.0;
  const int steps = 20000;
  for (int i = 0; i < steps; ++i)
  {
    const double r = footprint.extentAt (2.0 * M_PI * (i + 0.5) / steps);
    area += 0.5 * r * r * 2.0 * M_PI / steps;
  }
  EXPECT_LT (area, 0.54);
  // Still a cover of the triangle.
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; i + j <= 20; ++j)
      EXPECT_TRUE (footprint.contains (i / 20.0, j / 20.0)) << i << " " << j;
}

// Three angles (the smallest footprint): a border edge from sector 0 to sector 2 (65 to 242 degrees, under 180)
// crosses rays 1 and 2. Its arc's first ray was also its last, so only ray 0 was tried: ray 1 crossed no
// border edge, was clipped to the seed, and the footprint lost the sliver of the triangle along 120 degrees.
TEST (PatchFootprint, ThreeAnglesBorderEdgeAcrossAllSectors)
{
  auto at = [] (double degrees, double r) {
    return Eigen::Vector3d (r * std::cos (degrees * M_PI / 180.0), r * std::sin (degrees * M_PI / 180.0), 0.0);
  };
  TriangleMesh mesh;
  mesh.vertices = {Eigen::Vector3d::Zero (), at (65.0, 1.0), at (242.0, 1.0), at (0.0, 3.0)};
  mesh.triangles = {Eigen::Vector3i (0, 1, 2), Eigen::Vector3i (0, 2, 3), Eigen::Vector3i (0, 3, 1)};
  const Patch patch = wholeMeshPatch (mesh, 1.0);
  const PatchFootprint footprint = computePatchFootprint (patch, mesh, 3, false, true);
  // The chord from 65 to 242 degrees passes 0.026 from the seed; along 120 degrees it is 0.031 away.
  const double chord = std::cos (88.5 * M_PI / 180.0) / std::cos ((153.5 - 120.0) * M_PI / 180.0);
  EXPECT_NEAR (footprint.extentAt (2.0 * M_PI / 3.0), chord, 1e-4);
  for (const double r : {0.005, 0.015, 0.025, 0.03})
    EXPECT_TRUE (footprint.contains (at (120.0, r).x (), at (120.0, r).y ())) << r;
}

// The compression bound cuts codes to fewer atoms: truncatePatchCode gives, bit for bit, what coding the
// patch again with that L gives (OMP's first k steps do not depend on L), for every k.
TEST (PatchCoder, TruncatedCodeIsTheCodeWithFewerAtoms)
{
  const auto bumpy = [] (double x, double y) { return 0.2 * std::cos (3.0 * x) * std::cos (5.0 * y) + 0.1 * x * x * y * y; };
  const TriangleMesh mesh = makeHeightFieldGrid (10, 10, 1.0, 1.0, bumpy);
  const MeshTopology topology = buildMeshTopology (mesh);
  const Patch patch = wholeMeshPatch (mesh, 1.5);
  const std::vector<double> rings = meanRingEdgeLengths (mesh, topology);
  const CosineDictionary dictionary (12);
  SparseCodingOptions options;
  options.tolerance = 1e-9;  // all 12 atoms
  PatchCodingInfo full_info;
  const PatchCode full = codePatch (patch, 5, mesh, rings, dictionary, options, &full_info);
  ASSERT_EQ (full.atoms.size (), 12u);
  ASSERT_EQ (full_info.prefix_coefficients.size (), 12u * 13u / 2u);
  for (int k = 0; k <= 13; ++k)
  {
    PatchCode cut = full;
    PatchCodingInfo cut_info = full_info;
    truncatePatchCode (k, cut, cut_info);
    SparseCodingOptions fewer = options;
    fewer.max_atoms = std::clamp (k, 1, 12);
    PatchCodingInfo info;
    PatchCode again = codePatch (patch, 5, mesh, rings, dictionary, fewer, &info);
    if (k == 0)  // codePatch needs L >= 1: the empty code is the first atom's prefix
    {
      again.atoms.clear ();
      again.coefficients.clear ();
      info.residual_norms.resize (1);
      info.prefix_coefficients.clear ();
      info.relative_residual = 1.0;
    }
    EXPECT_EQ (cut.atoms, again.atoms) << k;
    EXPECT_EQ (cut.coefficients, again.coefficients) << k;  // exact: the same arithmetic
    EXPECT_EQ (cut_info.residual_norms, info.residual_norms) << k;
    EXPECT_EQ (cut_info.prefix_coefficients, info.prefix_coefficients) << k;
    EXPECT_EQ (cut_info.relative_residual, info.relative_residual) << k;
  }
  PatchCodingInfo none;
  PatchCode code = full;
  EXPECT_THROW (truncatePatchCode (3, code, none), Error);  // no prefixes to cut to
}

namespace
{
  /// The triangles of \a mesh whose centroid lies within \a radius of \a centre (in x, y), as a patch with
  /// the identity frame at \a centre and radius 1 (local coordinates are world offsets).
  Patch
  discPatch (const TriangleMesh& mesh, const Eigen::Vector3d& centre, double radius)
  {
    Patch patch;
    patch.origin = centre;
    patch.radius = 1.0;
    std::vector<int> local (mesh.vertices.size (), -1);
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    {
      const Eigen::Vector3i& t = mesh.triangles[f];
      const Eigen::Vector3d c = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
      if ((c - centre).head<2> ().norm () > radius)
        continue;
      patch.triangles.push_back (static_cast<int> (f));
      for (int k = 0; k < 3; ++k)
        if (local[t[k]] < 0)
        {
          local[t[k]] = static_cast<int> (patch.vertices.size ());
          patch.vertices.push_back (t[k]);
          patch.local.push_back (patch.toLocal (mesh.vertices[t[k]]));
        }
    }
    return patch;
  }

  /// The footprints of \a patch clipped at its border, without and with the reach over smooth borders.
  std::pair<PatchFootprint, PatchFootprint>
  clippedAndReached (const Patch& patch, const TriangleMesh& mesh, const MeshTopology& topology)
  {
    return {computePatchFootprint (patch, mesh, 64, false, true),
            computePatchFootprint (patch, mesh, 64, false, true, 17.0, &topology, 20.0)};
  }
} // namespace

// Inside a plane the clipped footprint follows the zigzag of the patch's outer corners; the reach raises the
// extents between them (never lowers one, never by more than half the median edge, 0.05 here), and without a
// topology or with no reach nothing changes.
TEST (PatchFootprint, ReachesAlongSmoothBordersByAtMostHalfAnEdge)
{
  const TriangleMesh mesh = makePlaneGrid (20);  // edges 0.1 and diagonals 0.14
  const MeshTopology topology = buildMeshTopology (mesh);
  const Patch patch = discPatch (mesh, Eigen::Vector3d (0.0, 0.0, 0.0), 0.45);
  const auto [clipped, reached] = clippedAndReached (patch, mesh, topology);
  ASSERT_EQ (reached.extent.size (), 64u);
  int raised = 0;
  for (std::size_t k = 0; k < 64; ++k)
  {
    EXPECT_GE (reached.extent[k], clipped.extent[k]) << k;
    EXPECT_LE (reached.extent[k], clipped.extent[k] + 0.05 + 1e-6) << k;
    raised += reached.extent[k] > clipped.extent[k] + 0.01;
  }
  EXPECT_GE (raised, 24);  // measured 48 of the 64
  EXPECT_EQ (computePatchFootprint (patch, mesh, 64, false, true, 17.0, nullptr).extent, clipped.extent);
  EXPECT_EQ (computePatchFootprint (patch, mesh, 64, false, true, 0.0, &topology).extent, clipped.extent);
  EXPECT_EQ (computePatchFootprint (patch, mesh, 64, false, false, 17.0, &topology).extent,
             computePatchFootprint (patch, mesh, 64).extent);  // no clip, no reach: the sector maxima
}

// Where the patch meets the mesh's open border (x = 1) or a fold (faces tilted 30 degrees from its normal past
// x = 0.5), the rays leaving across them keep their clipped extents; those leaving into the plane reach.
TEST (PatchFootprint, StaysClippedAtOpenBordersAndFolds)
{
  const TriangleMesh plane = makePlaneGrid (20);
  const MeshTopology plane_topology = buildMeshTopology (plane);
  const Patch near_border = discPatch (plane, Eigen::Vector3d (0.8, 0.0, 0.0), 0.45);
  const auto [clipped, reached] = clippedAndReached (near_border, plane, plane_topology);
  // Rays within 60 degrees of +x leave across the border x = 1 (0.2 away, within the disc of 0.45).
  int raised_elsewhere = 0;
  for (std::size_t k = 0; k < 64; ++k)
  {
    const double angle = 2.0 * M_PI * static_cast<double> (k) / 64.0;
    if (std::cos (angle) > 0.5)
      EXPECT_FLOAT_EQ (reached.extent[k], clipped.extent[k]) << k;
    else
      raised_elsewhere += reached.extent[k] > clipped.extent[k] + 0.01;
  }
  EXPECT_GE (raised_elsewhere, 4);

  const double slope = std::tan (30.0 * M_PI / 180.0);
  const TriangleMesh folded =
    makeHeightFieldGrid (20, 20, 1.0, 1.0, [slope] (double x, double) { return x > 0.5 ? slope * (x - 0.5) : 0.0; });
  const MeshTopology folded_topology = buildMeshTopology (folded);
  const Patch before_fold = discPatch (folded, Eigen::Vector3d (0.2, 0.0, 0.0), 0.32);
  const auto [clipped_fold, reached_fold] = clippedAndReached (before_fold, folded, folded_topology);
  for (std::size_t k = 0; k < 64; ++k)
    if (std::cos (2.0 * M_PI * static_cast<double> (k) / 64.0) > 0.8)  // across the fold at x = 0.5
      EXPECT_FLOAT_EQ (reached_fold.extent[k], clipped_fold.extent[k]) << k;
}
