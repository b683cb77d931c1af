// pcl_sparse_encode and pcl_sparse_decode under mpirun (issue 16): the tiled model file is byte-identical for
// 1, 2 and 3 ranks on localhost and to the run without mpirun, and so is the decoded cloud for 2 and 3 ranks.
// Skipped, saying why, when the tools are built without MPI.

#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include <gtest/gtest.h>

#include "generated_clouds.h"
#include "test_file_helpers.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

using namespace pcl_sparse;

namespace
{
  const std::string tools = std::string (PCL_SPARSE_BINARY_DIR) + "/apps";

  /// Open MPI refuses root without these (CI runs as the same user as the developers' machine).
  const std::string kMpiEnvironment = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader "
                                      "OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1 ";

  using pcl_sparse_test::runCommand;
} // namespace

TEST (TilesMpi, SameFilesForOneTwoThreeRanksAndWithout)
{
#ifndef PCL_SPARSE_MPIEXEC
  GTEST_SKIP () << "the tools are built without MPI (CMake found none, or PCL_SPARSE_WITH_MPI is off)";
#else
  const std::string mpiexec = PCL_SPARSE_MPIEXEC;
  if (!std::filesystem::exists (tools + "/pcl_sparse_encode"))
    GTEST_SKIP () << "pcl_sparse_encode not built";
  const pcl_sparse_test::TempDir dir ("pcl_sparse_mpi");
  const std::string mesh = dir.file ("terrain.off");
  saveTriangleMesh (mesh, makeHeightFieldGrid (120, 120, 1.0, 1.0, [] (double x, double y) {
                      return 0.06 * std::sin (9.0 * x) * std::cos (8.0 * y) + 0.05 * x * y;
                    }));
  const std::string encode = tools + "/pcl_sparse_encode " + mesh + " -tiles 3 -threads 1 -q";
  std::string out;
  ASSERT_EQ (runCommand (encode + " -o " + dir.file ("alone.psm"), out), 0) << out;
  const std::string alone = pcl_sparse_test::readBytes (dir.file ("alone.psm"));
  ASSERT_TRUE (isTiledModelFile (dir.file ("alone.psm")));
  for (int ranks : {1, 2, 3})
  {
    const std::string file = dir.file ("ranks" + std::to_string (ranks) + ".psm");
    const int code = runCommand (kMpiEnvironment + mpiexec + " --oversubscribe -n " + std::to_string (ranks) + " " + encode +
                            " -o " + file + " --json",
                          out);
    ASSERT_EQ (code, 0) << out;
    EXPECT_NE (out.find ("\"ranks\": " + std::to_string (ranks)), std::string::npos) << out;
    EXPECT_TRUE (pcl_sparse_test::readBytes (file) == alone) << ranks << " ranks";
  }
  // A cloud over -memory, spilled into tiles on disk by each rank: the same file as loaded without mpirun.
  const std::string terrain_pcd = dir.file ("terrain.pcd");
  pcl_sparse_test::TerrainOptions terrain;
  terrain.points = 30000;
  pcl_sparse_test::writeTerrainPcd (terrain_pcd, terrain);
  const std::string encode_cloud = tools + "/pcl_sparse_encode " + terrain_pcd + " -tiles 3 -threads 1";
  ASSERT_EQ (runCommand (encode_cloud + " -q -o " + dir.file ("cloud_alone.psm"), out), 0) << out;
  ASSERT_EQ (runCommand (kMpiEnvironment + mpiexec + " --oversubscribe -n 2 " + encode_cloud + " -memory 1M --json -o " +
                    dir.file ("cloud_two.psm"),
                  out),
             0)
    << out;
  EXPECT_NE (out.find ("\"spilled\": true"), std::string::npos) << out;
  EXPECT_NE (out.find ("\"ranks\": 2"), std::string::npos) << out;
  EXPECT_TRUE (pcl_sparse_test::readBytes (dir.file ("cloud_two.psm")) == pcl_sparse_test::readBytes (dir.file ("cloud_alone.psm")));
  // Decoding spread the same way: each rank its run of tiles, rank 0 writes the same cloud.
  const std::string decode = tools + "/pcl_sparse_decode " + dir.file ("alone.psm") + " ";
  ASSERT_EQ (runCommand (decode + dir.file ("alone.pcd") + " -density 30000 -q", out), 0) << out;
  const std::string cloud = pcl_sparse_test::readBytes (dir.file ("alone.pcd"));
  ASSERT_GT (cloud.size (), 1000u);
  for (int ranks : {2, 3})
  {
    const std::string file = dir.file ("ranks" + std::to_string (ranks) + ".pcd");
    ASSERT_EQ (runCommand (kMpiEnvironment + mpiexec + " --oversubscribe -n " + std::to_string (ranks) + " " + decode + file +
                      " -density 30000 --json",
                    out),
               0)
      << out;
    EXPECT_NE (out.find ("\"ranks\": " + std::to_string (ranks)), std::string::npos) << out;
    EXPECT_TRUE (pcl_sparse_test::readBytes (file) == cloud) << ranks << " ranks";
  }
#endif
}
