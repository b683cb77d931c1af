// pcl_sparse_render and the -png option of the other tools: pictures written, byte-identical across runs
// and thread counts, and a bad input or option gives one stderr line, exit 1 and no file.

#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include "generated_clouds.h"
#include "test_file_helpers.h"
#include "shared_data.h"

#include <gtest/gtest.h>

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <png.h>

#include <sys/wait.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pcl_sparse_test::readBytes;

namespace
{
  std::string
  tool (const std::string& name)
  {
    return std::string (PCL_SPARSE_BINARY_DIR) + "/apps/pcl_sparse_" + name;
  }

  struct ToolRun
  {
    int code = -1;
    std::string out, err;
  };

  /// Runs \a command (arguments already quoted where needed) with stdout and stderr captured in \a dir.
  ToolRun
  run (const pcl_sparse_test::TempDir& dir, const std::string& command)
  {
    const std::string out = dir.file ("stdout.txt"), err = dir.file ("stderr.txt");
    const int status = std::system ((command + " > " + out + " 2> " + err).c_str ());
    ToolRun r;
    r.code = WIFEXITED (status) ? WEXITSTATUS (status) : -1;
    r.out = readBytes (out);
    r.err = readBytes (err);
    return r;
  }

  int
  lines (const std::string& text)
  {
    int n = 0;
    for (std::size_t i = 0; i < text.size (); ++i)
      n += text[i] == '\n';
    return n + (!text.empty () && text.back () != '\n');
  }

  class RenderTool : public ::testing::Test
  {
  protected:
    void
    SetUp () override
    {
      if (!fs::exists (tool ("render")))
        GTEST_SKIP () << "the tools are not built in " << PCL_SPARSE_BINARY_DIR << "/apps";
      pcl_sparse::saveTriangleMesh (dir_.file ("sphere.off"), pcl_sparse::makeIcosphere (3));
    }
    pcl_sparse_test::TempDir dir_{"render_tool"};
  };
} // namespace

TEST_F (RenderTool, WritesTheSameBytesForAnyRunAndThreadCount)
{
  const std::string in = dir_.file ("sphere.off");
  const ToolRun a = run (dir_, "OMP_NUM_THREADS=1 " + tool ("render") + " " + in + " " + dir_.file ("a.png") + " -size 160x120 --json");
  ASSERT_EQ (a.code, 0) << a.err;
  EXPECT_NE (a.out.find ("\"pixels_covered\": "), std::string::npos) << a.out;
  EXPECT_NE (a.out.find ("\"render_seconds\": "), std::string::npos) << a.out;
  run (dir_, "OMP_NUM_THREADS=1 " + tool ("render") + " " + in + " " + dir_.file ("b.png") + " -size 160x120 -q");
  run (dir_, "OMP_NUM_THREADS=2 " + tool ("render") + " " + in + " " + dir_.file ("c.png") + " -size 160x120 -q");
  const std::string png = readBytes (dir_.file ("a.png"));
  ASSERT_GT (png.size (), 100u);
  EXPECT_EQ (png.substr (1, 3), "PNG");
  EXPECT_EQ (png, readBytes (dir_.file ("b.png")));
  EXPECT_EQ (png, readBytes (dir_.file ("c.png")));
}

TEST_F (RenderTool, ColorModes)
{
  const std::string in = dir_.file ("sphere.off");
  std::vector<std::string> pictures;
  for (const std::string& mode : std::vector<std::string>{"plain", "normal", "height", "patch", "error -ref " + in})
  {
    const ToolRun r = run (dir_, tool ("render") + " " + in + " " + dir_.file ("m.png") + " -size 200x150 -view iso -q -color " + mode);
    EXPECT_EQ (r.code, 0) << mode << ": " << r.err;
    EXPECT_TRUE (fs::exists (dir_.file ("m.png"))) << mode;
    pictures.push_back (readBytes (dir_.file ("m.png")));
    fs::remove (dir_.file ("m.png"));
  }
  // Each mode colours the same view differently: an ignored -color would give two equal pictures.
  for (std::size_t a = 0; a < pictures.size (); ++a)
    for (std::size_t b = a + 1; b < pictures.size (); ++b)
      EXPECT_NE (pictures[a], pictures[b]) << "modes " << a << " and " << b;
}

TEST_F (RenderTool, BadInputOrOptionGivesOneLineAndNoFile)
{
  const std::string in = dir_.file ("sphere.off"), out = dir_.file ("bad.png");
  pcl_sparse_test::writeBytes (dir_.file ("broken.off"), "OFF\n3 1 0\n0 0 0\n1 0\n");
  const std::vector<std::string> cases = {
    dir_.file ("missing.off") + " " + out,
    dir_.file ("broken.off") + " " + out,
    in + " " + dir_.file ("bad.jpg"),
    in + " " + out + " -size 0x10",
    in + " " + out + " -size 100",
    in + " " + out + " -view back",
    in + " " + out + " -color rainbow",
    in + " " + out + " -color error",
    in + " " + out + " -color rgb",
    in + " " + out + " -color error -ref " + dir_.file ("missing.off"),
    in + " " + out + " -bogus 3",
    in + " " + dir_.file ("no_such_dir/out.png"),
  };
  for (const std::string& c : cases)
  {
    const ToolRun r = run (dir_, tool ("render") + " " + c);
    EXPECT_EQ (r.code, 1) << c;
    EXPECT_EQ (lines (r.err), 1) << c << "\n" << r.err;
    EXPECT_FALSE (fs::exists (out)) << c;
    EXPECT_FALSE (fs::exists (dir_.file ("bad.jpg"))) << c;
  }
}

TEST_F (RenderTool, OtherToolsDrawWithPng)
{
  const std::string in = dir_.file ("sphere.off");
  const std::vector<std::string> commands = {
    tool ("patches") + " " + in + " " + dir_.file ("p.ply") + " -q -png " + dir_.file ("patches.png") + " -size 160x120",
    tool ("keypoints") + " " + in + " " + dir_.file ("k.pcd") + " -q -png " + dir_.file ("keypoints.png"),
    tool ("resample") + " " + in + " " + dir_.file ("r.pcd") + " -q -png " + dir_.file ("resample.png") + " -view side",
    tool ("encode") + " " + in + " -q -png " + dir_.file ("encode.png") + " -size 200x150",
  };
  for (const char* png : {"patches", "keypoints", "resample", "encode"})
    fs::remove (dir_.file (std::string (png) + ".png"));
  for (const std::string& c : commands)
  {
    const ToolRun r = run (dir_, c);
    EXPECT_EQ (r.code, 0) << c << "\n" << r.err;
  }
  for (const char* png : {"patches", "keypoints", "resample", "encode"})
    EXPECT_TRUE (fs::exists (dir_.file (std::string (png) + ".png"))) << png;
  // With --json, stdout is the JSON object alone (it began with "Wrote encode.png: ..."; found by a review),
  // and -q keeps the picture's line off it too.
  for (const std::string& mode : {std::string (" --json"), std::string (" -q")})
    for (const std::string& app : {std::string ("encode ") + in, "patches " + in + " " + dir_.file ("p2.ply")})
    {
      const ToolRun r = run (dir_, tool (app.substr (0, app.find (' '))) + app.substr (app.find (' ')) + mode + " -png " +
                                     dir_.file ("quiet.png") + " -size 80x60");
      EXPECT_EQ (r.code, 0) << app << mode << "\n" << r.err;
      EXPECT_EQ (r.out.find ("Wrote"), std::string::npos) << app << mode << "\n" << r.out;
      if (mode == " --json")
        EXPECT_TRUE (!r.out.empty () && r.out.front () == '{' && lines (r.out) == 1) << app << "\n" << r.out;
    }
  // A bad picture option is refused before the tool writes anything.
  // -size or -view without -png did nothing and exited 0.
  for (const std::string& bad_option : {" -png " + dir_.file ("x.gif"), " -png " + dir_.file ("x.png") + " -size 0x10",
                                        " -png " + dir_.file ("x.png") + " -view sideways", std::string (" -size 80x60"),
                                        std::string (" -view top")})
  {
    fs::remove (dir_.file ("never.ply"));
    const ToolRun bad = run (dir_, tool ("patches") + " " + in + " " + dir_.file ("never.ply") + " -q" + bad_option);
    EXPECT_EQ (bad.code, 1) << bad_option;
    EXPECT_EQ (lines (bad.err), 1) << bad.err;
    EXPECT_FALSE (fs::exists (dir_.file ("never.ply"))) << bad_option;
    EXPECT_FALSE (fs::exists (dir_.file ("x.png"))) << bad_option;
  }
}

TEST_F (RenderTool, SharedMeshAndScan)
{
  const std::string mesh = std::string (PCL_SPARSE_SHARED_MESHES) + "/fandisk.off";
  const std::string scan = std::string (PCL_SPARSE_SHARED_CLOUDS) + "/bun000.ply";
  PCL_SPARSE_NEED_SHARED_FILE (mesh);
  PCL_SPARSE_NEED_SHARED_FILE (scan);
  const ToolRun m = run (dir_, tool ("render") + " " + mesh + " " + dir_.file ("f.png") + " -size 320x240 -view iso --json");
  EXPECT_EQ (m.code, 0) << m.err;
  EXPECT_EQ (readBytes (dir_.file ("f.png")).substr (1, 3), "PNG");
  const ToolRun s = run (dir_, tool ("render") + " " + scan + " " + dir_.file ("s.png") + " -size 320x240 --json");
  EXPECT_EQ (s.code, 0) << s.err;
  EXPECT_EQ (readBytes (dir_.file ("s.png")).substr (1, 3), "PNG");
  // A scan is drawn as touching splats: a good part of the image is covered.
  const std::size_t at = s.out.find ("\"pixels_covered\": ");
  ASSERT_NE (at, std::string::npos) << s.out;
  EXPECT_GT (std::stoul (s.out.substr (at + 18)), 320u * 240u / 10u) << s.out;
}

// A model's colours: -color rgb refused every .psm ("the input has no colours") because the model was resampled
// without its colour channel; a model encoded from a red cloud now draws red, and a model without colours is
// refused saying so.
TEST_F (RenderTool, ModelColours)
{
  double area = 0.0;
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  for (const Eigen::Vector3d& v : pcl_sparse_test::sampleSurface (pcl_sparse::makeIcosphere (3), 4000, 7, area))
  {
    pcl::PointXYZRGB p;
    p.getVector3fMap () = v.cast<float> ();
    p.r = 255;
    p.g = p.b = 0;
    cloud.push_back (p);
  }
  ASSERT_EQ (pcl::io::savePCDFileBinary (dir_.file ("red.pcd"), cloud), 0);
  const ToolRun e = run (dir_, tool ("encode") + " " + dir_.file ("red.pcd") + " -o " + dir_.file ("red.psm") + " -q");
  ASSERT_EQ (e.code, 0) << e.err;
  const std::string png = dir_.file ("red.png");
  const ToolRun r = run (dir_, tool ("render") + " " + dir_.file ("red.psm") + " " + png + " -size 160x120 -color rgb -q");
  ASSERT_EQ (r.code, 0) << r.err;
  ASSERT_TRUE (fs::exists (png));
  png_image read;
  std::memset (&read, 0, sizeof (read));
  read.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE (png_image_begin_read_from_file (&read, png.c_str ())) << read.message;
  read.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> pixels (PNG_IMAGE_SIZE (read));
  ASSERT_TRUE (png_image_finish_read (&read, nullptr, pixels.data (), 0, nullptr)) << read.message;
  ASSERT_EQ (pixels.size (), 160u * 120u * 3u);
  // The background is white; every covered pixel is the cloud's red, shaded: red dominates it.
  std::size_t red = 0, other = 0;
  for (std::size_t i = 0; i < pixels.size (); i += 3)
  {
    const int R = pixels[i], G = pixels[i + 1], B = pixels[i + 2];
    if (R == 255 && G == 255 && B == 255)
      continue;
    (R > G + 40 && R > B + 40 ? red : other) += 1;
  }
  EXPECT_GT (red, 160u * 120u / 10u);
  EXPECT_LT (other, red / 10) << red << " red pixels";

  // A model without colours (from the plain sphere) is refused, saying why, with no picture.
  const ToolRun p = run (dir_, tool ("encode") + " " + dir_.file ("sphere.off") + " -o " + dir_.file ("plain.psm") + " -q");
  ASSERT_EQ (p.code, 0) << p.err;
  const ToolRun refused = run (dir_, tool ("render") + " " + dir_.file ("plain.psm") + " " + dir_.file ("plain.png") + " -color rgb -q");
  EXPECT_EQ (refused.code, 1);
  EXPECT_EQ (lines (refused.err), 1) << refused.err;
  EXPECT_NE (refused.err.find ("the model has no colour channel"), std::string::npos) << refused.err;
  EXPECT_FALSE (fs::exists (dir_.file ("plain.png")));
}
