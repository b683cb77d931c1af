// Mesh and point cloud file formats: round trips, every syntax variant on hand-written files, the shared
// real meshes against the table in ../shared/meshes/README.md.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/polygon_mesh_conversion.h>
#include <pcl_sparse/mesh/mesh_primitives.h>

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "test_file_helpers.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

using namespace pcl_sparse;
using namespace pcl_sparse_test;

namespace
{
  /// A torus plus one unreferenced vertex: the loaders must keep it.
  TriangleMesh
  testMesh ()
  {
    TriangleMesh mesh = makeTorus (12, 8, 1.0, 0.3);
    mesh.vertices.emplace_back (0.1234567890123, -7.5e-12, 3.0e8);
    return mesh;
  }

  void
  expectTriangles (const TriangleMesh& mesh, const std::vector<Eigen::Vector3i>& expected)
  {
    ASSERT_EQ (mesh.triangles.size (), expected.size ());
    for (std::size_t f = 0; f < expected.size (); ++f)
      EXPECT_EQ (mesh.triangles[f], expected[f]) << "triangle " << f;
  }
} // namespace

// ---- round trips -------------------------------------------------------------------------------------------

class IoRoundTrip : public ::testing::TestWithParam<std::string>
{
};

TEST_P (IoRoundTrip, ExactForObjOffPly)
{
  TempDir dir;
  const TriangleMesh mesh = testMesh ();
  const std::string path = dir.file ("mesh" + GetParam ());
  saveTriangleMesh (path, mesh);
  const TriangleMesh loaded = loadTriangleMesh (path);
  ASSERT_EQ (loaded.numVertices (), mesh.numVertices ());
  ASSERT_EQ (loaded.numTriangles (), mesh.numTriangles ());
  for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
    EXPECT_EQ (loaded.vertices[i], mesh.vertices[i]) << "vertex " << i;  // bit-exact doubles
  for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    EXPECT_EQ (loaded.triangles[f], mesh.triangles[f]);
}

INSTANTIATE_TEST_SUITE_P (Formats, IoRoundTrip, ::testing::Values (".obj", ".off", ".ply", ".OBJ", ".Ply"));

TEST (IoRoundTrip, StlIsWeldedBackToTheSameMeshAtFloatPrecision)
{
  TempDir dir;
  const TriangleMesh mesh = makeTorus (12, 8, 1.0, 0.3);  // no unreferenced vertex: STL has no vertex list
  const std::string path = dir.file ("mesh.stl");
  saveTriangleMesh (path, mesh);
  EXPECT_EQ (readBytes (path).size (), 84u + 50u * mesh.numTriangles ());
  const TriangleMesh loaded = loadTriangleMesh (path);
  ASSERT_EQ (loaded.numVertices (), mesh.numVertices ());
  ASSERT_EQ (loaded.numTriangles (), mesh.numTriangles ());
  for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ (loaded.vertices[loaded.triangles[f][k]], mesh.vertices[mesh.triangles[f][k]].cast<float> ().cast<double> ());
}

TEST (IoRoundTrip, StlTriangleSoupStaysUnwelded)
{
  // Every triangle with its own three corners, slightly moved: nothing is equal, nothing may be welded
  // (and the weld table has to grow well past its initial size).
  TempDir dir;
  const TriangleMesh sphere = makeIcosphere (3);
  TriangleMesh soup;
  for (const Eigen::Vector3i& t : sphere.triangles)
  {
    const int base = static_cast<int> (soup.vertices.size ());
    for (int k = 0; k < 3; ++k)
      soup.vertices.push_back (sphere.vertices[t[k]] * (1.0 + 1e-5 * static_cast<double> (soup.vertices.size ())));
    soup.triangles.emplace_back (base, base + 1, base + 2);
  }
  const std::string path = dir.file ("soup.stl");
  saveTriangleMesh (path, soup);
  const TriangleMesh loaded = loadTriangleMesh (path);
  ASSERT_EQ (loaded.numVertices (), soup.numVertices ());
  for (std::size_t i = 0; i < soup.vertices.size (); ++i)
    EXPECT_EQ (loaded.vertices[i], soup.vertices[i].cast<float> ().cast<double> ());
}

TEST (IoRoundTrip, ColoredPlyKeepsPositionsAndColours)
{
  TempDir dir;
  const TriangleMesh mesh = makeIcosphere (1);
  std::vector<std::array<std::uint8_t, 3>> colors (mesh.numVertices ());
  for (std::size_t i = 0; i < colors.size (); ++i)
    colors[i] = {static_cast<std::uint8_t> (i), static_cast<std::uint8_t> (255 - i), 7};
  const std::string path = dir.file ("colored.ply");
  saveColoredMesh (path, mesh, colors);
  const std::string bytes = readBytes (path);
  EXPECT_NE (bytes.find ("property uchar red\nproperty uchar green\nproperty uchar blue\n"), std::string::npos);
  const TriangleMesh loaded = loadTriangleMesh (path);
  ASSERT_EQ (loaded.numVertices (), mesh.numVertices ());
  ASSERT_EQ (loaded.numTriangles (), mesh.numTriangles ());
  for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
    EXPECT_EQ (loaded.vertices[i], mesh.vertices[i].cast<float> ().cast<double> ());
  // The colours of vertex 5 follow its three floats (header + 5 records of 15 bytes).
  const std::size_t body = bytes.find ("end_header\n") + 11;
  EXPECT_EQ (static_cast<std::uint8_t> (bytes[body + 5 * 15 + 12]), 5);
  EXPECT_EQ (static_cast<std::uint8_t> (bytes[body + 5 * 15 + 13]), 250);
  EXPECT_EQ (static_cast<std::uint8_t> (bytes[body + 5 * 15 + 14]), 7);
  EXPECT_THROW (saveColoredMesh (dir.file ("colored.obj"), mesh, colors), Error);
  colors.pop_back ();
  EXPECT_THROW (saveColoredMesh (dir.file ("short.ply"), mesh, colors), Error);
}

TEST (IoRoundTrip, WritersRefuseBadIndicesAndLeaveNoFile)
{
  TempDir dir;
  TriangleMesh mesh = makeTetrahedron ();
  mesh.triangles[2][1] = 4;
  EXPECT_THROW (saveTriangleMesh (dir.file ("bad.ply"), mesh), Error);
  EXPECT_THROW (saveTriangleMesh (dir.file ("bad.xyz"), makeTetrahedron ()), Error);
  EXPECT_THROW (saveTriangleMesh (dir.file ("missing_folder/mesh.obj"), makeTetrahedron ()), Error);
  struct stat info;
  EXPECT_NE (::stat (dir.file ("bad.ply").c_str (), &info), 0);
}

// ---- OBJ ---------------------------------------------------------------------------------------------------

TEST (IoObj, EveryFaceFormNegativeIndicesPolygonsCommentsCrlf)
{
  TempDir dir;
  const std::string text = "# a comment\r\n"
                           "mtllib some.mtl\r\n"
                           "o object\r\n"
                           "\r\n"
                           "v 0 0 0\r\n"
                           "v 1.5 0 0 1.0\r\n"  // optional w
                           "v +1 1 -0\r\n"
                           "v 0 1 0 0.5 0.5 0.5\r\n"  // vertex colour
                           "v 2e0 2E-1 .5\r\n"
                           "v 9 9 9\r\n"  // unreferenced
                           "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\n"
                           "vn 0 0 1\r\n"
                           "g group\r\ns off\r\nusemtl mat\r\n"
                           "f 1 2 3\r\n"
                           "f 1/1 2/2 3/3\r\n"
                           "f 1/1/1 2/2/1 3/3/1\r\n"
                           "f 1//1 2//1 3//1 # trailing comment\r\n"
                           "f -6 -5 -4\r\n"            // relative: vertices 1 2 3
                           "f -6/-3/-1 -4/-1/-1 -3\r\n"  // vertices 1 3 4
                           "f 1 2 3 4\r\n"              // quad -> 2 triangles
                           "\tf  1  2  3  4  5 \r\n"        // pentagon -> 3 triangles, tabs and spaces
                           "l 1 2\r\n";
  const std::string path = dir.file ("syntax.obj");
  writeBytes (path, text);
  const TriangleMesh mesh = loadTriangleMesh (path);
  ASSERT_EQ (mesh.numVertices (), 6u);
  EXPECT_EQ (mesh.vertices[1], Eigen::Vector3d (1.5, 0, 0));
  EXPECT_EQ (mesh.vertices[2], Eigen::Vector3d (1, 1, 0));
  EXPECT_EQ (mesh.vertices[4], Eigen::Vector3d (2, 0.2, 0.5));
  EXPECT_EQ (mesh.vertices[5], Eigen::Vector3d (9, 9, 9));
  expectTriangles (mesh, {{0, 1, 2}, {0, 1, 2}, {0, 1, 2}, {0, 1, 2}, {0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 3},
                          {0, 1, 2}, {0, 2, 3}, {0, 3, 4}});
}

TEST (IoObj, ForwardReferencesAndNoTrailingNewline)
{
  TempDir dir;
  const std::string path = dir.file ("forward.obj");
  writeBytes (path, "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0");
  const TriangleMesh mesh = loadTriangleMesh (path);
  EXPECT_EQ (mesh.numVertices (), 3u);
  expectTriangles (mesh, {{0, 1, 2}});
  EXPECT_EQ (mesh.vertices[2], Eigen::Vector3d (0, 1, 0));
}

// ---- OFF ---------------------------------------------------------------------------------------------------

TEST (IoOff, CountsOnHeaderLineCommentsAndPolygons)
{
  TempDir dir;
  const std::string path = dir.file ("quad.off");
  writeBytes (path, "OFF 5 2 0 # counts on the header line\n"
                    "# a comment line\n"
                    "0 0 0\n1 0 0\n1 1 0   # trailing comment\n\n0 1 0\n5 5 5\n"
                    "4 0 1 2 3\n3 0 2 1\n");
  const TriangleMesh mesh = loadTriangleMesh (path);
  EXPECT_EQ (mesh.numVertices (), 5u);
  expectTriangles (mesh, {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}});
  EXPECT_EQ (mesh.vertices[2], Eigen::Vector3d (1, 1, 0));
}

TEST (IoOff, ColourAndNormalVariantsWithExtraColumns)
{
  TempDir dir;
  const std::string coff = dir.file ("c.off");
  writeBytes (coff, "COFF\r\n3 1 3\r\n0 0 0 255 0 0 255\r\n1 0 0 0 255 0 255\r\n0 1 0 0 0 255 255\r\n3 0 1 2 0.5 0.5 0.5\r\n");
  TriangleMesh mesh = loadTriangleMesh (coff);
  EXPECT_EQ (mesh.numVertices (), 3u);
  expectTriangles (mesh, {{0, 1, 2}});
  EXPECT_EQ (mesh.vertices[1], Eigen::Vector3d (1, 0, 0));

  const std::string noff = dir.file ("n.OFF");
  writeBytes (noff, "NOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 2 1 0\n");
  mesh = loadTriangleMesh (noff);
  EXPECT_EQ (mesh.numVertices (), 3u);
  expectTriangles (mesh, {{2, 1, 0}});
}

// ---- PLY ---------------------------------------------------------------------------------------------------

TEST (IoPly, AsciiWithExtraPropertiesElementsAndBothListNames)
{
  TempDir dir;
  const std::string path = dir.file ("ascii.ply");
  writeBytes (path, "ply\r\nformat ascii 1.0\r\ncomment hand written\r\nobj_info test\r\n"
                    "element vertex 4\r\nproperty float nx\r\nproperty double x\r\nproperty float y\r\n"
                    "property int z\r\nproperty uchar red\r\nproperty list uchar float texcoord\r\n"
                    "element face 2\r\nproperty list uchar int vertex_indices\r\nproperty int flags\r\n"
                    "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
                    "end_header\r\n"
                    "0.5 0 0 0 255 2 0 0\r\n"
                    "0.5 1.25 0 0 255 0\r\n"
                    "0.5 1 1 -3 255 1 0.5\r\n"
                    "0.5 0 1 0 255 0\r\n"
                    "4 0 1 2 3 7\r\n"
                    "3 0 2 1 8\r\n"
                    "0 1\r\n");
  const TriangleMesh mesh = loadTriangleMesh (path);
  ASSERT_EQ (mesh.numVertices (), 4u);
  EXPECT_EQ (mesh.vertices[1], Eigen::Vector3d (1.25, 0, 0));
  EXPECT_EQ (mesh.vertices[2], Eigen::Vector3d (1, 1, -3));
  expectTriangles (mesh, {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}});
}

namespace
{
  /// A binary PLY with mixed vertex property types, an extra element between vertex and face, and the given
  /// face list count/index types.
  template <typename Count, typename Index>
  std::string
  binaryPly (bool big_endian, const char* count_type, const char* index_type, const char* list_name)
  {
    std::string out = std::string ("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 4\nproperty double x\nproperty float y\nproperty short z\n"
                      "property uchar alpha\nproperty list ushort int extra\n"
                      "element material 1\nproperty float shininess\n"
                      "element face 2\nproperty uchar flags\nproperty list " +
                      count_type + " " + index_type + " " + list_name + "\nend_header\n";
    const double xs[4] = {0.1, 1.0, 1.0, -2.5e-7};
    const float ys[4] = {0.0f, 0.5f, 1.0f, 1.0f};
    const std::int16_t zs[4] = {0, -1, 300, 2};
    for (int i = 0; i < 4; ++i)
    {
      put (out, xs[i], big_endian);
      put (out, ys[i], big_endian);
      put (out, zs[i], big_endian);
      put (out, static_cast<std::uint8_t> (200), big_endian);
      put (out, static_cast<std::uint16_t> (i % 2), big_endian);  // a list of 0 or 1 ints
      if (i % 2)
        put (out, static_cast<std::int32_t> (42), big_endian);
    }
    put (out, 0.75f, big_endian);
    put (out, static_cast<std::uint8_t> (1), big_endian);
    put (out, static_cast<Count> (4), big_endian);
    for (Index i : {0, 1, 2, 3})
      put (out, i, big_endian);
    put (out, static_cast<std::uint8_t> (1), big_endian);
    put (out, static_cast<Count> (3), big_endian);
    for (Index i : {3, 2, 1})
      put (out, i, big_endian);
    return out;
  }

  void
  checkBinaryPly (const TriangleMesh& mesh)
  {
    ASSERT_EQ (mesh.numVertices (), 4u);
    EXPECT_EQ (mesh.vertices[0], Eigen::Vector3d (0.1, 0, 0));
    EXPECT_EQ (mesh.vertices[1], Eigen::Vector3d (1.0, 0.5, -1));
    EXPECT_EQ (mesh.vertices[2], Eigen::Vector3d (1.0, 1.0, 300));
    EXPECT_EQ (mesh.vertices[3], Eigen::Vector3d (-2.5e-7, 1.0, 2));
    expectTriangles (mesh, {{0, 1, 2}, {0, 2, 3}, {3, 2, 1}});
  }
} // namespace

TEST (IoPly, BinaryLittleAndBigEndianWithAllListTypes)
{
  TempDir dir;
  for (bool big_endian : {false, true})
  {
    SCOPED_TRACE (big_endian ? "big endian" : "little endian");
    const std::string path = dir.file ("binary.ply");
    writeBytes (path, binaryPly<std::uint8_t, std::int32_t> (big_endian, "uchar", "int", "vertex_indices"));
    checkBinaryPly (loadTriangleMesh (path));
    writeBytes (path, binaryPly<std::int8_t, std::uint32_t> (big_endian, "char", "uint", "vertex_index"));
    checkBinaryPly (loadTriangleMesh (path));
    writeBytes (path, binaryPly<std::uint16_t, std::int16_t> (big_endian, "ushort", "short", "vertex_indices"));
    checkBinaryPly (loadTriangleMesh (path));
    writeBytes (path, binaryPly<std::int32_t, std::uint16_t> (big_endian, "int", "ushort", "vertex_indices"));
    checkBinaryPly (loadTriangleMesh (path));
    writeBytes (path, binaryPly<std::uint32_t, std::uint8_t> (big_endian, "uint32", "uint8", "vertex_indices"));
    checkBinaryPly (loadTriangleMesh (path));
  }
}

// ---- STL ---------------------------------------------------------------------------------------------------

TEST (IoStl, AsciiIsWeldedExactly)
{
  TempDir dir;
  const std::string path = dir.file ("two.stl");
  writeBytes (path, "solid two\r\n"
                    "  facet normal 0 0 1\r\n    outer loop\r\n"
                    "      vertex 0 0 0\r\n      vertex 1 0 0\r\n      vertex 1 1 0\r\n"
                    "    endloop\r\n  endfacet\r\n"
                    "  facet normal 0 0 1\n    outer loop\n"
                    "      vertex 0 0 -0\n      vertex 1 1 0\n      vertex 0 1 0\n"
                    "    endloop\n  endfacet\n"
                    "  facet normal 0 0 1\n    outer loop\n"  // almost, but not exactly, a shared corner
                    "      vertex 1e-300 0 0\n      vertex 1 1 0\n      vertex 0 1 0\n"
                    "    endloop\n  endfacet\n"
                    "endsolid two\n");
  const TriangleMesh mesh = loadTriangleMesh (path);
  EXPECT_EQ (mesh.numVertices (), 5u);
  expectTriangles (mesh, {{0, 1, 2}, {0, 2, 3}, {4, 2, 3}});
  EXPECT_EQ (mesh.vertices[3], Eigen::Vector3d (0, 1, 0));
}

TEST (IoStl, BinaryEvenWithSolidInItsHeader)
{
  TempDir dir;
  std::string out (80, ' ');
  out.replace (0, 11, "solid liar ");  // some exporters write "solid" into binary headers
  put (out, std::uint32_t (2));
  const float triangles[2][9] = {{0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 0, 1, 1, 0, 0, 1, 0.25f}};
  for (const auto& t : triangles)
  {
    for (float n : {0.0f, 0.0f, 1.0f})
      put (out, n);
    for (float c : t)
      put (out, c);
    put (out, std::uint16_t (0));
  }
  const std::string path = dir.file ("binary.STL");
  writeBytes (path, out);
  const TriangleMesh mesh = loadTriangleMesh (path);
  EXPECT_EQ (mesh.numVertices (), 4u);
  expectTriangles (mesh, {{0, 1, 2}, {0, 2, 3}});
  EXPECT_EQ (mesh.vertices[3], Eigen::Vector3d (0, 1, 0.25));
  // Padded after the last triangle (some exporters do): still binary, the padding is ignored.
  writeBytes (path, out + std::string (3, '\0'));
  const TriangleMesh padded = loadTriangleMesh (path);
  EXPECT_EQ (padded.numVertices (), 4u);
  EXPECT_EQ (padded.numTriangles (), 2u);
}

// ---- PCL types and point clouds ----------------------------------------------------------------------------

TEST (IoPolygonMesh, ConversionsRoundTripAndTriangulate)
{
  const TriangleMesh mesh = makeCube (2);
  const pcl::PolygonMesh polygon_mesh = toPolygonMesh (mesh);
  EXPECT_EQ (polygon_mesh.cloud.width * polygon_mesh.cloud.height, mesh.numVertices ());
  EXPECT_EQ (polygon_mesh.polygons.size (), mesh.numTriangles ());
  const TriangleMesh back = fromPolygonMesh (polygon_mesh);
  ASSERT_EQ (back.numVertices (), mesh.numVertices ());
  for (std::size_t i = 0; i < mesh.vertices.size (); ++i)
    EXPECT_EQ (back.vertices[i], mesh.vertices[i].cast<float> ().cast<double> ());
  for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
    EXPECT_EQ (back.triangles[f], mesh.triangles[f]);

  pcl::PolygonMesh quad = toPolygonMesh (makePlaneGrid (1));  // 4 vertices
  quad.polygons.resize (1);
  quad.polygons[0].vertices = {0, 1, 3, 2};
  expectTriangles (fromPolygonMesh (quad), {{0, 1, 3}, {0, 3, 2}});
  quad.polygons[0].vertices = {0, 1, 4};
  EXPECT_THROW (fromPolygonMesh (quad), Error);
  quad.polygons[0].vertices = {0, 1};
  EXPECT_THROW (fromPolygonMesh (quad), Error);
  quad.cloud.fields.pop_back ();  // no z
  quad.polygons.clear ();
  EXPECT_THROW (fromPolygonMesh (quad), Error);
}

TEST (IoPolygonMesh, LoadPolygonMesh)
{
  TempDir dir;
  const TriangleMesh mesh = testMesh ();
  saveTriangleMesh (dir.file ("m.ply"), mesh);
  pcl::PolygonMesh polygon_mesh;
  loadPolygonMesh (dir.file ("m.ply"), polygon_mesh);
  EXPECT_EQ (polygon_mesh.cloud.width, mesh.numVertices ());
  EXPECT_EQ (polygon_mesh.polygons.size (), mesh.numTriangles ());
  // The values too (the PLY stores float32 coordinates).
  const TriangleMesh back = fromPolygonMesh (polygon_mesh);
  ASSERT_EQ (back.numVertices (), mesh.numVertices ());
  for (std::size_t v = 0; v < mesh.numVertices (); ++v)
    EXPECT_EQ (back.vertices[v], mesh.vertices[v].cast<float> ().cast<double> ()) << v;
  EXPECT_EQ (back.triangles, mesh.triangles);
  EXPECT_THROW (loadPolygonMesh (dir.file ("missing.ply"), polygon_mesh), Error);
}

TEST (IoCloud, PointNormalCloudRoundTripsThroughPcdAndPly)
{
  TempDir dir;
  pcl::PointCloud<pcl::PointNormal> cloud;
  for (int i = 0; i < 50; ++i)
  {
    pcl::PointNormal p;
    p.x = 0.1f * i;
    p.y = std::sin (0.3f * i);
    p.z = -1.0f / (i + 1);
    p.normal_x = 0.0f;
    p.normal_y = 0.6f;
    p.normal_z = 0.8f;
    p.curvature = 0.01f * i;
    cloud.push_back (p);
  }
  for (const char* name : {"c.pcd", "c.ply"})
    for (bool binary : {true, false})
    {
      SCOPED_TRACE (std::string (name) + (binary ? " binary" : " ascii"));
      const std::string path = dir.file (name);
      savePointNormalCloud (path, cloud, binary);
      const std::string bytes = readBytes (path);
      EXPECT_NE (bytes.find (binary ? "binary" : "ascii"), std::string::npos);
      EXPECT_NE (bytes.find ("curvature"), std::string::npos);
      pcl::PointCloud<pcl::PointXYZ> loaded;
      loadPointCloud (path, loaded);
      ASSERT_EQ (loaded.size (), cloud.size ());
      EXPECT_TRUE (loaded.is_dense);
      for (std::size_t i = 0; i < cloud.size (); ++i)
      {
        EXPECT_EQ (loaded[i].x, cloud[i].x);
        EXPECT_EQ (loaded[i].y, cloud[i].y);
        EXPECT_EQ (loaded[i].z, cloud[i].z);
      }
      // The normals and curvature too, read back by PCL's own readers.
      pcl::PointCloud<pcl::PointNormal> with_normals;
      ASSERT_EQ (std::string (name) == "c.pcd" ? pcl::io::loadPCDFile (path, with_normals)
                                               : pcl::io::loadPLYFile (path, with_normals),
                 0);
      ASSERT_EQ (with_normals.size (), cloud.size ());
      for (std::size_t i = 0; i < cloud.size (); ++i)
      {
        EXPECT_EQ (with_normals[i].getNormalVector3fMap (), cloud[i].getNormalVector3fMap ()) << i;
        EXPECT_EQ (with_normals[i].curvature, cloud[i].curvature) << i;
      }
    }
  EXPECT_THROW (savePointNormalCloud (dir.file ("c.txt"), cloud), Error);
  EXPECT_THROW (savePointNormalCloud (dir.file ("missing_folder/c.pcd"), cloud), Error);

  // An empty cloud is a valid result (e.g. nothing resampled) and reads back empty.
  for (const char* name : {"empty.pcd", "empty.ply"})
    for (bool binary : {true, false})
    {
      SCOPED_TRACE (std::string (name) + (binary ? " binary" : " ascii"));
      savePointNormalCloud (dir.file (name), pcl::PointCloud<pcl::PointNormal> (), binary);
      pcl::PointCloud<pcl::PointXYZ> loaded;
      loaded.resize (3);
      loadPointCloud (dir.file (name), loaded);
      EXPECT_EQ (loaded.size (), 0u);
    }
}

TEST (IoCloud, PcdWithDoubleFieldsAndExtraFields)
{
  // pcl::fromPCLPointCloud2 would leave double x/y/z at zero: loadPointCloud reads them at their own type.
  TempDir dir;
  const std::string path = dir.file ("double.pcd");
  writeBytes (path, "# .PCD v0.7\nVERSION 0.7\nFIELDS intensity x y z\nSIZE 4 8 8 8\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                    "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n"
                    "0.5 1.25 -2 3e2\n0.5 0.1 0.2 0.3\n");
  pcl::PointCloud<pcl::PointXYZ> cloud;
  loadPointCloud (path, cloud);
  ASSERT_EQ (cloud.size (), 2u);
  EXPECT_EQ (cloud[0].x, 1.25f);
  EXPECT_EQ (cloud[0].y, -2.0f);
  EXPECT_EQ (cloud[0].z, 300.0f);
  EXPECT_EQ (cloud[1].z, 0.3f);
}

TEST (IoCloud, PlyWithoutFacesIsACloudNotAMesh)
{
  TempDir dir;
  const std::string path = dir.file ("points.ply");
  writeBytes (path, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "end_header\n1 2 3\n4 5 6\nnan 0 0\n");
  pcl::PointCloud<pcl::PointXYZ> cloud;
  loadPointCloud (path, cloud);
  ASSERT_EQ (cloud.size (), 3u);
  EXPECT_EQ (cloud[1].y, 5.0f);
  EXPECT_FALSE (cloud.is_dense);  // NaN points are PCL's "invalid point", kept
  try
  {
    loadTriangleMesh (path);
    FAIL () << "a PLY without faces loaded as a mesh";
  }
  catch (const Error& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("points.ply"), std::string::npos);
  }
  MeshLoadOptions options;
  options.allow_no_faces = true;
  options.allow_non_finite = true;
  EXPECT_EQ (loadTriangleMesh (path, options).numVertices (), 3u);
}

// ---- the shared real meshes ----------------------------------------------------------------------------------

namespace
{
  bool
  sharedMeshesPresent ()
  {
    struct stat info;
    return ::stat (PCL_SPARSE_SHARED_MESHES "/README.md", &info) == 0;
  }
} // namespace

TEST (IoSharedMeshes, CountsMatchTheReadmeTable)
{
  if (!sharedMeshesPresent ())
    GTEST_SKIP () << "shared meshes not found at " PCL_SPARSE_SHARED_MESHES;
  // ../shared/meshes/README.md: file, V, F (V counts every vertex of the file, unreferenced ones included).
  const struct
  {
    const char* file;
    std::size_t vertices, faces;
  } table[] = {{"fandisk.off", 6475, 12946},         {"bunny-npm-1k.obj", 1839, 3674},
               {"bunny-hr-closed.obj", 29834, 59664}, {"spot.obj", 11533, 23062},
               {"blub.obj", 10786, 21568},            {"wingnut.obj", 3047, 6090},
               {"anchor-dense.off", 3793, 7598},      {"turbine.off", 9210, 18460},
               {"blade.off", 8231, 16222},            {"stanford-bunny.obj", 35947, 69451},
               {"koala.obj", 49999, 99994},           {"koala-loop1-200k.ply", 199990, 399976},
               {"sword.obj", 22293, 44582}};
  for (const auto& row : table)
  {
    SCOPED_TRACE (row.file);
    const TriangleMesh mesh = loadTriangleMesh (std::string (PCL_SPARSE_SHARED_MESHES "/") + row.file);
    EXPECT_EQ (mesh.numVertices (), row.vertices);
    EXPECT_EQ (mesh.numTriangles (), row.faces);
  }
}

TEST (IoSharedMeshes, Koala200kPlyLoadsWellUnderASecond)
{
  if (!sharedMeshesPresent ())
    GTEST_SKIP () << "shared meshes not found at " PCL_SPARSE_SHARED_MESHES;
  const std::string path = PCL_SPARSE_SHARED_MESHES "/koala-loop1-200k.ply";
  const auto start = std::chrono::steady_clock::now ();
  const TriangleMesh mesh = loadTriangleMesh (path);
  const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  std::printf ("koala-loop1-200k.ply: %zu vertices, %zu faces in %.3f s\n", mesh.numVertices (), mesh.numTriangles (),
               seconds);
  EXPECT_EQ (mesh.numVertices (), 199990u);
  EXPECT_LT (seconds, 1.0);  // < 0.05 s in Release on the development machine (the tests build Release)
}
