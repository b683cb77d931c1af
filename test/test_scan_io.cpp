// Scan input (issue 12, points 1-2): loadScanCloud for PCD (ascii, binary, binary_compressed, double x y z),
// PLY (vertices, range grids) and XYZ, the cleaning counts (non-finite, at the sensor, exact duplicates),
// the local frame for map coordinates, toScanCloud for PCL's point types, bad files, and the real scans in
// ../shared/clouds against the counts of their README.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/scan_cleaning.h>
#include <pcl_sparse/io/scan_conversion.h>
#include <pcl_sparse/io/scan_io.h>
#include <pcl_sparse/io/mesh_io.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <gtest/gtest.h>

#include "error_message.h"
#include "shared_data.h"
#include "test_file_helpers.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <sys/stat.h>

using namespace pcl_sparse;
using namespace pcl_sparse_test;

#ifndef PCL_SPARSE_SHARED_CLOUDS
#define PCL_SPARSE_SHARED_CLOUDS ""
#endif

namespace
{
  const double kNaN = std::numeric_limits<double>::quiet_NaN ();
  const float kNaNf = std::numeric_limits<float>::quiet_NaN ();

  /// Loads \a path expecting a pcl_sparse::Error whose one-line message names the file and contains \a problem.
  void
  expectRefused (const std::string& path, const std::string& problem = "")
  {
    SCOPED_TRACE (path);
    try
    {
      ScanCloud scan;
      loadScanCloud (path, scan);
      ADD_FAILURE () << "loaded without error (" << scan.size () << " points)";
    }
    catch (const Error& e)
    {
      const std::string message = e.what ();
      EXPECT_NE (message.find (path), std::string::npos) << message;
      EXPECT_EQ (message.find ('\n'), std::string::npos) << message;
      EXPECT_NE (message.find (problem), std::string::npos) << "message: " << message << "\nexpected: " << problem;
    }
  }

  void
  expectCounts (const ScanCleaningReport& r, std::size_t input, std::size_t non_finite, std::size_t at_sensor,
                std::size_t duplicates, std::size_t kept)
  {
    EXPECT_EQ (r.input_points, input);
    EXPECT_EQ (r.non_finite, non_finite);
    EXPECT_EQ (r.at_sensor_origin, at_sensor);
    EXPECT_EQ (r.duplicates_merged, duplicates);
    EXPECT_EQ (r.kept, kept);
    EXPECT_EQ (r.input_points, r.non_finite + r.at_sensor_origin + r.duplicates_merged + r.kept);
  }

  /// An organized 4 x 3 cloud with every trap: 3 NaN points (one with only z NaN), 1 Inf, 2 points at
  /// (0, 0, 0), a position stored three times and one twice. Colours tell the points apart.
  ///   expected: 12 points, 4 non-finite, 2 at the sensor, 3 duplicates merged, 3 kept (indices 0, 1, 3)
  pcl::PointCloud<pcl::PointXYZRGBA>
  trapGrid ()
  {
    pcl::PointCloud<pcl::PointXYZRGBA> cloud (4, 3);
    const float values[12][3] = {{1, 2, 3},     {0.5f, 0.25f, 4}, {kNaNf, 0, 0},  {-1, -2, 5},
                                 {1, 2, 3},     {0, 0, 0},        {0, 0, kNaNf},  {0.5f, 0.25f, 4},
                                 {kNaNf, kNaNf, kNaNf}, {1, 2, 3}, {std::numeric_limits<float>::infinity (), 1, 1}, {0, 0, 0}};
    for (std::size_t i = 0; i < 12; ++i)
    {
      cloud[i].x = values[i][0];
      cloud[i].y = values[i][1];
      cloud[i].z = values[i][2];
      cloud[i].rgba = 0xff000000u | static_cast<std::uint32_t> (i * 0x010203);
    }
    cloud.is_dense = true;  // a lie, as in real files
    return cloud;
  }

  void
  expectTrapGrid (const ScanCloud& scan)
  {
    expectCounts (scan.report, 12, 4, 2, 3, 3);
    EXPECT_EQ (scan.width, 4u);
    EXPECT_EQ (scan.height, 3u);
    EXPECT_TRUE (scan.isOrganized ());
    ASSERT_EQ (scan.size (), 3u);
    ASSERT_EQ (scan.indices, (std::vector<std::size_t>{0, 1, 3}));
    ASSERT_EQ (scan.colors.size (), 3u);
    EXPECT_EQ (scan.colors[2], 0xff000000u | 3u * 0x010203u);
    EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (1, 2, 3));
    EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (0.5, 0.25, 4));
    EXPECT_EQ (scan.worldPosition (2), Eigen::Vector3d (-1, -2, 5));
  }

  std::string
  asciiPly (const std::string& header_extra, const std::string& properties, int vertices, const std::string& body)
  {
    return "ply\nformat ascii 1.0\n" + header_extra + "element vertex " + std::to_string (vertices) + "\n" + properties +
           body;
  }

  std::string
  sharedCloud (const std::string& name)
  {
    return std::string (PCL_SPARSE_SHARED_CLOUDS) + "/" + name;
  }
} // namespace

// ---- cleaning, on data in memory ------------------------------------------------------------------------

TEST (ScanCleaning, CountsEachCauseAndKeepsTheFirstOfDuplicates)
{
  ScanCloud scan;
  scan.positions = {{1, 2, 3}, {0, 0, 0}, {kNaN, 0, 0}, {1, 2, 3}, {4, 5, 6}, {0, 0, -0.0}, {0, 0, std::numeric_limits<double>::infinity ()},
                    {4, 5, 6}, {1, 2, 3}, {7, 8, 9}};
  scan.intensities = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  scan.normals.assign (10, Eigen::Vector3d::UnitZ ());
  scan.normals[4] = Eigen::Vector3d::UnitX ();
  const ScanCleaningReport report = cleanScan (scan);
  expectCounts (report, 10, 2, 2, 3, 3);
  expectCounts (scan.report, 10, 2, 2, 3, 3);
  EXPECT_EQ (report.finitePoints (), 8u);
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 4, 9}));  // empty indices were 0, 1, 2, ...
  EXPECT_EQ (scan.intensities, (std::vector<float>{0, 4, 9}));
  EXPECT_EQ (scan.normals, (std::vector<Eigen::Vector3d>{Eigen::Vector3d::UnitZ (), Eigen::Vector3d::UnitX (), Eigen::Vector3d::UnitZ ()}));
  EXPECT_EQ (scan.positions, (std::vector<Eigen::Vector3d>{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}));

  // Cleaning a clean scan changes nothing.
  const ScanCloud before = scan;
  expectCounts (cleanScan (scan), 3, 0, 0, 0, 3);
  EXPECT_EQ (scan.positions, before.positions);
  EXPECT_EQ (scan.indices, before.indices);
}

TEST (ScanCleaning, DuplicatesKeepTheEarliestWhateverTheOrder)
{
  // Many copies in shuffled order: the kept one of each position is its first in file order.
  std::mt19937 random (42);
  ScanCloud scan;
  std::vector<std::size_t> first (20, std::numeric_limits<std::size_t>::max ());
  for (std::size_t i = 0; i < 500; ++i)
  {
    const int k = static_cast<int> (random () % 20);
    scan.positions.emplace_back (k, -k, 0.5 * k + 1);
    first[static_cast<std::size_t> (k)] = std::min (first[static_cast<std::size_t> (k)], i);
  }
  expectCounts (cleanScan (scan), 500, 0, 0, 480, 20);
  std::vector<std::size_t> expected = first;
  std::sort (expected.begin (), expected.end ());
  EXPECT_EQ (scan.indices, expected);
}

TEST (ScanCleaning, DuplicatesAreExactPositionsWithMinusZeroAsZero)
{
  // -0 and 0 compare equal: one point. Positions one ulp apart, or with the coordinates swapped, are not.
  ScanCloud scan;
  const double next = std::nextafter (1.0, 2.0);
  scan.positions = {{0.0, 1.0, 2.0}, {-0.0, 1.0, 2.0}, {0.0, next, 2.0}, {1.0, 0.0, 2.0}, {0.0, 1.0, 2.0},
                    {1.0, -0.0, 2.0}, {1.0, 0.0, -2.0}};
  expectCounts (cleanScan (scan), 7, 0, 0, 3, 4);
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 2, 3, 6}));
}

TEST (ScanCleaning, SensorOriginAndOptions)
{
  ScanCloud scan;
  scan.origin = Eigen::Vector3d (100, 200, 300);
  scan.sensor_origin = Eigen::Vector3d (101, 200, 300);  // local (1, 0, 0)
  scan.has_sensor_pose = true;
  scan.positions = {{1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, 0}};
  ScanCloud copy = scan;
  expectCounts (cleanScan (copy), 5, 0, 2, 1, 2);
  EXPECT_EQ (copy.indices, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ (copy.positions, (std::vector<Eigen::Vector3d>{{0, 0, 0}, {2, 0, 0}}));  // (0, 0, 0) is a point here

  ScanCleaningOptions keep_all;
  keep_all.drop_at_sensor_origin = false;
  keep_all.merge_duplicates = false;
  copy = scan;
  expectCounts (cleanScan (copy, keep_all), 5, 0, 0, 0, 5);
  keep_all.merge_duplicates = true;
  copy = scan;
  expectCounts (cleanScan (copy, keep_all), 5, 0, 0, 2, 3);
  EXPECT_EQ (copy.indices, (std::vector<std::size_t>{0, 1, 3}));

  // A sensor position the caller gives (file coordinates, as -viewpoint) replaces the file's: the points there go,
  // those at the file's sensor origin stay.
  ScanCleaningOptions given;
  given.sensor_position = Eigen::Vector3d (102, 200, 300);  // local (2, 0, 0)
  copy = scan;
  expectCounts (cleanScan (copy, given), 5, 0, 2, 1, 2);
  EXPECT_EQ (copy.indices, (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ (cleaningSensorPosition (given, scan.sensor_origin), Eigen::Vector3d (102, 200, 300));
  EXPECT_EQ (cleaningSensorPosition (ScanCleaningOptions (), scan.sensor_origin), scan.sensor_origin);
}

TEST (ScanCleaning, RefusesAttributesOfTheWrongSize)
{
  ScanCloud scan;
  scan.positions = {{1, 2, 3}, {4, 5, 6}};
  // Refused with the attribute named and counted, not with some other error (an out-of-range read, say).
  const auto refusal = [&] { return pcl_sparse_test::errorMessage ([&] { cleanScan (scan); }); };
  scan.colors = {1};
  EXPECT_EQ (refusal (), "ScanCloud: colors has 1 entries for 2 points");
  scan.colors.clear ();
  scan.indices = {0, 1, 2};
  EXPECT_EQ (refusal (), "ScanCloud: indices has 3 entries for 2 points");
  ScanCloud empty;
  expectCounts (cleanScan (empty), 0, 0, 0, 0, 0);
}

// ---- local frame ----------------------------------------------------------------------------------------

TEST (ScanFrame, OriginIsARoundedCentre)
{
  EXPECT_EQ (localFrameOrigin ({}), Eigen::Vector3d::Zero ());
  EXPECT_EQ (localFrameOrigin ({{kNaN, 1, 1}}), Eigen::Vector3d::Zero ());
  EXPECT_EQ (localFrameOrigin ({{3.3, -2, 7}, {3.3, -2, 7}}), Eigen::Vector3d (3.3, -2, 7));
  // Box [0, 10] x [100, 101] x [-5, -5]: side 10, step 2^(3+1-8) = 1/16; centre (5, 100.5, -5), of which only
  // y is farther than 2 sides from 0.
  EXPECT_EQ (localFrameOrigin ({{0, 100, -5}, {10, 101, -5}, {kNaN, 0, 0}}), Eigen::Vector3d (0, 100.5, 0));
  EXPECT_EQ (localFrameOrigin ({{0, 100.03, -5}, {10, 101, -5}}), Eigen::Vector3d (0, 100.5, 0));
  // Map coordinates: side 348 -> step 2; centre rounded to even metres (heights stay: 345 < 2 x 348).
  const Eigen::Vector3d o = localFrameOrigin ({{512600.3, 5403500.7, 300.1}, {512948.3, 5403800.2, 390.0}});
  EXPECT_EQ (o, Eigen::Vector3d (512774, 5403650, 0));
}

TEST (ScanFrame, MapCoordinatesSurviveInDouble)
{
  // Double map coordinates with all their digits: local positions are small and origin + p is exact.
  std::mt19937_64 random (42);
  std::uniform_real_distribution<double> east (512600.0, 512950.0), north (5403500.0, 5403850.0), up (280.0, 400.0);
  ScanCloud scan;
  for (int i = 0; i < 1000; ++i)
    scan.positions.emplace_back (east (random), north (random), up (random));
  const std::vector<Eigen::Vector3d> world = scan.positions;
  centreScan (scan);
  EXPECT_NE (scan.origin, Eigen::Vector3d::Zero ());
  for (std::size_t i = 0; i < world.size (); ++i)
  {
    ASSERT_EQ (scan.worldPosition (i), world[i]) << i;
    ASSERT_LT (scan.positions[i].head<2> ().cwiseAbs ().maxCoeff (), 200.0);  // heights stay (near 0 for their range)
  }
  EXPECT_EQ (worldPositions (scan), world);
}

TEST (ScanFrame, RoundTripIsExactForAnyBox)
{
  // Boxes near 0, straddling it, and far from it, tiny to huge, in double and in float: origin + p is the
  // input, bit for bit.
  std::mt19937_64 random (7);
  int boxes = 0;
  for (double offset : {0.0, 1e-3, 0.7, 3.0, 1e3, 5.4e6, -2.5e8, 1e15})
    for (double side : {1e-6, 0.01, 1.0, 3.0, 1e3, 1e6})
      for (bool as_float : {false, true})
      {
        std::uniform_real_distribution<double> coordinate (offset - side / 2, offset + side / 2);
        ScanCloud scan;
        for (int i = 0; i < 200; ++i)
        {
          Eigen::Vector3d p (coordinate (random), coordinate (random), -coordinate (random));
          if (as_float)
            p = p.cast<float> ().cast<double> ();
          scan.positions.push_back (p);
        }
        const std::vector<Eigen::Vector3d> world = scan.positions;
        centreScan (scan);
        for (std::size_t i = 0; i < world.size (); ++i)
          ASSERT_EQ (scan.worldPosition (i), world[i]) << "offset " << offset << " side " << side << " point " << i;
        ++boxes;
      }
  EXPECT_EQ (boxes, 96);
}

// ---- PCD ------------------------------------------------------------------------------------------------

TEST (ScanPcd, AsciiBinaryCompressedOrganizedWithTraps)
{
  TempDir dir;
  pcl::PointCloud<pcl::PointXYZRGBA> cloud = trapGrid ();
  const std::string paths[3] = {dir.file ("a.pcd"), dir.file ("b.pcd"), dir.file ("c.pcd")};
  ASSERT_EQ (pcl::io::savePCDFileASCII (paths[0], cloud), 0);
  ASSERT_EQ (pcl::io::savePCDFileBinary (paths[1], cloud), 0);
  ASSERT_EQ (pcl::io::savePCDFileBinaryCompressed (paths[2], cloud), 0);
  for (const std::string& path : paths)
  {
    SCOPED_TRACE (path);
    ScanCloud scan;
    loadScanCloud (path, scan);
    expectTrapGrid (scan);
    EXPECT_EQ (scan.fields, (std::vector<std::string>{"x", "y", "z", "rgba"}));
    EXPECT_TRUE (scan.has_sensor_pose);
    EXPECT_TRUE (scan.normals.empty ());
    EXPECT_TRUE (scan.intensities.empty ());

    ScanLoadOptions raw;
    raw.clean = false;
    loadScanCloud (path, scan, raw);
    expectCounts (scan.report, 12, 0, 0, 0, 12);
    ASSERT_EQ (scan.size (), 12u);
    ASSERT_EQ (scan.indices.size (), 12u);
    ASSERT_EQ (scan.colors.size (), 12u);
    EXPECT_TRUE (std::isnan (scan.positions[6].z ()));
    EXPECT_TRUE (std::isinf (scan.positions[10].x ()));
    EXPECT_EQ (scan.indices[11], 11u);
    EXPECT_EQ (scan.colors[11], 0xff000000u | 11u * 0x010203u);
  }
}

TEST (ScanPcd, ViewpointIsTheSensorOrigin)
{
  // A no-return point at the sensor (2, 3, 4), and one at (0, 0, 0), which is then a real point.
  TempDir dir;
  pcl::PointCloud<pcl::PointXYZI> cloud;
  for (const Eigen::Vector3f& p : {Eigen::Vector3f (2, 3, 4), Eigen::Vector3f (0, 0, 0), Eigen::Vector3f (2, 3, 4.5f)})
  {
    pcl::PointXYZI q;
    q.getVector3fMap () = p;
    q.intensity = p.z ();
    cloud.push_back (q);
  }
  cloud.sensor_origin_ = Eigen::Vector4f (2, 3, 4, 0);
  cloud.sensor_orientation_ = Eigen::Quaternionf (0, 1, 0, 0);
  const std::string path = dir.file ("v.pcd");
  ASSERT_EQ (pcl::io::savePCDFileBinary (path, cloud), 0);
  ScanCloud scan;
  loadScanCloud (path, scan);
  expectCounts (scan.report, 3, 0, 1, 0, 2);
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{1, 2}));
  ASSERT_EQ (scan.size (), 2u);
  EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (0, 0, 0));
  EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (2, 3, 4.5));
  EXPECT_EQ (scan.intensities, (std::vector<float>{0.0f, 4.5f}));
  EXPECT_EQ (scan.sensor_origin, Eigen::Vector3d (2, 3, 4));
  EXPECT_EQ (scan.sensor_orientation.coeffs (), Eigen::Vector4d (1, 0, 0, 0));  // x y z w
  EXPECT_FALSE (scan.isOrganized ());
  EXPECT_EQ (scan.width, 3u);
}

TEST (ScanPcd, NormalsAndPackedRgb)
{
  TempDir dir;
  pcl::PointCloud<pcl::PointXYZRGBNormal> cloud;
  for (int i = 0; i < 5; ++i)
  {
    pcl::PointXYZRGBNormal p;
    p.x = 0.1f * i;
    p.y = 1.0f;
    p.z = 2.0f;
    p.normal_x = 0;
    p.normal_y = 0.6f;
    p.normal_z = -0.8f;
    p.rgba = 0x00102030u + static_cast<std::uint32_t> (i);  // alpha 0: as float "rgb", a denormal
    p.curvature = 0;
    cloud.push_back (p);
  }
  const std::string path = dir.file ("n.pcd");
  ASSERT_EQ (pcl::io::savePCDFileBinaryCompressed (path, cloud), 0);
  ScanCloud scan;
  loadScanCloud (path, scan);
  expectCounts (scan.report, 5, 0, 0, 0, 5);
  // Every point: its position, normal and colour (alpha 0 kept), not only one of each.
  ASSERT_EQ (scan.size (), 5u);
  ASSERT_EQ (scan.normals.size (), 5u);
  ASSERT_EQ (scan.colors.size (), 5u);
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  for (std::size_t i = 0; i < 5; ++i)
  {
    EXPECT_EQ (scan.worldPosition (i), Eigen::Vector3d (cloud[i].x, 1.0, 2.0)) << i;
    EXPECT_EQ (scan.normals[i], Eigen::Vector3d (0, 0.6f, -0.8f)) << i;
    EXPECT_EQ (scan.colors[i], 0x00102030u + i) << i;
  }
  EXPECT_TRUE (scan.intensities.empty ());
  EXPECT_EQ (scan.fields, (std::vector<std::string>{"x", "y", "z", "rgb", "normal_x", "normal_y", "normal_z", "curvature"}));
}

namespace
{
  /// A PCLPointCloud2 with x y z as FLOAT64 (and an intensity float between them).
  pcl::PCLPointCloud2
  doubleBlob (const std::vector<Eigen::Vector3d>& points)
  {
    pcl::PCLPointCloud2 blob;
    const char* names[4] = {"x", "intensity", "y", "z"};
    const std::uint32_t offsets[4] = {0, 8, 12, 20};
    for (int k = 0; k < 4; ++k)
    {
      pcl::PCLPointField field;
      field.name = names[k];
      field.offset = offsets[k];
      field.datatype = k == 1 ? pcl::PCLPointField::FLOAT32 : pcl::PCLPointField::FLOAT64;
      field.count = 1;
      blob.fields.push_back (field);
    }
    blob.point_step = 28;
    blob.width = static_cast<std::uint32_t> (points.size ());
    blob.height = 1;
    blob.row_step = blob.point_step * blob.width;
    blob.is_dense = true;
    for (const Eigen::Vector3d& p : points)
    {
      std::string record;
      put (record, p.x ());
      put (record, 7.5f);
      put (record, p.y ());
      put (record, p.z ());
      blob.data.insert (blob.data.end (), record.begin (), record.end ());
    }
    return blob;
  }
} // namespace

TEST (ScanPcd, DoubleCoordinatesAreReadAtTheirPrecision)
{
  // PCL 1.13 reads TYPE F SIZE 8 x y z into PointXYZ as zeros; loadScanCloud reads the doubles, and map
  // coordinates come back exactly from the local frame.
  const std::vector<Eigen::Vector3d> points = {{512734.123456789012, 5403612.987654321098, 312.000001},
                                               {512734.123456789012, 5403612.987654321098, 312.000001},
                                               {512701.5000000001, 5403599.25, 298.75},
                                               {0, 0, 0},
                                               {512950.0625, 5403850.3, 401.1}};
  TempDir dir;
  const pcl::PCLPointCloud2 blob = doubleBlob (points);
  pcl::PCDWriter writer;
  const std::string binary = dir.file ("d_binary.pcd"), compressed = dir.file ("d_compressed.pcd");
  ASSERT_EQ (writer.writeBinary (binary, blob), 0);
  ASSERT_EQ (writer.writeBinaryCompressed (compressed, blob), 0);
  std::string ascii_text = "# .PCD v0.7\nVERSION 0.7\nFIELDS x intensity y z\nSIZE 8 4 8 8\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                           "WIDTH 5\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 5\nDATA ascii\n";
  for (const Eigen::Vector3d& p : points)
  {
    char line[128];
    std::snprintf (line, sizeof (line), "%.17g 7.5 %.17g %.17g\n", p.x (), p.y (), p.z ());
    ascii_text += line;
  }
  const std::string ascii = dir.file ("d_ascii.pcd");
  writeBytes (ascii, ascii_text);
  for (const std::string& path : {binary, compressed, ascii})
  {
    SCOPED_TRACE (path);
    ScanCloud scan;
    loadScanCloud (path, scan);
    expectCounts (scan.report, 5, 0, 1, 1, 3);
    EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 2, 4}));
    ASSERT_EQ (scan.size (), 3u);
    for (std::size_t i = 0; i < scan.size (); ++i)
    {
      EXPECT_EQ (scan.worldPosition (i), points[scan.indices[i]]) << i;
      EXPECT_LT (scan.positions[i].head<2> ().norm (), 300.0);
    }
    EXPECT_EQ (scan.intensities, (std::vector<float>{7.5f, 7.5f, 7.5f}));
  }
}

// ---- XYZ ------------------------------------------------------------------------------------------------

TEST (ScanXyz, PositionsWithAndWithoutNormals)
{
  TempDir dir;
  writeBytes (dir.file ("p.xyz"), "# exported\n1 2 3\n\n4.5 -6 7e-3   # a comment\r\n0 0 0\nnan 1 1\n1 2 3\n+8 9 10");
  ScanCloud scan;
  loadScanCloud (dir.file ("p.xyz"), scan);
  expectCounts (scan.report, 6, 1, 1, 1, 3);
  EXPECT_EQ (scan.fields, (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_TRUE (scan.normals.empty ());
  EXPECT_FALSE (scan.has_sensor_pose);
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 1, 5}));
  ASSERT_EQ (scan.size (), 3u);
  EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (1, 2, 3));
  EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (4.5, -6, 7e-3));
  EXPECT_EQ (scan.worldPosition (2), Eigen::Vector3d (8, 9, 10));

  // The same ScanCloud loaded again: every figure is the new file's (none left from the one before).
  writeBytes (dir.file ("n.XYZ"), "1 2 3 0 0 1\n4 5 6 0 1 0\n1 2 3 1 0 0\n");
  loadScanCloud (dir.file ("n.XYZ"), scan);
  expectCounts (scan.report, 3, 0, 0, 1, 2);
  EXPECT_EQ (scan.fields, (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz"}));
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 1}));
  ASSERT_EQ (scan.size (), 2u);
  EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (1, 2, 3));
  EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (4, 5, 6));
  ASSERT_EQ (scan.normals.size (), 2u);
  EXPECT_EQ (scan.normals[0], Eigen::Vector3d (0, 0, 1));
  EXPECT_EQ (scan.normals[1], Eigen::Vector3d (0, 1, 0));

  // Digits beyond float's survive.
  writeBytes (dir.file ("utm.xyz"), "512734.123456789 5403612.987654321 312.000001\n512735.5 5403613.25 313\n");
  loadScanCloud (dir.file ("utm.xyz"), scan);
  expectCounts (scan.report, 2, 0, 0, 0, 2);
  EXPECT_EQ (scan.fields, (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_TRUE (scan.normals.empty ()) << "the normals of n.XYZ stayed";
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 1}));
  ASSERT_EQ (scan.size (), 2u);
  EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (512734.123456789, 5403612.987654321, 312.000001));
  EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (512735.5, 5403613.25, 313));
  EXPECT_LT (scan.positions[0].norm (), 10.0);  // in a local frame near the points
}

TEST (ScanXyz, BadLinesAreRefused)
{
  TempDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {"1 2 3\n4 5\n", ":2: 2 values on an XYZ line, the lines before have 3"},
      {"1 2 3 4\n", ":1: 4 values"},
      {"1 2 3 0 0 1\n1 2 3\n", ":2: 3 values"},
      {"1 2 3 4 5 6 7\n", "more than 6 values"},
      {"1 2 x\n", "bad XYZ value 'x'"},
      {"1,2,3\n", "bad XYZ value"},
      {"# only a comment\n", "no points"},
  };
  int k = 0;
  for (const auto& [text, problem] : cases)
  {
    const std::string path = dir.file ("bad" + std::to_string (k++) + ".xyz");
    writeBytes (path, text);
    expectRefused (path, problem);
  }
  std::string with_nul ("1 2 3\n4 5 6\0", 12);
  writeBytes (dir.file ("nul.xyz"), with_nul);
  expectRefused (dir.file ("nul.xyz"), "binary data");
}

// ---- PLY ------------------------------------------------------------------------------------------------

TEST (ScanPly, VerticesWithNormalsColoursAndIntensity)
{
  TempDir dir;
  const std::string properties = "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                                 "property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                                 "property float scalar_intensity\nend_header\n";
  writeBytes (dir.file ("a.ply"), asciiPly ("", properties, 4,
                                            "1 2 3 0 0 1 255 128 0 0.5\n0 0 0 0 0 1 1 2 3 0\n"
                                            "1 2 3 1 0 0 9 9 9 9\n-1 2.5 3 0 1 0 10 20 30 0.25\n"));
  // The same vertices as binary big endian, with a face element after them (ignored).
  std::string binary = "ply\nformat binary_big_endian 1.0\nelement vertex 4\n" + properties.substr (0, properties.size () - 11) +
                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[4][7] = {{1, 2, 3, 0, 0, 1, 0.5f}, {0, 0, 0, 0, 0, 1, 0}, {1, 2, 3, 1, 0, 0, 9}, {-1, 2.5f, 3, 0, 1, 0, 0.25f}};
  const std::uint8_t c[4][3] = {{255, 128, 0}, {1, 2, 3}, {9, 9, 9}, {10, 20, 30}};
  for (int i = 0; i < 4; ++i)
  {
    for (int k = 0; k < 6; ++k)
      put (binary, v[i][k], true);
    for (int k = 0; k < 3; ++k)
      put (binary, c[i][k], true);
    put (binary, v[i][6], true);
  }
  put (binary, std::uint8_t (3));
  for (int index : {0, 2, 3})
    put (binary, index, true);
  writeBytes (dir.file ("b.ply"), binary);
  for (const char* name : {"a.ply", "b.ply"})
  {
    SCOPED_TRACE (name);
    ScanCloud scan;
    loadScanCloud (dir.file (name), scan);
    expectCounts (scan.report, 4, 0, 1, 1, 2);
    EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 3}));
    ASSERT_EQ (scan.size (), 2u);
    EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (1, 2, 3));
    EXPECT_FALSE (scan.has_sensor_pose);
    EXPECT_EQ (scan.fields.size (), 10u);
    ASSERT_EQ (scan.normals.size (), 2u);
    EXPECT_EQ (scan.normals[0], Eigen::Vector3d (0, 0, 1));
    EXPECT_EQ (scan.normals[1], Eigen::Vector3d (0, 1, 0));
    ASSERT_EQ (scan.colors.size (), 2u);
    EXPECT_EQ (scan.colors[0], 0xffff8000u);
    EXPECT_EQ (scan.colors[1], 0xff0a141eu);
    EXPECT_EQ (scan.intensities, (std::vector<float>{0.5f, 0.25f}));
    EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (-1, 2.5, 3));
  }
}

namespace
{
  /// A Stanford-style range grid of 3 columns x 2 rows with 4 vertices: cells 0, 2, 3, 5 hold vertices
  /// 0, 1, 2, 3; vertex 3 is at (0, 0, 0).
  std::string
  rangeGridPly (bool binary, const std::string& obj_info = "obj_info num_cols 3\nobj_info num_rows 2\n",
                const std::vector<std::vector<int>>& cells = {{0}, {}, {1}, {2}, {}, {3}})
  {
    std::string text = std::string ("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") + " 1.0\n" + obj_info +
                       "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement range_grid " +
                       std::to_string (cells.size ()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    const float v[4][3] = {{1, 1, 1}, {2, 1, 1}, {1, 2, 1}, {0, 0, 0}};
    for (const auto& p : v)
    {
      if (binary)
        for (float x : p)
          put (text, x);
      else
        text += std::to_string (p[0]) + " " + std::to_string (p[1]) + " " + std::to_string (p[2]) + "\n";
    }
    for (const std::vector<int>& cell : cells)
    {
      if (binary)
      {
        put (text, static_cast<std::uint8_t> (cell.size ()));
        for (int index : cell)
          put (text, index);
        continue;
      }
      text += std::to_string (cell.size ());
      for (int index : cell)
        text += " " + std::to_string (index);
      text += "\n";
    }
    return text;
  }
} // namespace

TEST (ScanPly, RangeGridIsAnOrganizedScan)
{
  TempDir dir;
  for (bool binary : {false, true})
  {
    SCOPED_TRACE (binary ? "binary" : "ascii");
    const std::string path = dir.file (binary ? "grid_b.ply" : "grid_a.ply");
    writeBytes (path, rangeGridPly (binary));
    ScanCloud scan;
    loadScanCloud (path, scan);
    expectCounts (scan.report, 6, 2, 1, 0, 3);
    EXPECT_EQ (scan.width, 3u);
    EXPECT_EQ (scan.height, 2u);
    EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 2, 3}));  // grid cells, row * 3 + column
    ASSERT_EQ (scan.size (), 3u);
    EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (1, 1, 1));
    EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (2, 1, 1));
    EXPECT_EQ (scan.worldPosition (2), Eigen::Vector3d (1, 2, 1));

    ScanLoadOptions raw;
    raw.clean = false;
    loadScanCloud (path, scan, raw);
    ASSERT_EQ (scan.size (), 6u);
    EXPECT_TRUE (std::isnan (scan.positions[1].x ()));
    EXPECT_TRUE (std::isnan (scan.positions[4].x ()));
    EXPECT_EQ (scan.worldPosition (3), Eigen::Vector3d (1, 2, 1));
    EXPECT_EQ (scan.worldPosition (5), Eigen::Vector3d::Zero ());

    // The mesh reader still reads the vertices and skips the grid.
    MeshLoadOptions no_faces;
    no_faces.allow_no_faces = true;
    EXPECT_EQ (loadTriangleMesh (path, no_faces).vertices.size (), 4u);
  }
}

TEST (ScanPly, BadRangeGridsAreRefused)
{
  TempDir dir;
  const struct
  {
    std::string obj_info;
    std::vector<std::vector<int>> cells;
    const char* problem;
  } cases[] = {
      {"obj_info num_cols 3\n", {{0}, {}, {1}, {2}, {}, {3}}, "without obj_info num_cols and num_rows"},
      {"obj_info num_cols 2\nobj_info num_rows 2\n", {{0}, {}, {1}, {2}, {}, {3}}, "6 cells, not num_cols x num_rows = 2 x 2"},
      {"obj_info num_cols x\nobj_info num_rows 2\n", {{0}, {}, {1}, {2}, {}, {3}}, "bad PLY obj_info num_cols"},
      {"obj_info num_cols 3\nobj_info num_rows 2\n", {{0}, {}, {1, 2}, {2}, {}, {3}}, "cell 2 has 2 vertices"},
      {"obj_info num_cols 3\nobj_info num_rows 2\n", {{0}, {}, {1}, {1}, {}, {3}}, "vertex 1 is in two range_grid cells"},
      {"obj_info num_cols 3\nobj_info num_rows 2\n", {{0}, {}, {1}, {}, {}, {3}}, "vertex 2 is in no range_grid cell"},
      {"obj_info num_cols 3\nobj_info num_rows 2\n", {{0}, {}, {1}, {2}, {}, {4}}, "index 4 is out of range"},
      {"obj_info num_cols 3\nobj_info num_rows 2\n", {{0}, {}, {1}, {2}, {}, {-1}}, "index -1 is out of range"},
  };
  int k = 0;
  for (const auto& c : cases)
    for (bool binary : {false, true})
    {
      const std::string path = dir.file ("bad_grid" + std::to_string (k++) + ".ply");
      writeBytes (path, rangeGridPly (binary, c.obj_info, c.cells));
      expectRefused (path, c.problem);
    }
}

// ---- bad files ------------------------------------------------------------------------------------------

TEST (ScanBadInput, MissingEmptyDirectoryUnknownGarbage)
{
  TempDir dir;
  expectRefused (dir.file ("missing.pcd"), "cannot open");
  for (const char* name : {"empty.pcd", "empty.ply", "empty.xyz"})
  {
    writeBytes (dir.file (name), "");
    expectRefused (dir.file (name), "empty file");
  }
  ASSERT_EQ (::mkdir (dir.file ("folder.xyz").c_str (), 0755), 0);
  expectRefused (dir.file ("folder.xyz"), "directory");
  writeBytes (dir.file ("points.txt"), "1 2 3\n");
  expectRefused (dir.file ("points.txt"), "unknown point cloud file extension '.txt'");
  std::mt19937 random (7);
  std::string garbage (4000, '\0');
  for (char& c : garbage)
    c = static_cast<char> (random ());
  for (const char* name : {"garbage.pcd", "garbage.ply", "garbage.xyz", "garbage.obj", "garbage.off", "garbage.stl"})
  {
    writeBytes (dir.file (name), garbage);
    expectRefused (dir.file (name));
  }
  writeBytes (dir.file ("nofields.pcd"), "VERSION 0.7\nFIELDS a b\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\nHEIGHT 1\n"
                                         "POINTS 1\nDATA ascii\n1 2\n");
  expectRefused (dir.file ("nofields.pcd"), "no x, y, z");
  writeBytes (dir.file ("noxyz.ply"), asciiPly ("", "property float a\nend_header\n", 1, "1\n"));
  expectRefused (dir.file ("noxyz.ply"), "no x, y, z");
  writeBytes (dir.file ("nopoints.ply"), asciiPly ("", "property float x\nproperty float y\nproperty float z\nend_header\n", 0, ""));
  expectRefused (dir.file ("nopoints.ply"), "no points");
  writeBytes (dir.file ("nopoints.pcd"), "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 0\nHEIGHT 1\n"
                                         "POINTS 0\nDATA ascii\n");
  expectRefused (dir.file ("nopoints.pcd"), "no points");
}

TEST (ScanBadInput, LyingHeaders)
{
  TempDir dir;
  const std::string pcd_head = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  writeBytes (dir.file ("huge.pcd"), pcd_head + "WIDTH 2000000000\nHEIGHT 1000\nPOINTS 2000000000000\nDATA binary\n" +
                                         std::string (24, '\1'));
  expectRefused (dir.file ("huge.pcd"), "truncated PCD data");
  writeBytes (dir.file ("points.pcd"), pcd_head + "WIDTH 3\nHEIGHT 1\nPOINTS 4\nDATA ascii\n1 2 3\n4 5 6\n7 8 9\n");
  expectRefused (dir.file ("points.pcd"), "POINTS is not WIDTH * HEIGHT");
  writeBytes (dir.file ("short_ascii.pcd"), pcd_head + "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n1 2 3\n4 5 6\n");
  expectRefused (dir.file ("short_ascii.pcd"), "truncated or bad ascii PCD data (the file ends after 2 of 3 points)");
  writeBytes (dir.file ("kind.pcd"), pcd_head + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA zipped\n123456789012");
  expectRefused (dir.file ("kind.pcd"), "unknown PCD DATA kind");
  writeBytes (dir.file ("huge.ply"), asciiPly ("", "property float x\nproperty float y\nproperty float z\nend_header\n",
                                               1000000000, "1 2 3\n"));
  expectRefused (dir.file ("huge.ply"), "lying header: the PLY element 'vertex' announces 1000000000 records");
  std::string huge_grid = rangeGridPly (true, "obj_info num_cols 3\nobj_info num_rows 2\n", {});
  huge_grid.replace (huge_grid.find ("range_grid 0"), 12, "range_grid 4000000000");
  writeBytes (dir.file ("huge_grid.ply"), huge_grid);
  expectRefused (dir.file ("huge_grid.ply"), "the PLY element 'range_grid' announces 4000000000 records");
}

TEST (ScanBadInput, TruncatedFilesAreRefusedOrLoadFewerPoints)
{
  // Binary files cut anywhere must be refused; ascii files cut inside the last line may load a shorter
  // last number (the file is then valid), but never crash or load more points than the whole file.
  TempDir dir;
  pcl::PointCloud<pcl::PointXYZRGBA> cloud = trapGrid ();
  for (int i = 0; i < 40; ++i)
  {
    pcl::PointXYZRGBA p;
    p.x = 0.25f * i;
    p.y = 1.0f / (i + 1);
    p.z = -0.5f * i;
    p.rgba = 0xff00ff00u;
    cloud.push_back (p);
  }
  cloud.width = static_cast<std::uint32_t> (cloud.size ());
  cloud.height = 1;
  struct Whole
  {
    std::string name, bytes;
    bool binary;
  };
  std::vector<Whole> files;
  {
    const std::string a = dir.file ("w_a.pcd"), b = dir.file ("w_b.pcd"), c = dir.file ("w_c.pcd");
    ASSERT_EQ (pcl::io::savePCDFileASCII (a, cloud), 0);
    ASSERT_EQ (pcl::io::savePCDFileBinary (b, cloud), 0);
    ASSERT_EQ (pcl::io::savePCDFileBinaryCompressed (c, cloud), 0);
    files.push_back ({"t_ascii.pcd", readBytes (a), false});
    files.push_back ({"t_binary.pcd", readBytes (b), true});
    files.push_back ({"t_compressed.pcd", readBytes (c), true});
  }
  files.push_back ({"t_grid_b.ply", rangeGridPly (true), true});
  files.push_back ({"t_grid_a.ply", rangeGridPly (false), false});
  {
    std::string xyz;
    for (const auto& p : cloud)
      xyz += std::to_string (p.x) + " " + std::to_string (p.y) + " " + std::to_string (p.z) + "\n";
    files.push_back ({"t.xyz", xyz, false});
  }
  std::size_t cuts = 0, loaded = 0;
  for (const Whole& whole : files)
  {
    ScanCloud full;
    ScanLoadOptions raw;
    raw.clean = false;
    writeBytes (dir.file (whole.name), whole.bytes);
    loadScanCloud (dir.file (whole.name), full, raw);
    // The uncut file loads every point (12 + 40, or the grid's 6 cells): the cut ones are measured against it.
    ASSERT_EQ (full.size (), whole.name.find ("grid") != std::string::npos ? 6u : 52u) << whole.name;
    const std::size_t size = whole.bytes.size ();
    const std::size_t last_line = whole.bytes.rfind ('\n', size - 2) + 1;
    for (std::size_t cut : {std::size_t (1), std::size_t (3), size / 10, size / 4, size / 2, size - 200, size - 13,
                            size - 4, size - 1})
    {
      if (cut >= size)
        continue;
      SCOPED_TRACE (whole.name + " cut at " + std::to_string (cut) + " of " + std::to_string (size));
      const std::string path = dir.file ("cut_" + whole.name);
      writeBytes (path, whole.bytes.substr (0, cut));
      ScanCloud scan;
      ++cuts;
      try
      {
        loadScanCloud (path, scan, raw);
        ++loaded;
        EXPECT_FALSE (whole.binary) << "a cut binary file loaded";
        EXPECT_TRUE (cut >= last_line || whole.name == "t.xyz") << "loaded " << scan.size () << " points";
        if (whole.name == "t.xyz")
        {
          // Every whole line, and the cut last one if it still has its three numbers.
          const std::string kept = whole.bytes.substr (0, cut);
          std::istringstream partial (kept.substr (kept.rfind ('\n') + 1));
          std::size_t tokens = 0;
          for (std::string token; partial >> token;)
            ++tokens;
          EXPECT_EQ (scan.size (), static_cast<std::size_t> (std::count (kept.begin (), kept.end (), '\n')) + (tokens == 3));
        }
        else
          EXPECT_EQ (scan.size (), full.size ());  // only the last line was cut, inside its last number
      }
      catch (const Error& e)
      {
        EXPECT_NE (std::string (e.what ()).find (path), std::string::npos) << e.what ();
      }
    }
  }
  // Both branches ran: measured 54 cuts of the 6 files, of which 5 (ascii, cut in their last line) loaded.
  EXPECT_GE (cuts, 50u);
  EXPECT_GE (loaded, 3u);
  EXPECT_LE (loaded, 8u);
}

// ---- toScanCloud for PCL's point types ------------------------------------------------------------------

namespace
{
  template <typename PointT>
  pcl::PointCloud<PointT>
  trapGridAs ()
  {
    const pcl::PointCloud<pcl::PointXYZRGBA> source = trapGrid ();
    pcl::PointCloud<PointT> cloud (source.width, source.height);
    for (std::size_t i = 0; i < source.size (); ++i)
    {
      cloud[i].x = source[i].x;
      cloud[i].y = source[i].y;
      cloud[i].z = source[i].z;
      if constexpr (pcl::traits::has_normal_v<PointT>)
      {
        cloud[i].normal_x = 0;
        cloud[i].normal_y = 0;
        cloud[i].normal_z = static_cast<float> (i);
      }
      if constexpr (pcl::traits::has_color_v<PointT>)
        cloud[i].rgba = source[i].rgba;
      if constexpr (pcl::traits::has_intensity_v<PointT>)
        cloud[i].intensity = static_cast<float> (i);
    }
    cloud.is_dense = true;
    return cloud;
  }

  template <typename PointT>
  void
  checkToScanCloud (bool normals, bool colors, bool intensity)
  {
    ScanCloud scan;
    toScanCloud (trapGridAs<PointT> (), scan);
    expectCounts (scan.report, 12, 4, 2, 3, 3);
    EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 1, 3}));
    EXPECT_EQ (scan.width, 4u);
    EXPECT_EQ (scan.height, 3u);
    ASSERT_EQ (scan.size (), 3u);
    EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d (1, 2, 3));
    EXPECT_EQ (scan.worldPosition (1), Eigen::Vector3d (0.5, 0.25, 4));
    EXPECT_EQ (scan.worldPosition (2), Eigen::Vector3d (-1, -2, 5));
    ASSERT_EQ (scan.normals.size (), normals ? 3u : 0u);
    ASSERT_EQ (scan.colors.size (), colors ? 3u : 0u);
    ASSERT_EQ (scan.intensities.size (), intensity ? 3u : 0u);
    if (normals)
      EXPECT_EQ (scan.normals[2], Eigen::Vector3d (0, 0, 3));
    if (colors)
      EXPECT_EQ (scan.colors[2], 0xff000000u | 3u * 0x010203u);
    if (intensity)
      EXPECT_EQ (scan.intensities, (std::vector<float>{0.0f, 1.0f, 3.0f}));
    ASSERT_GE (scan.fields.size (), 3u);
    EXPECT_EQ (std::vector<std::string> (scan.fields.begin (), scan.fields.begin () + 3),
               (std::vector<std::string>{"x", "y", "z"}));
  }
} // namespace

TEST (ScanConversion, EveryInstantiatedPointType)
{
  checkToScanCloud<pcl::PointXYZ> (false, false, false);
  checkToScanCloud<pcl::PointXYZI> (false, false, true);
  checkToScanCloud<pcl::PointXYZRGB> (false, true, false);
  checkToScanCloud<pcl::PointXYZRGBA> (false, true, false);
  checkToScanCloud<pcl::PointNormal> (true, false, false);
  checkToScanCloud<pcl::PointXYZRGBNormal> (true, true, false);
}

TEST (ScanConversion, SensorOriginAndOptions)
{
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.push_back (pcl::PointXYZ (5, 5, 5));
  cloud.push_back (pcl::PointXYZ (0, 0, 0));
  cloud.push_back (pcl::PointXYZ (5, 5, 5));
  cloud.sensor_origin_ = Eigen::Vector4f (5, 5, 5, 0);
  ScanCloud scan;
  toScanCloud (cloud, scan);
  expectCounts (scan.report, 3, 0, 2, 0, 1);
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{1}));
  ASSERT_EQ (scan.size (), 1u);
  EXPECT_EQ (scan.worldPosition (0), Eigen::Vector3d::Zero ());
  EXPECT_EQ (scan.sensor_origin, Eigen::Vector3d (5, 5, 5));
  ScanCleaningOptions keep;
  keep.drop_at_sensor_origin = false;
  toScanCloud (cloud, scan, keep);
  expectCounts (scan.report, 3, 0, 0, 1, 2);
  EXPECT_EQ (scan.indices, (std::vector<std::size_t>{0, 1}));
}

// ---- the real scans -------------------------------------------------------------------------------------

namespace
{
  struct RealScan
  {
    const char* name;
    std::size_t points, finite, at_zero;
    std::size_t distinct;  ///< distinct finite nonzero positions where the README says; 0: no duplicates (finite - at_zero)
    std::uint32_t width, height;
    const char* fields;
  };

  // ../shared/clouds/README.md, "Files" and "traps" (points = grid cells for the range-grid PLYs).
  const RealScan kRealScans[] = {
      {"bun000.ply", 204800, 40256, 0, 0, 512, 400, "x y z"},
      {"bun045.ply", 204800, 40097, 0, 0, 512, 400, "x y z"},
      {"milk_color.pcd", 13704, 13704, 0, 0, 13704, 1, "x y z rgba"},
      {"table_scene_mug_stereo_textured.pcd", 307200, 209280, 0, 0, 640, 480, "x y z rgba"},
      {"milk_cartoon_all_small_clorox.pcd", 307200, 241407, 0, 0, 640, 480, "x y z rgba"},
      {"office1.pcd", 307200, 254456, 0, 0, 640, 480, "x y z rgb"},
      {"room_scan1.pcd", 112586, 112586, 0, 56159, 112586, 1, "x y z"},
      {"fast_gicp_251370668.pcd", 69088, 69088, 5032, 0, 69088, 1, "x y z intensity"},
      {"small_gicp_source.ply", 69792, 69792, 5107, 0, 69792, 1, "x y z scalar_intensity"},
      {"samp11-utm.pcd", 38010, 38010, 0, 37797, 38010, 1, "x y z"},
      {"lamppost.pcd", 1771, 1771, 0, 1757, 1771, 1, "x y z"},
  };

  std::string
  joined (const std::vector<std::string>& words)
  {
    std::string out;
    for (const std::string& w : words)
      out += (out.empty () ? "" : " ") + w;
    return out;
  }
} // namespace

TEST (ScanRealData, EveryCloudMatchesTheReadme)
{
  for (const RealScan& real : kRealScans)
  {
    SCOPED_TRACE (real.name);
    // Skipped when ../shared/clouds is absent; a file missing from it fails.
    PCL_SPARSE_NEED_SHARED_FILE (sharedCloud (real.name));
    const auto start = std::chrono::steady_clock::now ();
    ScanCloud scan;
    loadScanCloud (sharedCloud (real.name), scan);
    const double ms = std::chrono::duration<double, std::milli> (std::chrono::steady_clock::now () - start).count ();
    std::printf ("  %-40s %7zu points, %6zu kept, %7.1f ms\n", real.name, scan.report.input_points, scan.report.kept, ms);
    const ScanCleaningReport& r = scan.report;
    EXPECT_EQ (r.input_points, real.points);
    EXPECT_EQ (r.finitePoints (), real.finite);
    EXPECT_EQ (r.at_sensor_origin, real.at_zero);
    // The files without a distinct count hold no point twice (measured).
    EXPECT_EQ (r.kept, real.distinct ? real.distinct : real.finite - real.at_zero);
    EXPECT_EQ (r.input_points, r.non_finite + r.at_sensor_origin + r.duplicates_merged + r.kept);
    EXPECT_EQ (scan.width, real.width);
    EXPECT_EQ (scan.height, real.height);
    EXPECT_EQ (joined (scan.fields), real.fields);
    EXPECT_EQ (scan.colors.empty (), std::string (real.fields).find ("rgb") == std::string::npos);
    EXPECT_EQ (scan.intensities.empty (), std::string (real.fields).find ("intensity") == std::string::npos);
    // One attribute per kept point, and as many kept points as the report says (the loop below checks them).
    ASSERT_EQ (scan.size (), r.kept);
    ASSERT_EQ (scan.indices.size (), scan.size ());
    EXPECT_TRUE (scan.colors.empty () || scan.colors.size () == scan.size ());
    EXPECT_TRUE (scan.intensities.empty () || scan.intensities.size () == scan.size ());
    EXPECT_TRUE (scan.normals.empty ());
    // Every kept point is finite, distinct, not at the sensor, and its file index is within the grid.
    for (std::size_t i = 0; i < scan.size (); ++i)
    {
      ASSERT_TRUE (scan.positions[i].allFinite ());
      ASSERT_NE (scan.worldPosition (i), scan.sensor_origin) << i;
      ASSERT_LT (scan.indices[i], r.input_points);
      ASSERT_TRUE (i == 0 || scan.indices[i] > scan.indices[i - 1]);
    }
    std::vector<Eigen::Vector3d> sorted = scan.positions;
    std::sort (sorted.begin (), sorted.end (), [] (const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::lexicographical_compare (a.data (), a.data () + 3, b.data (), b.data () + 3);
    });
    EXPECT_EQ (std::adjacent_find (sorted.begin (), sorted.end ()), sorted.end ()) << "a point kept twice";
  }
}

TEST (ScanRealData, ViewpointsOfTheStereoAndKinectScenes)
{
  // Both headers say VIEWPOINT 0 0 0 0 1 0 0: the sensor at the origin, turned 180 degrees about x. A fresh
  // ScanCloud for each file (and its point count checked), so that no figure is the file's before.
  for (const auto& [name, kept] : {std::pair<const char*, std::size_t>{"office1.pcd", 254456}, {"table_scene_mug_stereo_textured.pcd", 209280}})
  {
    SCOPED_TRACE (name);
    PCL_SPARSE_NEED_SHARED_FILE (sharedCloud (name));
    ScanCloud scan;
    loadScanCloud (sharedCloud (name), scan);
    EXPECT_EQ (scan.size (), kept);  // README
    EXPECT_TRUE (scan.has_sensor_pose);
    EXPECT_EQ (scan.sensor_orientation.coeffs (), Eigen::Vector4d (1, 0, 0, 0));  // w = 0, x = 1
    EXPECT_EQ (scan.sensor_origin, Eigen::Vector3d::Zero ());
  }
  PCL_SPARSE_NEED_SHARED_FILE (sharedCloud ("lamppost.pcd"));
  ScanCloud scan;
  loadScanCloud (sharedCloud ("lamppost.pcd"), scan);
  EXPECT_EQ (scan.size (), 1757u);  // README
  EXPECT_TRUE (scan.has_sensor_pose);
  EXPECT_EQ (scan.sensor_orientation.coeffs (), Eigen::Vector4d (0, 0, 0, 1));
  EXPECT_EQ (scan.sensor_origin, Eigen::Vector3d::Zero ());
}

TEST (ScanRealData, MapCoordinatesComeBackExactly)
{
  // samp11-utm.pcd: eastings ~512,700 m, northings ~5,403,600 m in float32. origin + p must give every kept
  // point's file values exactly (read here through PCL's raw reader, at the file's precision).
  const std::string path = sharedCloud ("samp11-utm.pcd");
  PCL_SPARSE_NEED_SHARED_FILE (path);
  ScanCloud scan;
  loadScanCloud (path, scan);
  pcl::PointCloud<pcl::PointXYZ> reference;
  ASSERT_EQ (pcl::io::loadPCDFile (path, reference), 0);
  ASSERT_EQ (reference.size (), 38010u);
  ASSERT_EQ (scan.size (), 37797u);  // README: 37797 distinct positions
  EXPECT_GT (scan.origin.y (), 5.4e6);
  EXPECT_LT (scan.positions[0].head<2> ().norm (), 500.0);
  for (std::size_t i = 0; i < scan.size (); ++i)
  {
    const Eigen::Vector3d world = scan.worldPosition (i);
    const pcl::PointXYZ& p = reference[scan.indices[i]];
    ASSERT_EQ (world, Eigen::Vector3d (p.x, p.y, p.z)) << i;
    ASSERT_EQ (world.cast<float> ().cast<double> (), world);
  }
  // 606 distinct northings, 0.5 m apart (README): the float32 grid is visible, not smoothed away.
  std::vector<double> northings;
  for (std::size_t i = 0; i < scan.size (); ++i)
    northings.push_back (scan.worldPosition (i).y ());
  std::sort (northings.begin (), northings.end ());
  EXPECT_EQ (std::unique (northings.begin (), northings.end ()) - northings.begin (), 606);
}

TEST (ScanRealData, BunnyRangeGridMatchesPclsOrganizedCloud)
{
  // PCL's PLYReader makes the same 512 x 400 grid (with NaN cells, and is_dense = 1): cell for cell, our
  // kept points are its finite points.
  const std::string path = sharedCloud ("bun000.ply");
  PCL_SPARSE_NEED_SHARED_FILE (path);
  ScanCloud scan;
  loadScanCloud (path, scan);
  pcl::PointCloud<pcl::PointXYZ> reference;
  pcl::PLYReader reader;
  ASSERT_EQ (reader.read (path, reference), 0);
  ASSERT_EQ (reference.width, 512u);
  ASSERT_EQ (reference.height, 400u);
  std::size_t finite = 0;
  for (const pcl::PointXYZ& p : reference)
    finite += std::isfinite (p.x) && std::isfinite (p.y) && std::isfinite (p.z);
  ASSERT_EQ (finite, 40256u);  // README
  ASSERT_EQ (scan.size (), finite);
  for (std::size_t i = 0; i < scan.size (); ++i)
  {
    // Our reader keeps the ascii digits in double; PCL rounds them to the declared float.
    const pcl::PointXYZ& p = reference[scan.indices[i]];
    ASSERT_EQ (scan.worldPosition (i).cast<float> (), p.getVector3fMap ()) << i;
  }
}
