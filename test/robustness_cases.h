#pragma once
/// \file robustness_cases.h
/// Generators of bad and awkward meshes for the robustness tests: each case is the text of an OBJ file
/// (written by hand, not by saveTriangleMesh, so that invalid indices and NaN coordinates can be written)
/// and what the tools must do with it.

#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace pcl_sparse
{
  namespace robustness
  {
    /// What every tool must do with a case: succeed, fail cleanly, or either (both are sensible).
    enum class Expect
    {
      Success,
      Failure,
      Either
    };

    struct MeshCase
    {
      std::string name;  ///< file stem, also the test's label
      std::string obj;   ///< OBJ file content
      Expect expect;     ///< for every tool, unless coding says otherwise
      Expect coding = Expect::Either;  ///< pcl_sparse_encode, _resample, _decode, when override_coding
      bool override_coding = false;
    };

    inline void
    PrintTo (const MeshCase& c, std::ostream* os)
    {
      *os << c.name;
    }

    /// OBJ text of \a mesh, coordinates with 17 significant digits (round trip exact), 1-based indices.
    inline std::string
    objText (const TriangleMesh& mesh)
    {
      std::string text;
      char line[128];
      for (const Eigen::Vector3d& v : mesh.vertices)
      {
        std::snprintf (line, sizeof (line), "v %.17g %.17g %.17g\n", v.x (), v.y (), v.z ());
        text += line;
      }
      for (const Eigen::Vector3i& t : mesh.triangles)
      {
        std::snprintf (line, sizeof (line), "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
        text += line;
      }
      return text;
    }

    inline TriangleMesh
    scaled (TriangleMesh mesh, double factor)
    {
      for (Eigen::Vector3d& v : mesh.vertices)
        v *= factor;
      return mesh;
    }

    /// \a mesh as a triangle soup: every face with its own three vertices (all positions duplicated).
    inline TriangleMesh
    triangleSoup (const TriangleMesh& mesh)
    {
      TriangleMesh soup;
      for (const Eigen::Vector3i& t : mesh.triangles)
      {
        const int first = static_cast<int> (soup.vertices.size ());
        for (int k = 0; k < 3; ++k)
          soup.vertices.push_back (mesh.vertices[t[k]]);
        soup.triangles.push_back (Eigen::Vector3i (first, first + 1, first + 2));
      }
      return soup;
    }

    /// A small closed mesh with some curvature: the base of most cases (162 vertices, 320 faces).
    inline TriangleMesh
    baseMesh ()
    {
      return makeIcosphere (2);
    }

    /// Every case of the robustness table. Meshes are tiny so that the whole table runs in seconds.
    inline std::vector<MeshCase>
    meshCases ()
    {
      std::vector<MeshCase> cases;
      const TriangleMesh base = baseMesh ();

      cases.push_back ({"empty_file", "", Expect::Failure});
      cases.push_back ({"comments_only", "# nothing here\n", Expect::Failure});
      // pcl_sparse_info reports it as a point cloud; nothing can be coded from it.
      cases.push_back ({"vertices_no_faces", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", Expect::Either, Expect::Failure, true});
      cases.push_back ({"one_triangle", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", Expect::Either});
      cases.push_back ({"tetrahedron", objText (makeTetrahedron ()), Expect::Either});
      // Zero-area faces: collinear points and repeated indices.
      cases.push_back ({"all_degenerate", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\nf 1 1 2\nf 4 4 4\n",
                        Expect::Either, Expect::Failure, true});  // reported, but no surface to code
      {
        TriangleMesh m = base;
        m.vertices.push_back (m.vertices[0]);  // a few degenerate faces among good ones
        const int n = static_cast<int> (m.vertices.size ());
        m.triangles.push_back (Eigen::Vector3i (0, 1, 1));
        m.triangles.push_back (Eigen::Vector3i (0, n - 1, 2));
        cases.push_back ({"some_degenerate", objText (m), Expect::Success});
      }
      {
        std::string text = objText (base);
        text.replace (text.find ("v "), 0, "v nan 0 0\n");
        cases.push_back ({"nan_vertex", text, Expect::Failure});
      }
      {
        std::string text = objText (base);
        text.replace (text.find ("v "), 0, "v 0 inf 0\n");
        cases.push_back ({"inf_vertex", text, Expect::Failure});
      }
      cases.push_back ({"index_out_of_range", objText (base) + "f 1 2 100000\n", Expect::Failure});
      cases.push_back ({"index_zero", objText (base) + "f 0 1 2\n", Expect::Failure});
      cases.push_back ({"index_negative_beyond", objText (base) + "f -1 -2 -100000\n", Expect::Failure});
      cases.push_back ({"index_huge", objText (base) + "f 1 2 99999999999999999999\n", Expect::Failure});
      // The tools weld a soup's corners at equal positions (with a note), so every tool takes it.
      cases.push_back ({"triangle_soup", objText (triangleSoup (base)), Expect::Success});
      {
        // Every vertex listed twice; faces use the first copy or the second alternately.
        TriangleMesh m = base;
        const int n = static_cast<int> (base.vertices.size ());
        for (int v = 0; v < n; ++v)
          m.vertices.push_back (base.vertices[v]);
        for (std::size_t f = 0; f < m.triangles.size (); f += 2)
          m.triangles[f] += Eigen::Vector3i::Constant (n);
        cases.push_back ({"duplicate_vertices", objText (m), Expect::Either});
      }
      {
        TriangleMesh m = base;  // same face twice, once flipped
        m.triangles.push_back (base.triangles[0]);
        m.triangles.push_back (Eigen::Vector3i (base.triangles[1][0], base.triangles[1][2], base.triangles[1][1]));
        cases.push_back ({"duplicate_faces", objText (m), Expect::Either});
      }
      {
        // Non-manifold edge: a plane with three fins on its middle row of edges (four faces per edge).
        TriangleMesh m = makePlaneGrid (8);
        const int n = static_cast<int> (m.vertices.size ());
        for (int k = 0; k < 3; ++k)
        {
          const Eigen::Vector3i t = m.triangles[60 + 2 * k];
          m.vertices.push_back ((m.vertices[t[0]] + m.vertices[t[1]]) / 2 + Eigen::Vector3d (0, 0, 0.3));
          m.vertices.push_back ((m.vertices[t[0]] + m.vertices[t[1]]) / 2 + Eigen::Vector3d (0, 0, -0.3));
          m.triangles.push_back (Eigen::Vector3i (t[0], t[1], n + 2 * k));
          m.triangles.push_back (Eigen::Vector3i (t[1], t[0], n + 2 * k + 1));
        }
        cases.push_back ({"non_manifold_edges", objText (m), Expect::Success});
      }
      {
        // Non-manifold vertex: two spheres touching at one shared vertex.
        TriangleMesh a = base;
        TriangleMesh b = base;
        const Eigen::Vector3d shift = base.vertices[0] * 2.0;
        for (Eigen::Vector3d& v : b.vertices)
          v = shift - v;  // point reflection: b's vertex 0 lands on a's vertex 0
        const int n = static_cast<int> (a.vertices.size ());
        for (const Eigen::Vector3d& v : b.vertices)
          a.vertices.push_back (v);
        for (Eigen::Vector3i t : b.triangles)
        {
          for (int k = 0; k < 3; ++k)
            t[k] = t[k] == 0 ? 0 : t[k] + n;
          a.triangles.push_back (Eigen::Vector3i (t[0], t[2], t[1]));
        }
        cases.push_back ({"non_manifold_vertex", objText (a), Expect::Success});
      }
      {
        TriangleMesh m = base;
        for (int k = 0; k < 50; ++k)
          m.vertices.push_back (Eigen::Vector3d (3.0 + k, 0.5 * k, -1.0));
        cases.push_back ({"isolated_vertices", objText (m), Expect::Success});
      }
      {
        TriangleMesh m;
        for (int k = 0; k < 300; ++k)  // 300 tiny separate tetrahedra
        {
          TriangleMesh t = scaled (makeTetrahedron (), 0.01);
          for (Eigen::Vector3d& v : t.vertices)
            v += Eigen::Vector3d (0.1 * (k % 17), 0.1 * (k / 17), 0.0);
          appendMesh (m, t);
        }
        cases.push_back ({"many_tiny_components", objText (m), Expect::Either});
      }
      {
        TriangleMesh m;
        for (int k = 0; k < 200; ++k)  // 200 separate single triangles
        {
          const int first = static_cast<int> (m.vertices.size ());
          const Eigen::Vector3d o (0.1 * (k % 20), 0.1 * (k / 20), 0.0);
          m.vertices.push_back (o);
          m.vertices.push_back (o + Eigen::Vector3d (0.05, 0, 0));
          m.vertices.push_back (o + Eigen::Vector3d (0, 0.05, 0.01));
          m.triangles.push_back (Eigen::Vector3i (first, first + 1, first + 2));
        }
        cases.push_back ({"many_single_triangles", objText (m), Expect::Either});
      }
      cases.push_back ({"open_plane", objText (makePlaneGrid (12)), Expect::Success});
      cases.push_back ({"open_cylinder", objText (makeCylinder (24, 8)), Expect::Success});
      {
        TriangleMesh m = base;  // a sphere with a hole: drop 20 faces around vertex 0
        TriangleMesh holed;
        holed.vertices = m.vertices;
        for (const Eigen::Vector3i& t : m.triangles)
          if ((m.vertices[t[0]] - m.vertices[0]).norm () > 0.5)
            holed.triangles.push_back (t);
        cases.push_back ({"sphere_with_hole", objText (holed), Expect::Success});
      }
      {
        TriangleMesh m = base;  // every third face flipped
        for (std::size_t f = 0; f < m.triangles.size (); f += 3)
          std::swap (m.triangles[f][1], m.triangles[f][2]);
        cases.push_back ({"inconsistent_orientation", objText (m), Expect::Success});
      }
      cases.push_back ({"scale_1e-9", objText (scaled (base, 1e-9)), Expect::Success});
      cases.push_back ({"scale_1e9", objText (scaled (base, 1e9)), Expect::Success});
      {
        TriangleMesh m = base;  // far from the origin: large offset, small size
        for (Eigen::Vector3d& v : m.vertices)
          v += Eigen::Vector3d (1e6, -1e6, 1e6);
        cases.push_back ({"offset_1e6", objText (m), Expect::Success});
      }
      {
        TriangleMesh m = base;  // all vertices on a plane: a flat, doubly covered disk
        for (Eigen::Vector3d& v : m.vertices)
          v.z () = 0.0;
        cases.push_back ({"flattened_sphere", objText (m), Expect::Either});
      }
      cases.push_back ({"binary_garbage", std::string ("\x7f\x00\xff\x01garbage\x00\x02", 14), Expect::Failure});
      return cases;
    }
  } // namespace robustness
} // namespace pcl_sparse
