/// Scale invariance of the whole encoder: a mesh scaled by s gives the same model up to s, so the same
/// M, nnz, chosen atoms and RMSE / diagonal. Every threshold of the pipeline must therefore be relative
/// (to the bbox diagonal, the mean edge length, the total area ...), never an absolute epsilon.
///
/// Tolerances: for s a power of two (2^-20, 2^20), scaling is exact in floating point, and so must be
/// the result: identical M, nnz, seeds and atoms, RMSE / diagonal equal to 1e-12 relative. Any absolute
/// epsilon left in the pipeline shows here (before Harris 3D ran on the unit-diagonal mesh, 2^20 turned
/// M = 188, RMSE / diag 2.4e-4 into M = 140, 6.7e-4 on the generated mesh).
/// For s = 1e-6 and 1e6 every coordinate is rounded once (relative 1.1e-16). That reorders vertices whose
/// Harris responses tie (flat parts, where the response is rounding noise, and the cube's symmetric
/// vertices), and the greedy, sequential seed sampling then takes other seeds from there on: a
/// different but equally valid model. Measured: fandisk M 505 -> 524 (+3.8 %), RMSE / diag within 6.1 %;
/// the symmetric cube M 172 -> 155..165. So decimal scales are held to M within 12 % (measured up to 9.9 %,
/// the cube at 1e6), nnz within 2.5 % (measured up to 1.6 %, fandisk at 1e-6: 4520 -> 4594; the cube's
/// stays 1140) and RMSE / diagonal within 9 % (measured up to 6.1 %, fandisk at 1e-6).

#include "robustness_cases.h"
#include "shared_data.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

using namespace pcl_sparse;

namespace
{
  struct Encoded
  {
    ModelStatistics stats;
    std::vector<std::vector<int>> atoms;  ///< per patch
    std::vector<Eigen::Vector3d> origins;
  };

  /// \a scale as a trace names it: std::to_string wrote 2^-20 and 1e-6 alike as "0.000001", 1e-31 as "0.000000".
  std::string
  scaleName (double scale)
  {
    std::ostringstream out;
    out << "scaled by " << scale;
    return out.str ();
  }

  Encoded
  encode (const TriangleMesh& mesh)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (std::make_shared<TriangleMesh> (mesh));
    // The paper's atoms: the tolerances below were measured with them. With the dct atoms (the default) the
    // exact scales give the identical model too, but at x1e-6 the 4 % of patches that tie-breaking moves
    // change the RMSE by 22 % on fandisk (dct codes each patch closer, so its layout matters more).
    encoder.setOptions (encoderPresetOptions (EncoderPreset::Paper));
    SparseSurfaceModel model;
    encoder.compute (model);
    Encoded e;
    e.stats = model.statistics (mesh.vertices);
    for (const PatchCode& p : model.patches)
    {
      e.atoms.push_back (p.atoms);
      e.origins.push_back (p.origin);
    }
    return e;
  }

  /// A mesh with sharp edges, corners, curved parts and a boundary: a cube with a bumpy height field.
  TriangleMesh
  featureMesh ()
  {
    TriangleMesh mesh = makeCube (10, 1.0);
    TriangleMesh bumps = makeHeightFieldGrid (24, 24, 1.0, 1.0, [] (double x, double y) {
      return 2.0 + 0.25 * std::sin (3.0 * x) * std::cos (2.0 * y);
    });
    appendMesh (mesh, bumps);
    return mesh;
  }

  /// \a max_rmse_over_diagonal: a bound on the unscaled model's RMSE / diagonal, so that a model that is
  /// equally bad at every scale (no atom, NaN errors) does not pass as scale invariant.
  void
  expectSameModel (const TriangleMesh& mesh, const std::string& name, double max_rmse_over_diagonal)
  {
    const Encoded reference = encode (mesh);
    ASSERT_GT (reference.stats.num_patches, 0u);
    ASSERT_GT (reference.stats.num_nonzeros, reference.stats.num_patches);
    EXPECT_EQ (reference.stats.uncovered, 0u);
    ASSERT_GT (reference.stats.rmse_over_diagonal, 0.0);  // false for NaN
    EXPECT_LT (reference.stats.rmse_over_diagonal, max_rmse_over_diagonal);
    ASSERT_GT (reference.stats.max_error, reference.stats.rmse);
    std::cout << name << ": M " << reference.stats.num_patches << ", nnz " << reference.stats.num_nonzeros
              << ", RMSE/diag " << reference.stats.rmse_over_diagonal << std::endl;
    for (const double scale : {std::ldexp (1.0, -20), std::ldexp (1.0, 20), 1e-6, 1e6})
    {
      SCOPED_TRACE (name + " " + scaleName (scale));
      int exponent = 0;
      const bool exact = std::frexp (scale, &exponent) == 0.5;
      const Encoded e = encode (robustness::scaled (mesh, scale));
      std::cout << "  x " << scale << ": M " << e.stats.num_patches << ", nnz " << e.stats.num_nonzeros
                << ", RMSE/diag " << e.stats.rmse_over_diagonal << std::endl;
      if (exact)
      {
        EXPECT_EQ (e.stats.num_patches, reference.stats.num_patches);
        EXPECT_EQ (e.stats.num_nonzeros, reference.stats.num_nonzeros);
        EXPECT_EQ (e.stats.uncovered, reference.stats.uncovered);
        EXPECT_NEAR (e.stats.rmse_over_diagonal, reference.stats.rmse_over_diagonal,
                     1e-12 * reference.stats.rmse_over_diagonal);
        EXPECT_NEAR (e.stats.rmse / scale, reference.stats.rmse, 1e-12 * reference.stats.rmse);
        EXPECT_NEAR (e.stats.max_error / scale, reference.stats.max_error, 1e-12 * reference.stats.max_error);
      }
      else
      {
        EXPECT_NEAR (static_cast<double> (e.stats.num_patches), static_cast<double> (reference.stats.num_patches),
                     0.12 * reference.stats.num_patches);
        EXPECT_NEAR (static_cast<double> (e.stats.num_nonzeros), static_cast<double> (reference.stats.num_nonzeros),
                     0.025 * reference.stats.num_nonzeros);
        EXPECT_EQ (e.stats.uncovered, reference.stats.uncovered);
        EXPECT_NEAR (e.stats.rmse_over_diagonal, reference.stats.rmse_over_diagonal,
                     0.09 * reference.stats.rmse_over_diagonal);
      }
      if (exact && e.atoms.size () == reference.atoms.size ())
      {
        std::size_t different = 0;
        for (std::size_t p = 0; p < e.atoms.size (); ++p)
          different += e.atoms[p] != reference.atoms[p] || e.origins[p] != reference.origins[p] * scale;
        EXPECT_EQ (different, 0u) << "patches whose seed or atoms differ";
      }
    }
  }
} // namespace

TEST (ScaleInvariance, GeneratedMeshWithFeatures)
{
  expectSameModel (featureMesh (), "cube + bumpy sheet", 3.6e-4);  // measured RMSE / diagonal 2.37e-4
}

TEST (ScaleInvariance, Fandisk)
{
  const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/fandisk.off";
  PCL_SPARSE_NEED_SHARED_FILE (path);
  expectSameModel (loadTriangleMesh (path), "fandisk", 4.0e-4);  // measured RMSE / diagonal 2.65e-4
}

/// Beyond the scales the pipeline computes in, a mesh is refused with the reason instead of coded badly:
/// fandisk scaled by 1e100 or 1e-150 gave 5x its patches and no atom, without a word. Near the limits the
/// exact (power-of-two) scales still give the same model.
TEST (ScaleInvariance, ScalesOutsideTheRangeAreRefused)
{
  const TriangleMesh mesh = featureMesh ();
  for (const double scale : {1e31, 1e100, 1e200, 1e-31, 1e-150, 1e-200})
  {
    SCOPED_TRACE (scaleName (scale));
    try
    {
      encode (robustness::scaled (mesh, scale));
      ADD_FAILURE () << "accepted";
    }
    catch (const pcl_sparse::Error& e)
    {
      const std::string what = e.what ();
      EXPECT_NE (what.find (scale > 1.0 ? "beyond the 1e30" : "under 1e-30"), std::string::npos) << what;
      EXPECT_NE (what.find ("rescale the input"), std::string::npos) << what;
    }
  }
  const Encoded reference = encode (mesh);
  ASSERT_GT (reference.stats.num_patches, 0u);
  ASSERT_GT (reference.stats.rmse_over_diagonal, 0.0);
  ASSERT_GT (reference.stats.max_error, reference.stats.rmse);  // both positive and finite
  for (const double scale : {std::ldexp (1.0, 95), std::ldexp (1.0, -95)})  // 4e28, 2.5e-29
  {
    SCOPED_TRACE (scaleName (scale));
    const Encoded e = encode (robustness::scaled (mesh, scale));
    EXPECT_EQ (e.stats.num_patches, reference.stats.num_patches);
    EXPECT_EQ (e.stats.num_nonzeros, reference.stats.num_nonzeros);
    EXPECT_EQ (e.stats.uncovered, reference.stats.uncovered);
    EXPECT_TRUE (e.atoms == reference.atoms) << "other atoms";
    EXPECT_NEAR (e.stats.rmse_over_diagonal, reference.stats.rmse_over_diagonal, 1e-12 * reference.stats.rmse_over_diagonal);
    // The errors themselves scale with the mesh (a ratio right for wrong reasons, both 0 say, would pass above),
    // and the seeds are the same places, scaled exactly.
    EXPECT_NEAR (e.stats.rmse / scale, reference.stats.rmse, 1e-12 * reference.stats.rmse);
    EXPECT_NEAR (e.stats.max_error / scale, reference.stats.max_error, 1e-12 * reference.stats.max_error);
    ASSERT_EQ (e.origins.size (), reference.origins.size ());
    std::size_t moved = 0;
    for (std::size_t p = 0; p < e.origins.size (); ++p)
      moved += e.origins[p] != reference.origins[p] * scale;
    EXPECT_EQ (moved, 0u) << "patches seeded elsewhere";
  }
}
