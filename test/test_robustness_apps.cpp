/// Every tool on every bad or awkward mesh of robustness_cases.h and on bad options: each run either
/// succeeds with a valid output file or prints one error line on stderr and exits with 1; it never
/// crashes (signal), never hangs (timeout), and never leaves an output file behind when it fails.

#include "robustness_cases.h"
#include "test_file_helpers.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_cleaning.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/vertex_welding.h>

#include <gtest/gtest.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace pcl_sparse;
using namespace pcl_sparse::robustness;

namespace
{
  const int kTimeoutSeconds = 60;

  std::string
  appPath (const std::string& name)
  {
    return std::string (PCL_SPARSE_BINARY_DIR) + "/apps/pcl_sparse_" + name;
  }

  bool
  appsBuilt ()
  {
    for (const char* name : {"info", "keypoints", "patches", "encode", "resample", "decode"})
      if (!fs::exists (appPath (name)))
        return false;
    return true;
  }

  std::string
  readText (const fs::path& path)
  {
    std::ifstream in (path, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf ();
    return buffer.str ();
  }

  std::string
  quote (const std::string& s)
  {
    std::string out = "'";
    for (const char c : s)
      out += c == '\'' ? std::string ("'\\''") : std::string (1, c);
    return out + "'";
  }

  struct RunResult
  {
    bool signaled = false;    ///< killed by a signal (crash), seen directly or through timeout's 128 + signal
    bool timed_out = false;
    int exit_code = -1;
    std::string out;
    std::string err;
    std::string command;
  };

  /// Runs tool \a app with \a args under `timeout`, stdout and stderr to files in \a dir.
  RunResult
  runApp (const std::string& app, const std::vector<std::string>& args, const fs::path& dir,
          const std::string& env = "")
  {
    RunResult r;
    std::string command = env + (env.empty () ? "" : " ") + "timeout -k 5 " + std::to_string (kTimeoutSeconds) +
                          " " + quote (appPath (app));
    for (const std::string& a : args)
      command += " " + quote (a);
    r.command = command;
    const fs::path out = dir / "stdout.txt";
    const fs::path err = dir / "stderr.txt";
    const int status = std::system ((command + " > " + quote (out.string ()) + " 2> " + quote (err.string ())).c_str ());
    if (WIFSIGNALED (status))
      r.signaled = true;
    else if (WIFEXITED (status))
    {
      r.exit_code = WEXITSTATUS (status);
      r.timed_out = r.exit_code == 124 || r.exit_code == 137;
      r.signaled = r.exit_code > 128 && !r.timed_out;
    }
    r.out = readText (out);
    r.err = readText (err);
    fs::remove (out);
    fs::remove (err);
    return r;
  }

  int
  nonEmptyLines (const std::string& text)
  {
    int lines = 0;
    std::istringstream in (text);
    for (std::string line; std::getline (in, line);)
      if (line.find_first_not_of (" \t\r") != std::string::npos)
        ++lines;
    return lines;
  }

  /// Files in \a dir (the outputs a run left behind, including temporaries of atomic writes).
  std::vector<std::string>
  filesIn (const fs::path& dir)
  {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator (dir))
      names.push_back (e.path ().filename ().string ());
    return names;
  }

  /// Checks the contract of one run; \a output (may be empty) is the file a successful run must write.
  /// Returns true when the run succeeded. \a out_dir must hold nothing but what the run wrote.
  bool
  checkRun (const RunResult& r, const fs::path& out_dir, const std::string& output)
  {
    SCOPED_TRACE (r.command + "\nstderr: " + r.err);
    EXPECT_FALSE (r.signaled) << "crashed";
    EXPECT_FALSE (r.timed_out) << "did not finish in " << kTimeoutSeconds << " s";
    EXPECT_TRUE (r.exit_code == 0 || r.exit_code == 1) << "exit code " << r.exit_code;
    EXPECT_EQ (r.err.find ("Sanitizer"), std::string::npos);
    EXPECT_EQ (r.err.find ("runtime error"), std::string::npos);
    if (r.exit_code == 0)
    {
      if (!output.empty ())
        EXPECT_TRUE (fs::exists (out_dir / output)) << "success without the output file";
      return true;
    }
    EXPECT_EQ (nonEmptyLines (r.err), 1) << "expected exactly one error line on stderr";
    EXPECT_TRUE (filesIn (out_dir).empty ()) << "failure left " << filesIn (out_dir).size () << " file(s) behind, e.g. "
                                             << (filesIn (out_dir).empty () ? "" : filesIn (out_dir).front ());
    return false;
  }

  /// A cloud file written by a tool: loads, has \a expected points (or any number > 0 when 0), all finite.
  void
  expectValidCloud (const fs::path& path, std::size_t expected)
  {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    ASSERT_NO_THROW (loadPointCloud (path.string (), cloud)) << path;
    if (expected > 0)
      EXPECT_EQ (cloud.size (), expected) << path;
    for (const pcl::PointXYZ& p : cloud.points)
      ASSERT_TRUE (std::isfinite (p.x) && std::isfinite (p.y) && std::isfinite (p.z)) << path;
  }

  class RobustnessApps : public ::testing::TestWithParam<MeshCase>
  {
  protected:
    void
    SetUp () override
    {
      if (!appsBuilt ())
        GTEST_SKIP () << "the tools are not built in " << PCL_SPARSE_BINARY_DIR
                      << "/apps (build all targets, as scripts/test.sh does)";
      // One folder per test, not per case: ctest -j runs each tool's test of a case at once, and one's
      // SetUp emptied the folder another was writing to (empty_file failed now and then).
      std::string test = ::testing::UnitTest::GetInstance ()->current_test_info ()->name ();
      std::replace (test.begin (), test.end (), '/', '_');
      dir_ = fs::path (PCL_SPARSE_BINARY_DIR) / "robustness_apps" / test;
      fs::remove_all (dir_);
      fs::create_directories (dir_ / "out");
      input_ = (dir_ / (GetParam ().name + ".obj")).string ();
      std::ofstream (input_, std::ios::binary) << GetParam ().obj;
    }

    /// Runs \a app, checks the contract, and the case's expectation. Returns true on success.
    bool
    run (const std::string& app, const std::vector<std::string>& args, const std::string& output)
    {
      const fs::path out_dir = dir_ / "out";
      for (const fs::directory_entry& e : fs::directory_iterator (out_dir))
        fs::remove_all (e.path ());
      const RunResult r = runApp (app, args, dir_);
      last_out_ = r.out;
      const bool ok = checkRun (r, out_dir, output);
      const bool coding = app == "encode" || app == "resample" || app == "decode";
      const Expect expect = coding && GetParam ().override_coding ? GetParam ().coding : GetParam ().expect;
      if (expect == Expect::Success)
        EXPECT_TRUE (ok) << app << " should accept " << GetParam ().name << "; stderr: " << r.err;
      if (expect == Expect::Failure)
        EXPECT_FALSE (ok) << app << " should refuse " << GetParam ().name;
      return ok;
    }

    fs::path
    out (const std::string& name) const
    {
      return dir_ / "out" / name;
    }

    fs::path dir_;
    std::string input_;
    std::string last_out_;  ///< stdout of the last run
  };

  /// Lines of an OBJ text that start with \a tag and a blank ("v", "f").
  std::size_t
  countObjRecords (const std::string& obj, const std::string& tag)
  {
    std::istringstream in (obj);
    std::size_t count = 0;
    for (std::string line; std::getline (in, line);)
      count += line.rfind (tag + " ", 0) == 0;
    return count;
  }

  // Info reports what it finds in every file it can parse (a mesh without faces or surface too), and refuses
  // only what no tool can read.
  TEST_P (RobustnessApps, Info)
  {
    const bool ok = run ("info", {input_, "-q"}, "");
    if (GetParam ().expect != Expect::Failure)
    {
      ASSERT_TRUE (ok) << "info should report on " << GetParam ().name;
      EXPECT_NE (last_out_.find ("\nvertices: " + std::to_string (countObjRecords (GetParam ().obj, "v")) + "\n"),
                 std::string::npos)
        << last_out_;
      EXPECT_NE (last_out_.find ("\nfaces: " + std::to_string (countObjRecords (GetParam ().obj, "f")) + "\n"),
                 std::string::npos)
        << last_out_;
    }
  }

  TEST_P (RobustnessApps, Keypoints)
  {
    if (run ("keypoints", {input_, out ("k.pcd").string (), "-q"}, "k.pcd"))
    {
      expectValidCloud (out ("k.pcd"), 0);
      // A mesh every tool must accept has enough neighbourhoods for Harris 3D to find some; a single
      // triangle or a soup of tiny components may have none.
      if (GetParam ().expect == Expect::Success)
      {
        pcl::PointCloud<pcl::PointXYZ> cloud;
        loadPointCloud (out ("k.pcd").string (), cloud);
        EXPECT_GT (cloud.size (), 0u);
      }
    }
  }

  TEST_P (RobustnessApps, Patches)
  {
    if (run ("patches", {input_, out ("p.ply").string (), "-q"}, "p.ply"))
    {
      TriangleMesh input, coloured;
      ASSERT_NO_THROW (input = loadTriangleMesh (input_));
      ASSERT_NO_THROW (coloured = loadTriangleMesh (out ("p.ply").string ()));
      // The surface it worked on: the input, or a soup welded at equal positions.
      CleaningOptions weld_only{false, false, false, false};
      weld_only.weld_coincident_vertices = true;
      const std::size_t expected = isTriangleSoup (input) ? cleanMesh (input, weld_only).mesh.vertices.size () : input.vertices.size ();
      EXPECT_EQ (coloured.vertices.size (), expected);
    }
  }

  TEST_P (RobustnessApps, EncodeAndDecode)
  {
    if (!run ("encode", {input_, "-o", out ("m.psm").string (), "-q"}, "m.psm"))
      return;
    SparseSurfaceModel model;
    ASSERT_NO_THROW (model = loadModel (out ("m.psm").string ()));
    EXPECT_GT (model.patches.size (), 0u);
    // Decode the model just written (moved out of the output folder, which must be empty before a run).
    const fs::path psm = dir_ / "m.psm";
    fs::rename (out ("m.psm"), psm);
    if (run ("decode", {psm.string (), out ("d.pcd").string (), "-n", "300", "-q"}, "d.pcd"))
      expectValidCloud (out ("d.pcd"), 300);
  }

  TEST_P (RobustnessApps, Resample)
  {
    if (run ("resample", {input_, out ("r.pcd").string (), "-n", "500", "-q"}, "r.pcd"))
      expectValidCloud (out ("r.pcd"), 500);
  }

  INSTANTIATE_TEST_SUITE_P (Meshes, RobustnessApps, ::testing::ValuesIn (meshCases ()),
                            [] (const ::testing::TestParamInfo<MeshCase>& info) {
                              std::string name = info.param.name;
                              for (char& c : name)
                                if (!std::isalnum (static_cast<unsigned char> (c)))
                                  c = '_';
                              return name;
                            });

  /// A bad command line: must fail with one error line and leave nothing behind.
  struct OptionCase
  {
    std::string label;
    std::string app;
    std::vector<std::string> args;  ///< "IN" = a good mesh, "OUT.x" = output file x in the output folder, "PSM" = a good model
    Expect expect = Expect::Failure;
  };

  void
  PrintTo (const OptionCase& c, std::ostream* os)
  {
    *os << c.label;
  }

  std::vector<OptionCase>
  optionCases ()
  {
    return {
      // pcl_sparse_encode
      {"encode_negative_rho", "encode", {"IN", "-o", "OUT.m.psm", "-rho", "-0.01"}},
      {"encode_zero_rho", "encode", {"IN", "-o", "OUT.m.psm", "-rho", "0"}},
      // rho > 1 bounds nothing more than rho = 1: refused by every tool.
      {"encode_rho_above_one", "encode", {"IN", "-o", "OUT.m.psm", "-rho", "2"}},
      {"encode_f_above_one", "encode", {"IN", "-o", "OUT.m.psm", "-f", "1.5"}},
      {"encode_negative_f", "encode", {"IN", "-o", "OUT.m.psm", "-f", "-0.5"}},
      {"encode_zero_atoms", "encode", {"IN", "-o", "OUT.m.psm", "-L", "0"}},
      {"encode_huge_atoms", "encode", {"IN", "-o", "OUT.m.psm", "-L", "1e12"}},
      {"encode_eps_above_one", "encode", {"IN", "-o", "OUT.m.psm", "-eps", "1.5"}},
      {"encode_negative_sigma", "encode", {"IN", "-o", "OUT.m.psm", "-sigma", "-0.5"}},
      {"encode_nan_sigma", "encode", {"IN", "-o", "OUT.m.psm", "-sigma", "nan"}},
      {"encode_negative_merge", "encode", {"IN", "-o", "OUT.m.psm", "-merge-patches", "-1"}},
      {"encode_fractional_merge", "encode", {"IN", "-o", "OUT.m.psm", "-merge-patches", "2.5"}},
      {"encode_negative_point_patches", "encode", {"IN", "-o", "OUT.m.psm", "-point-patches", "-1"}},
      {"patches_nan_point_patches", "patches", {"IN", "OUT.p.ply", "-point-patches", "nan"}},
      {"encode_negative_atom_loss", "encode", {"IN", "-o", "OUT.m.psm", "-atom-loss", "-0.1"}},
      {"encode_nan_atom_loss", "encode", {"IN", "-o", "OUT.m.psm", "-atom-loss", "nan"}},
      {"encode_negative_threads", "encode", {"IN", "-o", "OUT.m.psm", "-threads", "-1"}},
      {"encode_rho_not_a_number", "encode", {"IN", "-o", "OUT.m.psm", "-rho", "abc"}},
      {"encode_rho_nan", "encode", {"IN", "-o", "OUT.m.psm", "-rho", "nan"}},
      {"encode_rho_missing_value", "encode", {"IN", "-o", "OUT.m.psm", "-rho"}},
      {"encode_unknown_flag", "encode", {"IN", "-o", "OUT.m.psm", "--bogus"}},
      {"encode_no_arguments", "encode", {}},
      {"encode_two_inputs", "encode", {"IN", "IN", "-o", "OUT.m.psm"}},
      {"encode_missing_input", "encode", {"MISSING.obj", "-o", "OUT.m.psm"}},
      {"encode_directory_input", "encode", {"DIR", "-o", "OUT.m.psm"}},
      {"encode_unwritable_output", "encode", {"IN", "-o", "/nonexistent_dir/m.psm"}},
      {"encode_negative_tolerance", "encode", {"IN", "-o", "OUT.m.psm", "-tolerance", "-1"}},
      {"encode_f_zero", "encode", {"IN", "-o", "OUT.m.psm", "-f", "0"}, Expect::Success},
      {"encode_f_one", "encode", {"IN", "-o", "OUT.m.psm", "-f", "1"}, Expect::Success},
      {"encode_rho_one", "encode", {"IN", "-o", "OUT.m.psm", "-rho", "1"}, Expect::Success},
      // pcl_sparse_resample
      {"resample_n_zero", "resample", {"IN", "OUT.r.pcd", "-n", "0"}},
      {"resample_n_negative", "resample", {"IN", "OUT.r.pcd", "-n", "-5"}},
      {"resample_n_fraction", "resample", {"IN", "OUT.r.pcd", "-n", "2.5"}},
      {"resample_n_huge", "resample", {"IN", "OUT.r.pcd", "-n", "1e15"}},
      {"resample_density_huge", "resample", {"IN", "OUT.r.pcd", "-density", "1e300"}},
      {"resample_spacing_tiny", "resample", {"IN", "OUT.r.pcd", "-spacing", "1e-300"}},
      {"resample_negative_density", "resample", {"IN", "OUT.r.pcd", "-density", "-1"}},
      {"resample_negative_rho", "resample", {"IN", "OUT.r.pcd", "-rho", "-1"}},
      {"resample_f_above_one", "resample", {"IN", "OUT.r.pcd", "-f", "2"}},
      {"resample_max_slope_zero", "resample", {"IN", "OUT.r.pcd", "-max-slope", "0"}},
      {"resample_max_slope_above_90", "resample", {"IN", "OUT.r.pcd", "-max-slope", "91"}},
      {"resample_max_slope_nan", "resample", {"IN", "OUT.r.pcd", "-max-slope", "nan"}},
      {"resample_negative_clearance", "resample", {"IN", "OUT.r.pcd", "-clearance", "-0.1"}},
      {"resample_clearance_nan", "resample", {"IN", "OUT.r.pcd", "-clearance", "nan"}},
      {"resample_unknown_flag", "resample", {"IN", "OUT.r.pcd", "--bogus"}},
      {"resample_missing_output", "resample", {"IN"}},
      {"resample_bad_output_extension", "resample", {"IN", "OUT.r.txt"}},
      {"resample_n_one", "resample", {"IN", "OUT.r.pcd", "-n", "1"}, Expect::Success},
      // pcl_sparse_decode
      {"decode_n_zero", "decode", {"PSM", "OUT.d.pcd", "-n", "0"}},
      {"decode_n_huge", "decode", {"PSM", "OUT.d.pcd", "-n", "1e15"}},
      {"decode_max_slope_zero", "decode", {"PSM", "OUT.d.pcd", "-max-slope", "0"}},
      {"decode_negative_clearance", "decode", {"PSM", "OUT.d.pcd", "-clearance", "-1"}},
      {"decode_mesh_as_model", "decode", {"IN", "OUT.d.pcd"}},
      {"decode_garbage_model", "decode", {"GARBAGE.psm", "OUT.d.pcd"}},
      {"decode_unknown_flag", "decode", {"PSM", "OUT.d.pcd", "--bogus"}},
      {"decode_missing_output", "decode", {"PSM"}},
      {"decode_recon_without_vertices", "decode", {"PSM", "OUT.d.pcd", "-recon", "IN", "OUT.recon.obj"}},
      // pcl_sparse_keypoints
      {"keypoints_fraction_above_one", "keypoints", {"IN", "OUT.k.pcd", "-fraction", "2"}},
      {"keypoints_fraction_zero", "keypoints", {"IN", "OUT.k.pcd", "-fraction", "0"}},
      {"keypoints_rings_zero", "keypoints", {"IN", "OUT.k.pcd", "-rings", "0"}},
      {"keypoints_negative_adaptive", "keypoints", {"IN", "OUT.k.pcd", "-adaptive", "-1"}},
      {"keypoints_k_nan", "keypoints", {"IN", "OUT.k.pcd", "-k", "nan"}},
      // -k 1e308 gave every keypoint a response of -inf
      {"keypoints_k_huge", "keypoints", {"IN", "OUT.k.pcd", "-k", "1e308"}},
      {"keypoints_k_negative", "keypoints", {"IN", "OUT.k.pcd", "-k", "-1"}},
      {"keypoints_unknown_flag", "keypoints", {"IN", "OUT.k.pcd", "--bogus"}},
      {"keypoints_missing_output", "keypoints", {"IN"}},
      // pcl_sparse_patches
      {"patches_negative_rho", "patches", {"IN", "OUT.p.ply", "-rho", "-1"}},
      {"patches_negative_delta", "patches", {"IN", "OUT.p.ply", "-delta", "-5"}},
      {"patches_eta_below_one", "patches", {"IN", "OUT.p.ply", "-eta", "0.5"}},
      {"patches_negative_min_size", "patches", {"IN", "OUT.p.ply", "-min-size", "-1"}},
      {"patches_unknown_flag", "patches", {"IN", "OUT.p.ply", "--bogus"}},
      {"patches_wrong_output_extension", "patches", {"IN", "OUT.p.pcd"}},
      // an option given twice (the first value won: "-o a.psm -o b.psm" never wrote b.psm)
      {"encode_output_twice", "encode", {"IN", "-o", "OUT.a.psm", "-o", "OUT.b.psm"}},
      {"encode_output_not_psm", "encode", {"IN", "-o", "OUT.m.ply"}},
      // an empty path: encode wrote no model and exited 0
      {"encode_output_empty", "encode", {"IN", "-o", ""}},
      {"encode_recon_empty", "encode", {"IN", "-recon", ""}},
      // pcl_sparse_render: sscanf wrapped 4294967297 to 1
      {"encode_rho_denormal", "encode", {"IN", "-o", "OUT.m.psm", "-rho", "1e-320"}},
      {"patches_zero_rho", "patches", {"IN", "OUT.p.ply", "-rho", "0"}},
      {"resample_model_with_encoder_option", "resample", {"PSM", "OUT.r.pcd", "-rho", "0.01"}},
      {"resample_threads_zero", "resample", {"IN", "OUT.r.pcd", "-threads", "0"}, Expect::Success},
      {"decode_box_stream_on", "decode", {"PSM", "OUT.d.pcd", "-density", "100", "-box", "-1,-1,-1,1,1,1", "-stream", "on"}},
      // options that did nothing, without a word: -block on a cloud written whole, -viewpoint on a mesh, render -n
      // on a mesh; and numbers strtod read but no user means (hexadecimal, a leading space)
      {"resample_block_stream_off", "resample", {"IN", "OUT.r.pcd", "-stream", "off", "-block", "8192"}},
      {"resample_block_ascii", "resample", {"IN", "OUT.r.pcd", "-ascii", "-block", "8192"}},
      {"resample_block_streamed", "resample", {"IN", "OUT.r.pcd", "-block", "8192"}, Expect::Success},
      {"decode_block_stream_off", "decode", {"PSM", "OUT.d.pcd", "-stream", "off", "-block", "8192"}},
      {"decode_block_box", "decode", {"PSM", "OUT.d.pcd", "-density", "100", "-box", "-1,-1,-1,1,1,1", "-block", "8192"}},
      {"resample_block_too_large", "resample", {"IN", "OUT.r.pcd", "-block", "67108865"}},
      {"resample_block_largest", "resample", {"IN", "OUT.r.pcd", "-block", "67108864"}, Expect::Success},
      {"decode_block_too_small", "decode", {"PSM", "OUT.d.pcd", "-block", "4095"}},
      {"decode_block_smallest", "decode", {"PSM", "OUT.d.pcd", "-block", "4096"}, Expect::Success},
      {"resample_viewpoint_on_mesh", "resample", {"IN", "OUT.r.pcd", "-viewpoint", "0,0,5"}},
      {"encode_viewpoint_on_mesh", "encode", {"IN", "-o", "OUT.m.psm", "-viewpoint", "0,0,5"}},
      {"patches_viewpoint_on_mesh", "patches", {"IN", "OUT.p.ply", "-viewpoint", "0,0,5"}},
      {"keypoints_viewpoint_on_mesh", "keypoints", {"IN", "OUT.k.pcd", "-viewpoint", "0,0,5"}},
      {"render_n_on_mesh", "render", {"IN", "OUT.x.png", "-n", "1000"}},
      {"resample_seed_hexadecimal", "resample", {"IN", "OUT.r.pcd", "-seed", "0x10"}},
      {"resample_n_leading_space", "resample", {"IN", "OUT.r.pcd", "-n", " 100"}},
      {"resample_seed_largest", "resample", {"IN", "OUT.r.pcd", "-seed", "18446744073709551615"}, Expect::Success},
      {"render_size_overflow", "render", {"IN", "OUT.x.png", "-size", "4294967297x5"}},
      {"render_size_signed", "render", {"IN", "OUT.x.png", "-size", "8x+5"}},
      {"render_view_huge", "render", {"IN", "OUT.x.png", "-view", "1e200,0,0"}, Expect::Success},
      {"render_view_trailing_comma", "render", {"IN", "OUT.x.png", "-view", "1,2,3,"}},
      {"patches_viewpoint_trailing_comma", "patches", {"IN", "OUT.p.ply", "-viewpoint", "1,2,3,"}},
      // pcl_sparse_info
      {"info_unknown_flag", "info", {"IN", "--bogus"}},
      {"info_no_arguments", "info", {}},
      {"info_missing_input", "info", {"MISSING.obj"}},
    };
  }

  class RobustnessOptions : public ::testing::TestWithParam<OptionCase>
  {
  };

  TEST_P (RobustnessOptions, RefusedCleanly)
  {
    if (!appsBuilt ())
      GTEST_SKIP () << "the tools are not built in " << PCL_SPARSE_BINARY_DIR << "/apps";
    const OptionCase& c = GetParam ();
    const fs::path dir = fs::path (PCL_SPARSE_BINARY_DIR) / "robustness_options" / c.label;
    fs::remove_all (dir);
    fs::create_directories (dir / "out");
    fs::create_directories (dir / "a_directory.obj");
    const std::string mesh = (dir / "good.obj").string ();
    std::ofstream (mesh) << objText (baseMesh ());
    const std::string garbage = (dir / "garbage.psm").string ();
    std::ofstream (garbage) << "PSM\x01 this is not a model";
    const std::string psm = (dir / "good.psm").string ();
    if (std::find (c.args.begin (), c.args.end (), "PSM") != c.args.end ())
    {
      const RunResult r = runApp ("encode", {mesh, "-o", psm, "-q"}, dir);
      ASSERT_EQ (r.exit_code, 0) << r.err;
    }
    std::vector<std::string> args;
    std::string output;
    for (const std::string& a : c.args)
      if (a == "IN")
        args.push_back (mesh);
      else if (a == "PSM")
        args.push_back (psm);
      else if (a == "GARBAGE.psm")
        args.push_back (garbage);
      else if (a == "MISSING.obj")
        args.push_back ((dir / "missing.obj").string ());
      else if (a == "DIR")
        args.push_back ((dir / "a_directory.obj").string ());
      else if (a.rfind ("OUT.", 0) == 0)
      {
        output = a.substr (4);
        args.push_back ((dir / "out" / output).string ());
      }
      else
        args.push_back (a);
    if (!args.empty ())
      args.push_back ("-q");
    const RunResult r = runApp (c.app, args, dir);
    const bool ok = checkRun (r, dir / "out", output);
    if (c.expect == Expect::Success)
      EXPECT_TRUE (ok) << r.command << "\n" << r.err;
    if (c.expect == Expect::Failure)
      EXPECT_FALSE (ok) << r.command << " should have been refused";
    fs::remove_all (dir);
  }

  INSTANTIATE_TEST_SUITE_P (Options, RobustnessOptions, ::testing::ValuesIn (optionCases ()),
                            [] (const ::testing::TestParamInfo<OptionCase>& info) { return info.param.label; });

  /// Each test runs the tools in a folder of its own, removed after; skipped when the tools are not built.
  class RobustnessAppsPaths : public ::testing::Test
  {
  protected:
    void
    SetUp () override
    {
      if (!appsBuilt ())
        GTEST_SKIP () << "the tools are not built in " << PCL_SPARSE_BINARY_DIR << "/apps";
      dir_ = fs::path (PCL_SPARSE_BINARY_DIR) / "robustness_paths" /
             ::testing::UnitTest::GetInstance ()->current_test_info ()->name ();
      fs::remove_all (dir_);
      fs::create_directories (dir_);
    }

    void
    TearDown () override
    {
      if (!dir_.empty ())
        fs::remove_all (dir_);
    }

    fs::path dir_;
  };

  /// decode -recon takes the faces of the mesh given and the model's positions of its vertices: the encoded
  /// mesh comes back within the model's error; the same mesh with its vertices in another order (same count)
  /// gave a tangle without a word. It is refused now, before anything is written.
  TEST_F (RobustnessAppsPaths, DecodeReconNeedsTheEncodedMesh)
  {
    const TriangleMesh mesh = baseMesh ();
    const std::string obj = (dir_ / "c.obj").string (), psm = (dir_ / "c.psm").string ();
    saveTriangleMesh (obj, mesh);
    ASSERT_EQ (runApp ("encode", {obj, "-o", psm, "--store-vertices", "-q"}, dir_).exit_code, 0);
    const std::string recon = (dir_ / "r.obj").string (), cloud = (dir_ / "o.pcd").string ();
    const RunResult good = runApp ("decode", {psm, cloud, "-recon", obj, recon, "-q"}, dir_);
    ASSERT_EQ (good.exit_code, 0) << good.err;
    const TriangleMesh r = loadTriangleMesh (recon);
    ASSERT_EQ (r.vertices.size (), mesh.vertices.size ());
    double farthest = 0.0;
    for (std::size_t v = 0; v < r.vertices.size (); ++v)
    {
      const double d = (r.vertices[v] - mesh.vertices[v]).norm ();
      ASSERT_TRUE (std::isfinite (d)) << "vertex " << v;  // std::max would keep the old value for a NaN
      farthest = std::max (farthest, d);
    }
    EXPECT_LT (farthest, 0.03) << "the icosphere has radius 1 (diagonal 3.46); the default file is quantised";

    // The same surface, vertices numbered backwards (faces follow): every vertex gets another's position.
    TriangleMesh reversed = mesh;
    const int n = static_cast<int> (mesh.vertices.size ());
    std::reverse (reversed.vertices.begin (), reversed.vertices.end ());
    for (Eigen::Vector3i& t : reversed.triangles)
      t = Eigen::Vector3i (n - 1 - t[0], n - 1 - t[1], n - 1 - t[2]);
    const std::string other = (dir_ / "reversed.obj").string ();
    saveTriangleMesh (other, reversed);
    fs::remove (cloud);
    fs::remove (recon);
    const RunResult bad = runApp ("decode", {psm, cloud, "-recon", other, recon, "-q"}, dir_);
    EXPECT_EQ (bad.exit_code, 1) << bad.err;
    EXPECT_NE (bad.err.find ("is not the mesh the model was encoded from"), std::string::npos) << bad.err;
    EXPECT_FALSE (fs::exists (cloud));
    EXPECT_FALSE (fs::exists (recon));
  }

  /// Outputs that name an input, another output or a folder that does not exist are refused before any
  /// work, and the input is left as it was (found by a review: "encode c.obj -recon c.obj" replaced the
  /// mesh, "decode m.psm c.ply -recon c.obj c.ply" wrote both outputs to one file).
  TEST_F (RobustnessAppsPaths, OutputsNeverOverwriteInputs)
  {
    const std::string obj = (dir_ / "c.obj").string (), ply = (dir_ / "c.ply").string (), psm = (dir_ / "c.psm").string ();
    saveTriangleMesh (obj, baseMesh ());
    saveTriangleMesh (ply, baseMesh ());
    ASSERT_EQ (runApp ("encode", {obj, "-o", psm, "-q"}, dir_).exit_code, 0);
    const std::string obj_bytes = readText (obj), ply_bytes = readText (ply), psm_bytes = readText (psm);
    fs::create_symlink ("c.obj", dir_ / "link.obj");
    const std::string same_obj = (dir_ / "." / "c.obj").string ();
    const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"encode", {obj, "-recon", obj}},
      {"encode", {(dir_ / "link.obj").string (), "-recon", same_obj}},
      {"encode", {obj, "-recon", (dir_ / "r.ply").string (), "-error", (dir_ / "r.ply").string ()}},
      {"resample", {ply, ply, "-n", "100"}},
      {"decode", {psm, (dir_ / "o.pcd").string (), "-recon", obj, obj}},
      {"decode", {psm, (dir_ / "x.ply").string (), "-recon", obj, (dir_ / "x.ply").string ()}},
      {"decode", {psm, (dir_ / "no_such_folder" / "o.pcd").string ()}},
      {"patches", {ply, ply}},
      {"keypoints", {ply, ply}},
    };
    for (const auto& [app, args] : runs)
    {
      std::vector<std::string> quiet (args);
      quiet.push_back ("-q");
      const RunResult r = runApp (app, quiet, dir_);
      EXPECT_EQ (r.exit_code, 1) << r.command;
      EXPECT_EQ (nonEmptyLines (r.err), 1) << r.command << "\n" << r.err;
      EXPECT_TRUE (r.err.find ("refusing to overwrite") != std::string::npos || r.err.find ("same file") != std::string::npos ||
                   r.err.find ("does not exist") != std::string::npos) << r.command << "\n" << r.err;
    }
    EXPECT_TRUE (readText (obj) == obj_bytes) << "the input mesh changed";
    EXPECT_TRUE (readText (ply) == ply_bytes) << "the input PLY changed";
    EXPECT_TRUE (readText (psm) == psm_bytes) << "the input model changed";
    for (const char* left : {"o.pcd", "x.ply", "r.ply"})
      EXPECT_FALSE (fs::exists (dir_ / left)) << left;

    // A FIFO is no model (opening it blocked decode forever), and a report lost to a full disk fails.
    const fs::path fifo = dir_ / "fifo.psm";
    ASSERT_EQ (::mkfifo (fifo.c_str (), 0600), 0);
    const RunResult r = runApp ("decode", {fifo.string (), (dir_ / "o.pcd").string (), "-q"}, dir_);
    EXPECT_EQ (r.exit_code, 1) << r.err;
    EXPECT_NE (r.err.find ("not a regular file"), std::string::npos) << r.err;
    if (fs::exists ("/dev/full"))
    {
      const int status = std::system ((quote (appPath ("info")) + " " + quote (obj) + " --json > /dev/full 2> /dev/null").c_str ());
      EXPECT_TRUE (WIFEXITED (status) && WEXITSTATUS (status) == 1) << status;
    }
  }

  /// Output names of 250 bytes (the file system takes 255) were refused: the temporary they are written
  /// through added ".tmp" and the pid. Every output of encode and resample is written through one.
  TEST_F (RobustnessAppsPaths, LongOutputNamesAreWritten)
  {
    const std::string obj = (dir_ / "c.obj").string ();
    saveTriangleMesh (obj, baseMesh ());
    const std::string stem = (dir_ / std::string (246, 'n')).string ();
    const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"encode", {obj, "-o", stem + ".psm", "-recon", stem + ".obj", "-q"}},
      {"resample", {obj, stem + ".pcd", "-n", "500", "-q"}},
      {"resample", {obj, stem + ".ply", "-n", "500", "-q"}},
    };
    for (const auto& [app, args] : runs)
    {
      const RunResult r = runApp (app, args, dir_);
      EXPECT_EQ (r.exit_code, 0) << r.command << "\n" << r.err;
    }
    for (const char* extension : {".psm", ".obj", ".pcd", ".ply"})
      EXPECT_TRUE (fs::exists (stem + extension)) << extension;
    for (const std::string& name : filesIn (dir_))
      EXPECT_EQ (name.find (".tmp"), std::string::npos) << name;
  }

  /// An output folder that takes no new file is refused before any work (an encode wrote its model, then
  /// failed on -recon in the same folder). The folder is made read-only with chmod, or for root, whom chmod
  /// does not stop, immutable with chattr +i; skipped where neither holds.
  TEST_F (RobustnessAppsPaths, UnwritableOutputFolderIsRefusedFirst)
  {
    const std::string obj = (dir_ / "c.obj").string ();
    saveTriangleMesh (obj, baseMesh ());
    const fs::path locked = dir_ / "locked";
    fs::create_directories (locked);
    fs::permissions (locked, fs::perms::owner_read | fs::perms::owner_exec);
    bool immutable = false;
    if (::access (locked.c_str (), W_OK) == 0)  // root
      immutable = std::system (("chattr +i " + quote (locked.string ()) + " 2> /dev/null").c_str ()) == 0;
    struct Unlock
    {
      fs::path folder;
      bool immutable;
      ~Unlock ()
      {
        if (immutable)
          std::system (("chattr -i " + quote (folder.string ())).c_str ());
        fs::permissions (folder, fs::perms::owner_all);
      }
    } unlock{locked, immutable};
    if (!immutable && ::access (locked.c_str (), W_OK) == 0)
      GTEST_SKIP () << "cannot make a folder that refuses files here (root without chattr)";
    const std::string model = (dir_ / "x.psm").string (), recon = (locked / "r.ply").string ();
    const RunResult r = runApp ("encode", {obj, "-o", model, "-recon", recon, "-q"}, dir_);
    EXPECT_EQ (r.exit_code, 1) << r.err;
    EXPECT_EQ (nonEmptyLines (r.err), 1) << r.err;
    EXPECT_NE (r.err.find ("output '" + recon + "': cannot write in the folder"), std::string::npos) << r.err;
    EXPECT_FALSE (fs::exists (model));
    EXPECT_TRUE (fs::is_empty (locked));
  }

  /// An output name one byte longer than a file name may be (255 bytes) in a folder that takes files: a
  /// portable output that fails only when it is written, after the checks.
  std::string
  unwritableName (const std::string& extension)
  {
    return std::string (256 - extension.size (), 'w') + extension;
  }

  /// A run that fails after it has written some of its outputs removes them: a failed run leaves no output
  /// (the encoded model stayed behind when -recon, -error or -png failed; resample's cloud when -png or
  /// stdout failed; decode's cloud when -recon failed; keypoints' when -responses failed; patches' when -png
  /// failed).
  TEST_F (RobustnessAppsPaths, FailedRunRemovesTheOutputsItWrote)
  {
    const std::string obj = (dir_ / "c.obj").string (), psm = (dir_ / "c.psm").string ();
    saveTriangleMesh (obj, baseMesh ());
    ASSERT_EQ (runApp ("encode", {obj, "-o", psm, "--store-vertices", "-q"}, dir_).exit_code, 0);
    const fs::path out = dir_ / "out";
    auto in_out = [&] (const std::string& name) { return (out / name).string (); };
    const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"encode", {obj, "-o", in_out ("x.psm"), "-recon", in_out (unwritableName (".ply"))}},
      {"encode", {obj, "-o", in_out ("x.psm"), "-error", in_out (unwritableName (".ply"))}},
      {"encode", {obj, "-o", in_out ("x.psm"), "-recon", in_out ("r.ply"), "-png", in_out (unwritableName (".png"))}},
      {"resample", {obj, in_out ("x.pcd"), "-n", "100", "-png", in_out (unwritableName (".png"))}},
      {"decode", {psm, in_out ("x.pcd"), "-recon", obj, in_out (unwritableName (".off"))}},
      {"decode", {psm, in_out ("x.pcd"), "-stream", "off", "-recon", obj, in_out (unwritableName (".off"))}},
      {"keypoints", {obj, in_out ("k.pcd"), "-responses", in_out (unwritableName (".ply"))}},
      {"keypoints", {obj, in_out ("k.pcd"), "-png", in_out (unwritableName (".png"))}},
      {"patches", {obj, in_out ("p.ply"), "-png", in_out (unwritableName (".png"))}},
    };
    for (const auto& [app, args] : runs)
    {
      fs::remove_all (out);
      fs::create_directories (out);
      std::vector<std::string> quiet (args);
      quiet.push_back ("-q");
      const RunResult r = runApp (app, quiet, dir_);
      checkRun (r, out, "");
      EXPECT_EQ (r.exit_code, 1) << r.command;
      EXPECT_NE (r.err.find ("could not write the file"), std::string::npos) << r.command << "\n" << r.err;
    }

    // The outputs are complete and the report is lost to a full disk: still a failure, so they go too.
    if (!fs::exists ("/dev/full"))
      return;
    const std::vector<std::pair<std::string, std::vector<std::string>>> full_runs = {
      {"resample", {obj, in_out ("f.pcd"), "-n", "100"}},
      {"resample", {obj, in_out ("f.pcd"), "-n", "100", "-stream", "off"}},
      {"decode", {psm, in_out ("f.pcd"), "-recon", obj, in_out ("r.off")}},
      {"encode", {obj, "-o", in_out ("f.psm"), "-recon", in_out ("r.ply")}},
      {"keypoints", {obj, in_out ("k.ply"), "-responses", in_out ("r.ply")}},
      {"patches", {obj, in_out ("p.ply")}},
      {"render", {obj, in_out ("r.png")}},
    };
    for (const auto& [app, args] : full_runs)
    {
      fs::remove_all (out);
      fs::create_directories (out);
      std::string command = quote (appPath (app));
      for (const std::string& a : args)
        command += " " + quote (a);
      const int status = std::system ((command + " --json > /dev/full 2> /dev/null").c_str ());
      EXPECT_TRUE (WIFEXITED (status) && WEXITSTATUS (status) == 1) << command << ": status " << status;
      EXPECT_TRUE (filesIn (out).empty ()) << command << " left " << (filesIn (out).empty () ? "" : filesIn (out).front ());
    }
  }

  /// decode's notes (here: the box holds no point) stay off stderr under --json and -q, as in the other tools.
  TEST_F (RobustnessAppsPaths, DecodeNotesAreQuietUnderJsonAndQ)
  {
    const std::string obj = (dir_ / "c.obj").string (), psm = (dir_ / "c.psm").string ();
    saveTriangleMesh (obj, baseMesh ());
    ASSERT_EQ (runApp ("encode", {obj, "-o", psm, "-q"}, dir_).exit_code, 0);
    const std::string cloud = (dir_ / "eb.pcd").string ();
    const std::vector<std::string> empty_box = {psm, cloud, "-box", "5,5,5,6,6,6", "-density", "100"};
    const RunResult noted = runApp ("decode", empty_box, dir_);
    EXPECT_EQ (noted.exit_code, 0) << noted.err;
    EXPECT_NE (noted.err.find ("no point of the model lies in the box"), std::string::npos) << "the note is gone: " << noted.err;
    for (const char* quiet : {"--json", "-q"})
    {
      std::vector<std::string> args (empty_box);
      args.push_back (quiet);
      const RunResult r = runApp ("decode", args, dir_);
      EXPECT_EQ (r.exit_code, 0) << quiet << ": " << r.err;
      EXPECT_EQ (r.err, "") << quiet;
      EXPECT_TRUE (fs::exists (cloud)) << quiet;
    }
  }

  /// keypoints names the output it cannot write, as the other tools do; it said "unexpected failure: :
  /// [pcl::PCDWriter::writeBinary] Error during open!". No temporary stays behind.
  TEST_F (RobustnessAppsPaths, KeypointsNameTheOutputTheyCannotWrite)
  {
    const std::string obj = (dir_ / "c.obj").string ();
    saveTriangleMesh (obj, baseMesh ());
    fs::create_directories (dir_ / "out");
    for (const char* extension : {".pcd", ".ply"})
    {
      const std::string output = (dir_ / "out" / unwritableName (extension)).string ();
      const RunResult r = runApp ("keypoints", {obj, output, "-q"}, dir_);
      checkRun (r, dir_ / "out", "");
      EXPECT_EQ (r.exit_code, 1) << r.command;
      // The reason follows when the system gives one (here: the name is too long for the rename).
      const std::string message = "pcl_sparse_keypoints: " + output + ": could not write the file";
      EXPECT_EQ (r.err.substr (0, message.size ()), message) << extension;
      EXPECT_EQ (nonEmptyLines (r.err), 1) << r.err;
    }
  }

  /// A full disk: PCL's binary PLY writer returned success and the tool kept a cut-short keypoint file (exit
  /// 0). Needs a 4 kB tmpfs, so root with the right to mount; skipped elsewhere.
  TEST_F (RobustnessAppsPaths, KeypointsOnAFullDiskFailAndLeaveNoFile)
  {
    TriangleMesh bumpy = makeIcosphere (4);  // 2562 vertices, radii jittered: hundreds of local maxima
    std::uint32_t state = 7;
    for (Eigen::Vector3d& v : bumpy.vertices)
    {
      state = state * 1664525u + 1013904223u;
      v *= 1.0 + 0.05 * static_cast<double> (state >> 24) / 255.0;
    }
    const std::string obj = (dir_ / "bumpy.obj").string ();
    saveTriangleMesh (obj, bumpy);
    const std::string roomy = (dir_ / "k.ply").string ();
    ASSERT_EQ (runApp ("keypoints", {obj, roomy, "-fraction", "1", "-q"}, dir_).exit_code, 0);
    ASSERT_GT (fs::file_size (roomy), 5000u) << "the keypoints must not fit in the 4 kB disk";  // measured 6653
    const fs::path full = dir_ / "full";
    fs::create_directories (full);
    if (std::system (("mount -t tmpfs -o size=4k tmpfs " + full.string () + " 2> /dev/null").c_str ()) != 0)
      GTEST_SKIP () << "cannot mount a small tmpfs here (needs root and CAP_SYS_ADMIN)";
    const std::string output = (full / "k.ply").string ();
    const RunResult r = runApp ("keypoints", {obj, output, "-fraction", "1", "-q"}, dir_);
    const bool left = fs::exists (output) || !fs::is_empty (full);
    std::system (("umount " + full.string ()).c_str ());
    EXPECT_EQ (r.exit_code, 1) << r.command;
    EXPECT_EQ (r.err, "pcl_sparse_keypoints: " + output + ": could not write the file (No space left on device)\n");
    EXPECT_FALSE (left) << "a cut-short or temporary file stayed";
  }

  /// A spacing no resampling can use is refused with the options, before the input is read and encoded (it
  /// failed only after encoding, minutes on a large input): here the input is not even a mesh, and the error
  /// must name the spacing.
  TEST_F (RobustnessAppsPaths, ResampleSpacingIsCheckedBeforeTheInputIsRead)
  {
    const std::string broken = (dir_ / "broken.obj").string ();
    std::ofstream (broken) << "v 0 0 0\nv 1 0\nf 1 2 3\n";
    for (const auto& [spacing, printed] : {std::pair<std::string, std::string> {"1e-200", "1e-200"}, {"1e200", "1e+200"}})
    {
      const RunResult r = runApp ("resample", {broken, (dir_ / "o.pcd").string (), "-spacing", spacing, "-q"}, dir_);
      EXPECT_EQ (r.exit_code, 1) << r.err;
      EXPECT_NE (r.err.find ("spacing " + printed), std::string::npos) << r.err;
      EXPECT_EQ (r.err.find ("broken.obj"), std::string::npos) << r.err;
      EXPECT_FALSE (fs::exists (dir_ / "o.pcd"));
    }
  }

  /// pcl_sparse_patches names the option behind a field out of range ("-min-size 0" was refused with
  /// "(angles are given in degrees)").
  TEST_F (RobustnessAppsPaths, PatchesNameTheOptionOutOfRange)
  {
    const std::string obj = (dir_ / "c.obj").string (), out = (dir_ / "p.ply").string ();
    saveTriangleMesh (obj, baseMesh ());
    RunResult r = runApp ("patches", {obj, out, "-min-size", "0", "-q"}, dir_);
    EXPECT_EQ (r.exit_code, 1) << r.err;
    EXPECT_NE (r.err.find ("(option -min-size)"), std::string::npos) << r.err;
    EXPECT_EQ (r.err.find ("degrees"), std::string::npos) << r.err;
    r = runApp ("patches", {obj, out, "-eta", "0.5", "-q"}, dir_);
    EXPECT_EQ (r.exit_code, 1) << r.err;
    EXPECT_NE (r.err.find ("(option -eta)"), std::string::npos) << r.err;
    EXPECT_EQ (r.err.find ("degrees"), std::string::npos) << r.err;
    EXPECT_FALSE (fs::exists (out));
  }

  /// pcl_sparse_encode names the option out of range, before reading the input ("-f 2" said
  /// "coding.nyquist_factor = 2"; "-tolerance 1e-12" failed after the whole encoding, at the file's seeds).
  TEST_F (RobustnessAppsPaths, EncodeNamesTheOptionOutOfRange)
  {
    const std::string obj = (dir_ / "c.obj").string (), out = (dir_ / "m.psm").string ();
    saveTriangleMesh (obj, baseMesh ());
    const std::vector<std::pair<std::string, std::string>> cases = {
      {"-f", "2"}, {"-L", "0"}, {"-eps", "1"}, {"-min-samples", "100001"}, {"-sigma", "-1"}, {"-tolerance", "1e-12"}};
    for (const auto& [option, value] : cases)
    {
      const RunResult r = runApp ("encode", {obj, "-o", out, option, value, "-q"}, dir_);
      EXPECT_EQ (r.exit_code, 1) << r.err;
      EXPECT_NE (r.err.find ("option " + option + ": " + value), std::string::npos) << r.err;
      EXPECT_EQ (r.err.find ("coding."), std::string::npos) << r.err;
      EXPECT_FALSE (fs::exists (out));
    }
    const RunResult fine = runApp ("encode", {obj, "-o", out, "-tolerance", "1e-8", "-q"}, dir_);
    EXPECT_EQ (fine.exit_code, 0) << fine.err;
    // A model given where a surface is expected is named for what it is ("unknown input extension").
    const RunResult model = runApp ("encode", {out, "-o", (dir_ / "again.psm").string (), "-q"}, dir_);
    EXPECT_EQ (model.exit_code, 1) << model.err;
    EXPECT_NE (model.err.find ("m.psm: a model file, not a mesh or a cloud (pcl_sparse_decode and pcl_sparse_resample "
                               "read it)"),
               std::string::npos)
      << model.err;
  }

  /// pcl_sparse_info names every kind of file it reads when it refuses an extension (it listed the meshes' four).
  TEST_F (RobustnessAppsPaths, InfoListsEveryFormatItReads)
  {
    const std::string text = (dir_ / "notes.txt").string ();
    std::ofstream (text) << "v 0 0 0\n";
    const RunResult r = runApp ("info", {text, "-q"}, dir_);
    EXPECT_EQ (r.exit_code, 1) << r.err;
    for (const char* extension : {".obj", ".psm", ".pcd", ".xyz"})
      EXPECT_NE (r.err.find (extension), std::string::npos) << r.err;
  }

  /// A write over the file-size limit ends the tool by SIGXFSZ: the temporary goes as on Ctrl-C (it left
  /// OUT.pcd.tmpPID, 10 MB under `ulimit -f 10000`). SIGPIPE, a cloud piped into a reader that quit, takes the
  /// same handler; when it comes depends on the reader, so it is not timed here.
  TEST_F (RobustnessAppsPaths, FileSizeLimitLeavesNoTemporary)
  {
    fs::create_directories (dir_ / "out");
    const std::string obj = (dir_ / "c.obj").string ();
    saveTriangleMesh (obj, baseMesh ());
    for (const std::string stream : {"on", "off"})
    {
      // 2000 blocks of 512 or 1024 bytes: a few MB, under the 1M-point cloud's 28 MB.
      const std::string command = "ulimit -f 2000; exec " + quote (appPath ("resample")) + " " + quote (obj) + " " +
                                  quote ((dir_ / "out" / "big.pcd").string ()) + " -n 1000000 -q -stream " + stream +
                                  " 2> /dev/null";
      const int status = std::system (("sh -c " + quote (command)).c_str ());
      ASSERT_TRUE (WIFEXITED (status)) << status;
      // Ended by SIGXFSZ (the shell's 128 + signal), or the write's error and exit 1; not another signal (a crash).
      EXPECT_TRUE (WEXITSTATUS (status) == 128 + SIGXFSZ || WEXITSTATUS (status) == 1)
        << "-stream " << stream << ": exit " << WEXITSTATUS (status) << "; the cloud cannot fit under the limit";
      EXPECT_TRUE (filesIn (dir_ / "out").empty ()) << "-stream " << stream << ": " << filesIn (dir_ / "out").front ();
    }
  }

  /// Ctrl-C during a long write removes the temporary (a streamed cloud of 20 M points stayed behind as
  /// OUT.ply.tmpPID, 58 MB and growing when the review stopped it).
  TEST_F (RobustnessAppsPaths, InterruptedWriteLeavesNoTemporary)
  {
    fs::create_directories (dir_ / "out");
    const std::string obj = (dir_ / "c.obj").string (), psm = (dir_ / "c.psm").string ();
    saveTriangleMesh (obj, baseMesh ());
    ASSERT_EQ (runApp ("encode", {obj, "-o", psm, "-q"}, dir_).exit_code, 0);
    auto temporaries = [&] { return filesIn (dir_ / "out").size (); };
    const pcl_sparse_test::InterruptedRun run = pcl_sparse_test::interruptOnceReady (
      {appPath ("decode"), psm, (dir_ / "out" / "big.ply").string (), "-n", "200000000", "-q"}, [&] { return temporaries () > 0; },
      {}, 50000);
    ASSERT_TRUE (run.ready) << "the decoder never made its temporary";
    EXPECT_TRUE (WIFSIGNALED (run.status) && WTERMSIG (run.status) == SIGINT) << "status " << run.status;
    EXPECT_EQ (temporaries (), 0u) << "left: " << (filesIn (dir_ / "out").empty () ? "" : filesIn (dir_ / "out")[0]);
  }
} // namespace

