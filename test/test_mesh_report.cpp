#include <pcl_sparse/geometry/sharp_edges.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/mesh/mesh_cleaning.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/vertex_welding.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  MeshReport
  reportOf (const TriangleMesh& mesh)
  {
    const MeshReport report = computeMeshReport (mesh, buildMeshTopology (mesh));
    // The count without the topology agrees wherever no face repeats a corner (which it leaves out, as
    // the stages do): 0, 1 and 3 non-manifold edges in these tests.
    const bool repeats_a_corner = std::any_of (mesh.triangles.begin (), mesh.triangles.end (), hasRepeatedIndex);
    if (!repeats_a_corner)
      EXPECT_EQ (countNonManifoldEdges (mesh), report.nonmanifold_edges);
    return report;
  }

  /// Two triangles sharing one edge: an open square made of (0, 1, 2) and (0, 2, 3).
  TriangleMesh
  makeSquare ()
  {
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return mesh;
  }

  void
  expectCleanClosedManifold (const MeshReport& r)
  {
    EXPECT_EQ (r.unreferenced_vertices, 0u);
    EXPECT_EQ (r.non_finite_vertices, 0u);
    EXPECT_EQ (r.degenerate_faces, 0u);
    EXPECT_EQ (r.duplicate_faces, 0u);
    EXPECT_EQ (r.boundary_edges, 0u);
    EXPECT_EQ (r.boundary_loops, 0u);
    EXPECT_EQ (r.nonmanifold_edges, 0u);
    EXPECT_EQ (r.nonmanifold_vertices, 0u);
    EXPECT_TRUE (r.manifold);
    EXPECT_TRUE (r.orientable);
    EXPECT_TRUE (r.closed);
  }
} // namespace

TEST (MeshReport, Tetrahedron)
{
  const MeshReport r = reportOf (makeTetrahedron ());
  EXPECT_EQ (r.vertices, 4u);
  EXPECT_EQ (r.faces, 4u);
  EXPECT_EQ (r.edges, 6u);
  expectCleanClosedManifold (r);
  EXPECT_EQ (r.components, 1u);
  EXPECT_EQ (r.euler_characteristic, 2);
  EXPECT_EQ (r.genus, 0);
  // Inscribed in the unit sphere: edge length sqrt(8/3); the box is [-a, a]^3 with a = 1/sqrt(3) when the
  // corners are (+-1, +-1, +-1)/sqrt(3), so its diagonal is 2.
  EXPECT_NEAR (r.mean_edge_length, std::sqrt (8.0 / 3.0), 1e-9);
  EXPECT_NEAR (r.bbox_diagonal, 2.0, 1e-9);
}

TEST (MeshReport, Cube)
{
  const int n = 3;
  const MeshReport r = reportOf (makeCube (n, 0.5));
  EXPECT_EQ (r.vertices, 6u * n * n + 2);
  EXPECT_EQ (r.faces, 12u * n * n);
  expectCleanClosedManifold (r);
  EXPECT_EQ (r.components, 1u);
  EXPECT_EQ (r.genus, 0);
  EXPECT_NEAR (r.bbox_diagonal, std::sqrt (3.0), 1e-12);
}

TEST (MeshReport, OpenDiskHasOneBoundaryLoop)
{
  const int rings = 4;
  const MeshReport r = reportOf (makeDisk (rings, 2.0));
  EXPECT_EQ (r.boundary_edges, 6u * rings);
  EXPECT_EQ (r.boundary_loops, 1u);
  EXPECT_EQ (r.nonmanifold_edges, 0u);
  EXPECT_EQ (r.nonmanifold_vertices, 0u);
  EXPECT_TRUE (r.manifold);
  EXPECT_TRUE (r.orientable);
  EXPECT_FALSE (r.closed);
  EXPECT_EQ (r.components, 1u);
  EXPECT_EQ (r.euler_characteristic, 1);
  EXPECT_EQ (r.genus, 0);
  EXPECT_NEAR (r.bbox_diagonal, std::hypot (4.0, 4.0), 1e-9);  // 24 outer vertices every 15 degrees
}

TEST (MeshReport, CylinderHasTwoBoundaryLoopsAndGenusZero)
{
  const MeshReport r = reportOf (makeCylinder (16, 5));
  EXPECT_EQ (r.boundary_edges, 32u);
  EXPECT_EQ (r.boundary_loops, 2u);
  EXPECT_EQ (r.euler_characteristic, 0);
  EXPECT_EQ (r.genus, 0);
}

TEST (MeshReport, TorusHasGenusOne)
{
  const MeshReport r = reportOf (makeTorus (24, 12));
  expectCleanClosedManifold (r);
  EXPECT_EQ (r.components, 1u);
  EXPECT_EQ (r.euler_characteristic, 0);
  EXPECT_EQ (r.genus, 1);
}

TEST (MeshReport, TwoTorusComponentsAddTheirGenus)
{
  TriangleMesh mesh = makeTorus (16, 8);
  TriangleMesh other = makeTorus (16, 8);
  for (auto& p : other.vertices)
    p.x () += 5.0;
  appendMesh (mesh, other);
  appendMesh (mesh, makeIcosphere (1, 1.0, Eigen::Vector3d (0, 5, 0)));
  const MeshReport r = reportOf (mesh);
  EXPECT_EQ (r.components, 3u);
  EXPECT_EQ (r.euler_characteristic, 2);
  EXPECT_EQ (r.genus, 2);
}

TEST (MeshReport, TwoDisjointSpheres)
{
  TriangleMesh mesh = makeIcosphere (2, 1.0);
  appendMesh (mesh, makeIcosphere (2, 1.0, Eigen::Vector3d (3, 0, 0)));
  const MeshReport r = reportOf (mesh);
  EXPECT_EQ (r.vertices, 2u * 162);
  expectCleanClosedManifold (r);
  EXPECT_EQ (r.components, 2u);
  EXPECT_EQ (r.euler_characteristic, 4);
  EXPECT_EQ (r.genus, 0);
  EXPECT_NEAR (r.bbox_diagonal, std::sqrt (25.0 + 4.0 + 4.0), 1e-9);  // x in [-1, 4]
}

TEST (MeshReport, DuplicatedFace)
{
  TriangleMesh mesh = makeTetrahedron ();
  const Eigen::Vector3i t = mesh.triangles[2];
  mesh.triangles.emplace_back (t[1], t[2], t[0]);  // same vertex set, rotated
  mesh.triangles.emplace_back (t[2], t[1], t[0]);  // same vertex set, flipped
  const MeshReport r = reportOf (mesh);
  EXPECT_EQ (r.duplicate_faces, 2u);
  EXPECT_EQ (r.nonmanifold_edges, 3u);  // the copies' three edges now have 4 faces
  EXPECT_FALSE (r.manifold);
  EXPECT_EQ (r.genus, -1);
  const std::vector<int> first = findDuplicateFaces (mesh);
  EXPECT_EQ (first, (std::vector<int>{0, 1, 2, 3, 2, 2}));
  // Without the copies, as the stages see the mesh: the tetrahedron's edges, two faces each.
  EXPECT_EQ (countNonManifoldEdges (mesh, first), 0u);
}

TEST (MeshReport, DegenerateFaces)
{
  TriangleMesh mesh = makeSquare ();
  mesh.vertices.emplace_back (2, 0, 0);
  mesh.vertices.emplace_back (3, 0, 0);
  mesh.triangles.emplace_back (1, 4, 5);  // collinear corners: zero area
  mesh.triangles.emplace_back (1, 1, 4);  // repeated index
  const MeshReport r = reportOf (mesh);
  EXPECT_EQ (r.degenerate_faces, 2u);
  EXPECT_TRUE (isDegenerateFace (mesh, 2));
  EXPECT_TRUE (isDegenerateFace (mesh, 3));
  EXPECT_FALSE (isDegenerateFace (mesh, 0));
  EXPECT_FALSE (r.manifold);  // a repeated index makes the topology meaningless
  EXPECT_EQ (r.genus, -1);
}

TEST (MeshReport, UnreferencedAndNonFiniteVertices)
{
  TriangleMesh mesh = makeTetrahedron ();
  mesh.vertices.emplace_back (10, 10, 10);  // unreferenced, far away: counts in the box
  mesh.vertices.emplace_back (std::numeric_limits<double>::quiet_NaN (), 0, 0);
  const MeshReport r = reportOf (mesh);
  EXPECT_EQ (r.vertices, 6u);
  EXPECT_EQ (r.unreferenced_vertices, 2u);
  EXPECT_EQ (r.non_finite_vertices, 1u);
  EXPECT_EQ (r.components, 1u);  // isolated vertices are not components
  EXPECT_EQ (r.euler_characteristic, 2);
  EXPECT_EQ (r.genus, 0);
  const double a = 1.0 / std::sqrt (3.0);
  EXPECT_NEAR (r.bbox_diagonal, std::sqrt (3.0) * (10.0 + a), 1e-9);
}

TEST (MeshReport, NonManifoldEdge)
{
  // Three triangles sharing edge (0, 1).
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshReport r = reportOf (mesh);
  EXPECT_EQ (r.nonmanifold_edges, 1u);
  EXPECT_EQ (r.boundary_edges, 6u);
  EXPECT_EQ (r.nonmanifold_vertices, 2u);  // 0 and 1: three single-face fans each
  EXPECT_EQ (r.components, 1u);
  EXPECT_FALSE (r.manifold);
  EXPECT_EQ (r.genus, -1);
}

TEST (MeshReport, NonManifoldEdgesAsTheStagesSeeThem)
{
  // A face repeating a corner on edge (0, 1) uses it twice: four face sides for the report, but the stages
  // leave the face out, and countNonManifoldEdges with them. A third proper face makes it non-manifold.
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 1}};
  EXPECT_EQ (computeMeshReport (mesh, buildMeshTopology (mesh)).nonmanifold_edges, 1u);
  EXPECT_EQ (countNonManifoldEdges (mesh), 0u);
  mesh.triangles.emplace_back (0, 1, 4);
  EXPECT_EQ (countNonManifoldEdges (mesh), 1u);
}

TEST (MeshReport, BowTieVertex)
{
  // Two triangles touching only at vertex 0.
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 3, 4}};
  const MeshReport r = reportOf (mesh);
  EXPECT_EQ (r.nonmanifold_edges, 0u);
  EXPECT_EQ (r.nonmanifold_vertices, 1u);
  EXPECT_EQ (r.boundary_edges, 6u);
  EXPECT_EQ (r.boundary_loops, 1u);  // the two loops touch at vertex 0
  EXPECT_EQ (r.components, 1u);
  EXPECT_FALSE (r.manifold);
  EXPECT_EQ (r.genus, -1);
}

TEST (MeshReport, MoebiusBandIsNotOrientable)
{
  // A strip of 2 x n quads whose ends are glued with a half twist.
  const int n = 8;
  TriangleMesh mesh;
  for (int i = 0; i < n; ++i)
  {
    const double a = 2.0 * M_PI * i / n;
    for (int s : {-1, 1})
    {
      const double w = 0.3 * s * std::cos (a / 2), h = 0.3 * s * std::sin (a / 2);
      mesh.vertices.emplace_back ((1 + w) * std::cos (a), (1 + w) * std::sin (a), h);
    }
  }
  for (int i = 0; i < n; ++i)
  {
    const int a0 = 2 * i, a1 = 2 * i + 1;
    const bool last = i + 1 == n;
    const int b0 = last ? 1 : 2 * i + 2, b1 = last ? 0 : 2 * i + 3;  // the twist swaps the sides
    mesh.triangles.emplace_back (a0, b0, b1);
    mesh.triangles.emplace_back (a0, b1, a1);
  }
  const MeshReport r = reportOf (mesh);
  EXPECT_TRUE (r.manifold);
  EXPECT_EQ (r.boundary_loops, 1u);
  EXPECT_EQ (r.boundary_edges, static_cast<std::size_t> (2 * n));
  EXPECT_FALSE (r.orientable);
  EXPECT_EQ (r.genus, -1);
}

TEST (MeshReport, FlippedFaceIsStillOrientable)
{
  TriangleMesh mesh = makeTorus (12, 6);
  std::swap (mesh.triangles[5][0], mesh.triangles[5][1]);
  const MeshReport r = reportOf (mesh);
  EXPECT_TRUE (r.orientable);
  EXPECT_EQ (r.genus, 1);
}

TEST (MeshReport, EmptyMesh)
{
  const MeshReport r = reportOf (TriangleMesh ());
  EXPECT_EQ (r.vertices, 0u);
  EXPECT_EQ (r.components, 0u);
  EXPECT_FALSE (r.manifold);  // no surface, no genus
  EXPECT_FALSE (r.closed);
  EXPECT_EQ (r.genus, -1);
  EXPECT_EQ (r.bbox_diagonal, 0.0);
  EXPECT_EQ (r.mean_edge_length, 0.0);
}

TEST (MeshReport, PointsWithoutFaces)
{
  TriangleMesh cloud;
  cloud.vertices = {{0, 0, 0}, {3, 4, 0}, {1, 1, 1}};
  const MeshReport r = reportOf (cloud);
  EXPECT_EQ (r.vertices, 3u);
  EXPECT_EQ (r.faces, 0u);
  EXPECT_EQ (r.unreferenced_vertices, 3u);
  EXPECT_EQ (r.components, 0u);
  EXPECT_EQ (r.genus, -1);
  EXPECT_NEAR (r.bbox_diagonal, std::sqrt (9.0 + 16.0 + 1.0), 1e-12);
}

TEST (MeshCleaning, IndexMaps)
{
  TriangleMesh mesh = makeSquare ();                                // faces 0, 1 on vertices 0..3
  mesh.vertices.insert (mesh.vertices.begin () + 1, {7, 7, 7});     // input vertex 1: unreferenced
  mesh.triangles = {{0, 2, 3}, {0, 3, 4}};
  mesh.vertices.emplace_back (std::numeric_limits<double>::infinity (), 0, 0);  // 5: non-finite
  mesh.vertices.emplace_back (2, 0, 0);                                         // 6
  mesh.vertices.emplace_back (3, 0, 0);                                         // 7
  mesh.triangles.emplace_back (2, 5, 3);  // 2: uses the non-finite vertex
  mesh.triangles.emplace_back (3, 4, 0);  // 3: duplicate of face 1
  mesh.triangles.emplace_back (2, 6, 7);  // 4: zero area
  mesh.triangles.emplace_back (3, 3, 6);  // 5: repeated index
  mesh.triangles.emplace_back (2, 6, 3);  // 6: a proper face

  const CleanedMesh all = cleanMesh (mesh);
  EXPECT_EQ (all.face_to_input, (std::vector<int>{0, 1, 6}));
  EXPECT_EQ (all.vertex_to_input, (std::vector<int>{0, 2, 3, 4, 6}));
  EXPECT_EQ (all.input_to_vertex, (std::vector<int>{0, -1, 1, 2, 3, -1, 4, -1}));
  ASSERT_EQ (all.mesh.numTriangles (), 3u);
  EXPECT_EQ (all.mesh.triangles[2], Eigen::Vector3i (1, 4, 2));
  for (std::size_t v = 0; v < all.mesh.numVertices (); ++v)
    EXPECT_EQ (all.mesh.vertices[v], mesh.vertices[all.vertex_to_input[v]]);
  const MeshReport r = reportOf (all.mesh);
  EXPECT_EQ (r.unreferenced_vertices + r.non_finite_vertices + r.degenerate_faces + r.duplicate_faces, 0u);

  CleaningOptions keep_vertices;
  keep_vertices.drop_unreferenced_vertices = false;
  keep_vertices.drop_non_finite_vertices = false;
  const CleanedMesh faces_only = cleanMesh (mesh, keep_vertices);
  EXPECT_EQ (faces_only.face_to_input, (std::vector<int>{0, 1, 2, 6}));
  EXPECT_EQ (faces_only.mesh.numVertices (), mesh.numVertices ());
  for (int v = 0; v < 8; ++v)
    EXPECT_EQ (faces_only.input_to_vertex[v], v);

  const CleanedMesh nothing = cleanMesh (mesh, CleaningOptions{false, false, false, false});
  EXPECT_EQ (nothing.mesh.numTriangles (), mesh.numTriangles ());
  EXPECT_EQ (nothing.mesh.triangles, mesh.triangles);
}

TEST (MeshCleaning, WeldingMergesCoincidentVertices)
{
  // A square as two faces that repeat their corners, -0 beside +0, a face that welding makes degenerate, an
  // unreferenced copy, and two NaN vertices (never equal, so never welded).
  const double nan = std::numeric_limits<double>::quiet_NaN ();
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {-0.0, 1, 0}, {0, 1, 0}, {nan, 0, 0}, {nan, 0, 0}};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  EXPECT_TRUE (isTriangleSoup (mesh));
  mesh.triangles.emplace_back (3, 2, 4);  // shares vertices with both: no longer a soup; (0 2 2) once welded
  EXPECT_FALSE (isTriangleSoup (mesh));
  EXPECT_EQ (findCoincidentVertices (mesh), (std::vector<int>{0, 1, 2, 0, 2, 5, 5, 7, 8}));

  CleaningOptions weld_only{false, false, false, false};
  weld_only.weld_coincident_vertices = true;
  const CleanedMesh welded = cleanMesh (mesh, weld_only);
  EXPECT_EQ (welded.vertex_to_input, (std::vector<int>{0, 1, 2, 5, 7, 8}));
  EXPECT_EQ (welded.input_to_vertex, (std::vector<int>{0, 1, 2, 0, 2, 3, 3, 4, 5}));
  EXPECT_EQ (welded.mesh.triangles, (std::vector<Eigen::Vector3i>{{0, 1, 2}, {0, 2, 3}, {0, 2, 2}}));

  CleaningOptions everything;
  everything.weld_coincident_vertices = true;
  const CleanedMesh clean = cleanMesh (mesh, everything);
  EXPECT_EQ (clean.vertex_to_input, (std::vector<int>{0, 1, 2, 5}));
  EXPECT_EQ (clean.input_to_vertex, (std::vector<int>{0, 1, 2, 0, 2, 3, 3, -1, -1}));
  EXPECT_EQ (clean.face_to_input, (std::vector<int>{0, 1}));
  EXPECT_EQ (clean.mesh.triangles, (std::vector<Eigen::Vector3i>{{0, 1, 2}, {0, 2, 3}}));
  const MeshReport r = reportOf (clean.mesh);
  EXPECT_TRUE (r.manifold);
  EXPECT_EQ (r.boundary_loops, 1u);

  // Without the option nothing is welded: the two faces stay apart.
  EXPECT_EQ (cleanMesh (mesh).mesh.numVertices (), 6u);
  // Separate triangles stay a soup: nothing to weld.
  TriangleMesh apart;
  apart.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
  apart.triangles = {{0, 1, 2}, {3, 4, 5}};
  EXPECT_TRUE (isTriangleSoup (cleanMesh (apart, everything).mesh));
  EXPECT_FALSE (isTriangleSoup (TriangleMesh ()));
}

// ---- the shared real meshes -------------------------------------------------------------------------

namespace
{
  /// One row of the table in ../shared/meshes/README.md.
  struct SharedMeshRow
  {
    std::string file;
    std::size_t vertices = 0;
    std::size_t faces = 0;
    std::string closed_manifold;  // "yes" / "no"
    std::string genus;            // empty when not given
    std::size_t sharp_edges = 0;  // edges whose faces meet at more than 60 degrees
    double bbox_diagonal = 0.0;
  };

  std::string
  trim (const std::string& s)
  {
    const auto first = s.find_first_not_of (" \t\r");
    const auto last = s.find_last_not_of (" \t\r");
    return first == std::string::npos ? std::string () : s.substr (first, last - first + 1);
  }

  std::vector<std::string>
  splitRow (const std::string& line)
  {
    std::vector<std::string> cells;
    std::stringstream stream (line);
    std::string cell;
    std::getline (stream, cell, '|');  // before the leading '|'
    while (std::getline (stream, cell, '|'))
      cells.push_back (trim (cell));
    return cells;
  }

  /// Parses the markdown table; the columns are found by their header names, so reordering is harmless.
  std::vector<SharedMeshRow>
  readSharedMeshTable (const std::string& readme)
  {
    std::ifstream in (readme);
    std::vector<SharedMeshRow> rows;
    std::vector<std::string> header;
    auto column = [&header] (const std::string& name) {
      return static_cast<std::size_t> (std::find (header.begin (), header.end (), name) - header.begin ());
    };
    std::string line;
    while (std::getline (in, line))
    {
      if (trim (line).rfind ("|", 0) != 0)
        continue;
      const std::vector<std::string> cells = splitRow (trim (line));
      if (header.empty ())
      {
        header = cells;
        continue;
      }
      if (cells.empty () || cells[0].rfind ("---", 0) == 0 || cells.size () < header.size ())
        continue;
      SharedMeshRow row;
      row.file = cells[column ("file")];
      row.vertices = std::stoul (cells[column ("V")]);
      row.faces = std::stoul (cells[column ("F")]);
      row.closed_manifold = cells[column ("closed manifold")];
      row.genus = cells[column ("genus")];
      row.sharp_edges = std::stoul (cells[column ("edges > 60°")]);
      row.bbox_diagonal = std::stod (cells[column ("bbox diagonal")]);
      rows.push_back (row);
    }
    return rows;
  }

  std::string
  sharedMeshes ()
  {
    return PCL_SPARSE_SHARED_MESHES;
  }
} // namespace

TEST (MeshReportSharedMeshes, AgreeWithTheReadmeTable)
{
  const std::string readme = sharedMeshes () + "/README.md";
  if (!std::ifstream (readme))
    GTEST_SKIP () << "no shared meshes at " << sharedMeshes ();
  const std::vector<SharedMeshRow> rows = readSharedMeshTable (readme);
  ASSERT_EQ (rows.size (), 13u) << "table in " << readme;
  for (const SharedMeshRow& row : rows)
  {
    SCOPED_TRACE (row.file);
    const TriangleMesh mesh = loadTriangleMesh (sharedMeshes () + "/" + row.file);
    const MeshReport r = reportOf (mesh);
    EXPECT_EQ (r.vertices, row.vertices);
    EXPECT_EQ (r.faces, row.faces);
    EXPECT_EQ (r.closed, row.closed_manifold == "yes");
    if (!row.genus.empty ())
      EXPECT_EQ (r.genus, std::stoi (row.genus));
    // The table gives 4 significant digits.
    EXPECT_NEAR (r.bbox_diagonal, row.bbox_diagonal, 6e-4 * row.bbox_diagonal);
    EXPECT_EQ (findSharpEdges (mesh, buildMeshTopology (mesh), 60.0).size (), row.sharp_edges);
    if (row.closed_manifold == "yes")
      EXPECT_TRUE (r.manifold);
    EXPECT_EQ (r.nonmanifold_edges, 0u);
    EXPECT_EQ (r.components, 1u);
  }
}

TEST (MeshReportSharedMeshes, KnownTopology)
{
  if (!std::ifstream (sharedMeshes () + "/README.md"))
    GTEST_SKIP () << "no shared meshes at " << sharedMeshes ();
  auto report = [] (const std::string& name) { return reportOf (loadTriangleMesh (sharedMeshes () + "/" + name)); };

  const MeshReport fandisk = report ("fandisk.off");
  EXPECT_TRUE (fandisk.closed);
  EXPECT_EQ (fandisk.genus, 0);
  EXPECT_EQ (fandisk.euler_characteristic, 2);

  EXPECT_EQ (report ("anchor-dense.off").genus, 4);
  EXPECT_EQ (report ("turbine.off").genus, 11);

  const MeshReport blade = report ("blade.off");
  EXPECT_FALSE (blade.closed);
  EXPECT_TRUE (blade.manifold);
  EXPECT_EQ (blade.boundary_edges, 240u);

  const MeshReport bunny = report ("stanford-bunny.obj");
  EXPECT_EQ (bunny.unreferenced_vertices, 1113u);
  EXPECT_EQ (bunny.boundary_loops, 5u);  // the scan's holes in the base
  EXPECT_EQ (bunny.boundary_edges, 223u);
  EXPECT_EQ (bunny.euler_characteristic, -3);
}

TEST (MeshReportSharedMeshes, LinearTimeOn200kVertices)
{
  const std::string path = sharedMeshes () + "/koala-loop1-200k.ply";
  if (!std::ifstream (path))
    GTEST_SKIP () << "no " << path;
  const TriangleMesh mesh = loadTriangleMesh (path);
  const auto start = std::chrono::steady_clock::now ();
  const MeshTopology topology = buildMeshTopology (mesh);
  const MeshReport r = computeMeshReport (mesh, topology);
  const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  RecordProperty ("topology_and_report_seconds", std::to_string (seconds));
  std::cout << "koala-loop1-200k: topology + report in " << seconds << " s" << std::endl;
  EXPECT_EQ (r.genus, 0);
#if defined(NDEBUG) && !defined(__SANITIZE_ADDRESS__)
  EXPECT_LT (seconds, 2.0);  // about 0.1-0.3 s in Release; generous for loaded CI machines
#endif
}
