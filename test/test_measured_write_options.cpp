// The default file chosen by measuring candidate files against the mesh (encoder/measured_write_options.h).
#include "model_helpers.h"
#include "shared_data.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/measured_write_options.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_sparse;
using namespace pcl_sparse_test;

namespace
{
  /// \a model written with \a options and read back.
  SparseSurfaceModel::ConstPtr
  roundTrip (const SparseSurfaceModel& model, const ModelWriteOptions& options)
  {
    const std::vector<std::uint8_t> bytes = encodeModel (model, options);
    return std::make_shared<const SparseSurfaceModel> (decodeModel (bytes.data (), bytes.size ()));
  }
} // namespace

TEST (MeasuredWriteOptions, ChoosesTheSmallestFileWithinTheAllowance)
{
  const auto sphere = std::make_shared<const TriangleMesh> (makeIcosphere (3));
  const SparseSurfaceModel::Ptr model = encodeMesh (sphere);
  const ModelWriteOptions start = boundWriteOptions (*model, sphere->vertices);
  const MeasuredWriteChoice choice = measuredWriteOptions (*model, *sphere, start);
  EXPECT_EQ (choice.start_bytes, encodeModel (*model, start).size ());
  EXPECT_EQ (choice.bytes, encodeModel (*model, choice.options).size ());
  EXPECT_EQ (choice.file, encodeModel (*model, choice.options));  // the bytes to write, as saveModel encodes them
  EXPECT_GT (choice.lossless_distance, 0.0);
  EXPECT_GE (choice.measured, 1u);
  EXPECT_LE (choice.distance, 1.08 * choice.lossless_distance);
  // With no allowance to speak of, every file is measured and fails, and the nearest wins.
  MeasuredWriteOptions strict;
  strict.max_increase = 1e-9;
  strict.confirm_points = 0;  // no second look with more points either
  const MeasuredWriteChoice nearest = measuredWriteOptions (*model, *sphere, start, strict);
  EXPECT_EQ (nearest.measured, strict.candidates.size () + 1);
  EXPECT_LE (nearest.distance, choice.distance);
  EXPECT_EQ (nearest.lossless_distance, choice.lossless_distance);
  EXPECT_GE (nearest.bytes, choice.bytes);
  // The same choice on one thread as on two.
  MeasuredWriteOptions one_thread, two_threads;
  one_thread.num_threads = 1;
  two_threads.num_threads = 2;
  const MeasuredWriteChoice a = measuredWriteOptions (*model, *sphere, start, one_thread);
  const MeasuredWriteChoice b = measuredWriteOptions (*model, *sphere, start, two_threads);
  EXPECT_EQ (a.bytes, b.bytes);
  EXPECT_EQ (a.distance, b.distance);
  EXPECT_EQ (a.lossless_distance, b.lossless_distance);
}

TEST (MeasuredWriteOptions, ReportsProgressPerMeasurement)
{
  const auto sphere = std::make_shared<const TriangleMesh> (makeIcosphere (3));
  const SparseSurfaceModel::Ptr model = encodeMesh (sphere);
  const ModelWriteOptions start = boundWriteOptions (*model, sphere->vertices);
  MeasuredWriteOptions strict;  // every file measured, nothing confirmed: the most the first pass can take
  strict.max_increase = 1e-9;
  strict.confirm_points = 0;
  for (const MeasuredWriteOptions& options : {MeasuredWriteOptions (), strict})
  {
    std::vector<double> fractions;
    const MeasuredWriteChoice choice = measuredWriteOptions (*model, *sphere, start, options, [&] (const std::string& stage, double f) {
      EXPECT_EQ (stage, "file");
      fractions.push_back (f);
    });
    // 0 first, then one per measurement (the lossless model, each file, with a confirmation the lossless model
    // again and each confirmed file), then 1; never backwards.
    const std::size_t lossless = 1 + (choice.confirmed > 0 ? 1 : 0);
    ASSERT_EQ (fractions.size (), 2 + lossless + choice.measured + choice.confirmed);
    EXPECT_EQ (fractions.front (), 0.0);
    EXPECT_EQ (fractions.back (), 1.0);
    for (std::size_t i = 1; i < fractions.size (); ++i)
      EXPECT_GE (fractions[i], fractions[i - 1]);
    EXPECT_GT (fractions[1], 0.0);
  }
  // The strict run measured everything there was to measure without a confirmation: its last measurement is 1.
  std::vector<double> fractions;
  measuredWriteOptions (*model, *sphere, start, strict, [&] (const std::string&, double f) { fractions.push_back (f); });
  EXPECT_EQ (fractions[fractions.size () - 2], 1.0);
}

TEST (MeasuredWriteOptions, BadOptionsAreRefused)
{
  const auto sphere = std::make_shared<const TriangleMesh> (makeIcosphere (2));
  const SparseSurfaceModel::Ptr model = encodeMesh (sphere);
  ModelWriteOptions lossless;
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, lossless), Error);
  const ModelWriteOptions start = boundWriteOptions (*model, sphere->vertices);
  for (double bad : {0.0, -0.1, 1.5, std::nan ("")})
  {
    MeasuredWriteOptions options;
    options.max_increase = bad;
    EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, options), Error) << bad;
  }
  MeasuredWriteOptions few;
  few.points = 10;
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, few), Error);
  MeasuredWriteOptions confirm;
  confirm.confirm_points = 10;
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, confirm), Error);
  confirm = MeasuredWriteOptions ();
  confirm.confirm_band = 0.5 * confirm.max_increase;
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, confirm), Error);
  confirm = MeasuredWriteOptions ();
  confirm.confirm_max_increase = 0.0;
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, confirm), Error);
  MeasuredWriteOptions bad_candidate;
  bad_candidate.candidates = {{0.0, 0, 2.0}};
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, bad_candidate), Error);
  bad_candidate.candidates = {{2.0, -7, 2.0}};
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, bad_candidate), Error);
  bad_candidate.candidates = {{2.0, -1, -1.0}};
  EXPECT_THROW (measuredWriteOptions (*model, *sphere, start, bad_candidate), Error);
}

// A surface the yardstick refuses (no triangle, a corner not finite) is an error, not a crash, though the
// yardstick is built on another thread than the candidate files (measured_write_options.cpp).
TEST (MeasuredWriteOptions, RefusedSurfaceIsAnErrorOnAnyThreadCount)
{
  const auto sphere = std::make_shared<const TriangleMesh> (makeIcosphere (2));
  const SparseSurfaceModel::Ptr model = encodeMesh (sphere);
  const ModelWriteOptions start = boundWriteOptions (*model, sphere->vertices);
  TriangleMesh broken = *sphere;
  broken.vertices[3].y () = std::numeric_limits<double>::infinity ();
  for (const int threads : {1, 2})
  {
    MeasuredWriteOptions options;
    options.num_threads = threads;
    EXPECT_THROW (measuredWriteOptions (*model, TriangleMesh (), start, options), Error) << threads;
    try
    {
      measuredWriteOptions (*model, broken, start, options);
      ADD_FAILURE () << "a non-finite corner was measured against, threads " << threads;
    }
    catch (const Error& e)
    {
      EXPECT_NE (std::string (e.what ()).find ("non-finite"), std::string::npos) << e.what ();
    }
  }
}

// On a real mesh the measured file is smaller than the bound's, and bench_format's Chamfer distance (200k points a
// side) of it stays within issue 13's 10 % of the lossless model's; wingnut, a CAD part whose coarser files cost
// more than that, keeps a file within it too.
TEST (MeasuredWriteOptions, SharedMeshesStayWithinTenPercent)
{
  for (const char* name : {"spot.obj", "wingnut.obj"})
  {
    const std::string path = std::string (PCL_SPARSE_SHARED_MESHES) + "/" + name;
    PCL_SPARSE_NEED_SHARED_FILE (path);
    const auto mesh = std::make_shared<const TriangleMesh> (loadTriangleMesh (path));
    const SparseSurfaceModel::Ptr model = encodeMesh (mesh);
    const ModelWriteOptions start = boundWriteOptions (*model, mesh->vertices);
    const MeasuredWriteChoice choice = measuredWriteOptions (*model, *mesh, start);
    const double lossless = chamferOf (model, *mesh, 200000);
    const double chosen = chamferOf (roundTrip (*model, choice.options), *mesh, 200000);
    std::cout << "  " << name << ": " << choice.start_bytes << " -> " << choice.bytes << " bytes, Chamfer "
              << chosen / lossless << " x the lossless model's, " << choice.measured << " measured, "
              << choice.confirmed << " confirmed" << std::endl;
    EXPECT_LE (chosen, 1.1 * lossless) << name;
    if (std::string (name) == "spot.obj")
    {
      // Twice the tolerance reads 8-11 % over with 30k points (the band that asks for confirmation) and +7.6 % with
      // the confirmation's 200k (the radii on their grid, 2026-12-06; +8.3 % before): confirmed, 23025 -> 19189
      // bytes. A confirmation allowing 7 % refuses it and keeps a larger file.
      EXPECT_EQ (choice.confirmed, 1u);
      EXPECT_TRUE (choice.chosen_by_confirmation);
      EXPECT_LT (choice.bytes, 0.85 * choice.start_bytes);
      MeasuredWriteOptions stricter;
      stricter.confirm_max_increase = 0.07;
      const MeasuredWriteChoice refused = measuredWriteOptions (*model, *mesh, start, stricter);
      EXPECT_EQ (refused.confirmed, 1u);
      EXPECT_FALSE (refused.chosen_by_confirmation);
      EXPECT_GT (refused.bytes, choice.bytes);
      EXPECT_LE (chamferOf (roundTrip (*model, refused.options), *mesh, 200000), 1.1 * lossless);
    }
    else
      EXPECT_EQ (choice.confirmed, 0u);  // wingnut's coarser files read +15 % and more: none is confirmed
  }
}
