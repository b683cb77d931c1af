// Runs the pcl_sparse_keypoints tool end to end (skips when the tool was not built).
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include "test_file_helpers.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace pcl_sparse;

namespace
{
  const fs::path kTool = fs::path (PCL_SPARSE_BINARY_DIR) / "apps" / "pcl_sparse_keypoints";

  struct ToolRun
  {
    int code;
    std::string out;
  };

  ToolRun
  run (const std::string& arguments)
  {
    ToolRun result;
    result.code = pcl_sparse_test::runShell (kTool.string () + " " + arguments + " 2>/dev/null", result.out);
    return result;
  }

  struct ToolFixture : public ::testing::Test
  {
    fs::path dir;
    std::string mesh_path;
    void
    SetUp () override
    {
      if (!fs::exists (kTool))
        GTEST_SKIP () << "tool not built: " << kTool;
      dir = fs::temp_directory_path () / ("pcl_sparse_keypoints_test_" + std::to_string (::getpid ()));
      fs::create_directories (dir);
      mesh_path = (dir / "cube.off").string ();
      saveTriangleMesh (mesh_path, makeCube (10, 1.0));
    }
    void
    TearDown () override
    {
      if (!dir.empty ())
        fs::remove_all (dir);
    }
  };
} // namespace

TEST_F (ToolFixture, WritesKeypointsAndResponsesAndJson)
{
  const std::string out = (dir / "keys.pcd").string (), resp = (dir / "resp.ply").string ();
  const ToolRun r = run (mesh_path + " " + out + " -fraction 0.0133 -responses " + resp + " --json");
  ASSERT_EQ (r.code, 0) << r.out;
  EXPECT_NE (r.out.find ("\"keypoints\": 8"), std::string::npos) << r.out;  // round (0.0133 x 602) = 8
  EXPECT_NE (r.out.find ("\"seconds\": "), std::string::npos);
  EXPECT_EQ (r.out.front (), '{');
  pcl::PointCloud<pcl::PointXYZI> keys;
  ASSERT_EQ (pcl::io::loadPCDFile (out, keys), 0);
  ASSERT_EQ (keys.size (), 8u);
  for (std::size_t i = 0; i < keys.size (); ++i)
  {
    EXPECT_NEAR (keys[i].getVector3fMap ().cwiseAbs ().minCoeff (), 1.0f, 1e-6f);  // the cube's corners
    if (i > 0)
      EXPECT_GE (keys[i - 1].intensity, keys[i].intensity);
  }
  const TriangleMesh colored = loadTriangleMesh (resp);
  EXPECT_EQ (colored.numVertices (), 602u);

  // PLY keypoints, fixed rings, quiet: nothing on stdout.
  const ToolRun ply = run (mesh_path + " " + (dir / "keys.ply").string () + " -rings 2 -q");
  EXPECT_EQ (ply.code, 0);
  EXPECT_TRUE (ply.out.empty ());
  EXPECT_TRUE (fs::exists (dir / "keys.ply"));
}

TEST_F (ToolFixture, BadInputFailsWithoutOutput)
{
  const std::string out = (dir / "never.pcd").string ();
  EXPECT_EQ (run ((dir / "missing.off").string () + " " + out).code, 1);
  EXPECT_EQ (run (mesh_path + " " + out + " -fraction 0").code, 1);
  EXPECT_EQ (run (mesh_path + " " + out + " -fraction abc").code, 1);
  EXPECT_EQ (run (mesh_path + " " + out + " -rings 2 -adaptive 0.02").code, 1);
  EXPECT_EQ (run (mesh_path + " " + out + " -rings 0").code, 1);
  EXPECT_EQ (run (mesh_path + " " + out + " -frobnicate").code, 1);
  EXPECT_EQ (run (mesh_path + " " + (dir / "keys.xyz").string ()).code, 1);
  EXPECT_EQ (run (mesh_path + " " + out + " -responses " + (dir / "r.obj").string ()).code, 1);
  EXPECT_EQ (run (mesh_path).code, 1);
  EXPECT_FALSE (fs::exists (out));
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator (dir))
    files += entry.is_regular_file ();
  EXPECT_EQ (files, 1u);  // only the input mesh: no partial or temporary files
}
