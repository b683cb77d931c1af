#include <pcl_sparse/mesh/mesh_primitives.h>

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <tuple>

namespace pcl_sparse
{
  TriangleMesh
  makeHeightFieldGrid (int nx, int ny, double half_x, double half_y, const std::function<double (double, double)>& height)
  {
    TriangleMesh mesh;
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
      {
        const double x = -half_x + 2.0 * half_x * i / nx;
        const double y = -half_y + 2.0 * half_y * j / ny;
        mesh.vertices.emplace_back (x, y, height (x, y));
      }
    auto id = [nx] (int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const int a = id (i, j), b = id (i + 1, j), c = id (i + 1, j + 1), d = id (i, j + 1);
        if ((i + j) % 2 == 0)
        {
          mesh.triangles.emplace_back (a, b, c);
          mesh.triangles.emplace_back (a, c, d);
        }
        else
        {
          mesh.triangles.emplace_back (a, b, d);
          mesh.triangles.emplace_back (b, c, d);
        }
      }
    return mesh;
  }

  TriangleMesh
  makePlaneGrid (int n, double half)
  {
    return makeHeightFieldGrid (n, n, half, half, [] (double, double) { return 0.0; });
  }

  TriangleMesh
  makeDisk (int rings, double radius)
  {
    TriangleMesh mesh;
    mesh.vertices.emplace_back (0.0, 0.0, 0.0);
    // Ring k has 6k vertices; ring_start[k] is the index of its first vertex.
    std::vector<int> ring_start (rings + 2, 1);
    for (int k = 1; k <= rings; ++k)
    {
      ring_start[k] = static_cast<int> (mesh.vertices.size ());
      for (int i = 0; i < 6 * k; ++i)
      {
        const double angle = 2.0 * M_PI * i / (6.0 * k);
        const double r = radius * k / rings;
        mesh.vertices.emplace_back (r * std::cos (angle), r * std::sin (angle), 0.0);
      }
    }
    for (int i = 0; i < 6; ++i)
      mesh.triangles.emplace_back (0, 1 + i, 1 + (i + 1) % 6);
    // Between ring k-1 (inner, 6(k-1) vertices) and ring k (outer, 6k): walk both by angle.
    for (int k = 2; k <= rings; ++k)
    {
      const int n_in = 6 * (k - 1), n_out = 6 * k;
      int i = 0, o = 0;
      while (i < n_in || o < n_out)
      {
        const int in_a = ring_start[k - 1] + i % n_in, in_b = ring_start[k - 1] + (i + 1) % n_in;
        const int out_a = ring_start[k] + o % n_out, out_b = ring_start[k] + (o + 1) % n_out;
        // Advance the ring whose next vertex comes first in angle.
        const double next_in = (i + 1.0) / n_in, next_out = (o + 1.0) / n_out;
        if (o < n_out && (i >= n_in || next_out <= next_in))
        {
          mesh.triangles.emplace_back (in_a, out_a, out_b);
          ++o;
        }
        else
        {
          mesh.triangles.emplace_back (in_a, out_a, in_b);
          ++i;
        }
      }
    }
    return mesh;
  }

  TriangleMesh
  makeIcosphere (int subdivisions, double radius, const Eigen::Vector3d& center)
  {
    const double t = (1.0 + std::sqrt (5.0)) / 2.0;
    std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (auto& p : v)
      p.normalize ();
    for (int s = 0; s < subdivisions; ++s)
    {
      std::map<std::pair<int, int>, int> midpoint;
      auto mid = [&] (int a, int b) {
        const auto key = std::make_pair (std::min (a, b), std::max (a, b));
        auto it = midpoint.find (key);
        if (it != midpoint.end ())
          return it->second;
        v.push_back ((v[a] + v[b]).normalized ());
        const int id = static_cast<int> (v.size ()) - 1;
        midpoint.emplace (key, id);
        return id;
      };
      std::vector<Eigen::Vector3i> next;
      next.reserve (f.size () * 4);
      for (const auto& tri : f)
      {
        const int ab = mid (tri[0], tri[1]), bc = mid (tri[1], tri[2]), ca = mid (tri[2], tri[0]);
        next.emplace_back (tri[0], ab, ca);
        next.emplace_back (tri[1], bc, ab);
        next.emplace_back (tri[2], ca, bc);
        next.emplace_back (ab, bc, ca);
      }
      f.swap (next);
    }
    TriangleMesh mesh;
    for (const auto& p : v)
      mesh.vertices.push_back (center + radius * p);
    mesh.triangles = f;
    return mesh;
  }

  TriangleMesh
  makeCube (int n, double half)
  {
    TriangleMesh mesh;
    std::map<std::tuple<int, int, int>, int> lattice;  // welds shared edge and corner vertices exactly
    auto vertex = [&] (int i, int j, int k) {
      const auto key = std::make_tuple (i, j, k);
      auto it = lattice.find (key);
      if (it != lattice.end ())
        return it->second;
      mesh.vertices.emplace_back (-half + 2.0 * half * i / n, -half + 2.0 * half * j / n, -half + 2.0 * half * k / n);
      const int id = static_cast<int> (mesh.vertices.size ()) - 1;
      lattice.emplace (key, id);
      return id;
    };
    // Each face: fixed axis `axis` at lattice value `side`; (u, v) axes chosen so u x v points outward.
    for (int axis = 0; axis < 3; ++axis)
      for (int side : {0, n})
      {
        const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
        const bool flip = side == 0;
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b)
          {
            auto corner = [&] (int du, int dv) {
              int c[3];
              c[axis] = side;
              c[u_axis] = a + du;
              c[v_axis] = b + dv;
              return vertex (c[0], c[1], c[2]);
            };
            const int p00 = corner (0, 0), p10 = corner (1, 0), p11 = corner (1, 1), p01 = corner (0, 1);
            if (!flip)
            {
              mesh.triangles.emplace_back (p00, p10, p11);
              mesh.triangles.emplace_back (p00, p11, p01);
            }
            else
            {
              mesh.triangles.emplace_back (p00, p11, p10);
              mesh.triangles.emplace_back (p00, p01, p11);
            }
          }
      }
    return mesh;
  }

  TriangleMesh
  makeCylinder (int around, int along, double radius, double half_height)
  {
    TriangleMesh mesh;
    for (int j = 0; j <= along; ++j)
      for (int i = 0; i < around; ++i)
      {
        const double angle = 2.0 * M_PI * i / around;
        mesh.vertices.emplace_back (radius * std::cos (angle), radius * std::sin (angle),
                                    -half_height + 2.0 * half_height * j / along);
      }
    auto id = [around] (int i, int j) { return j * around + (i % around); };
    for (int j = 0; j < along; ++j)
      for (int i = 0; i < around; ++i)
      {
        mesh.triangles.emplace_back (id (i, j), id (i + 1, j), id (i + 1, j + 1));
        mesh.triangles.emplace_back (id (i, j), id (i + 1, j + 1), id (i, j + 1));
      }
    return mesh;
  }

  TriangleMesh
  makeTorus (int major_segments, int minor_segments, double major_radius, double minor_radius)
  {
    TriangleMesh mesh;
    for (int i = 0; i < major_segments; ++i)
      for (int j = 0; j < minor_segments; ++j)
      {
        const double u = 2.0 * M_PI * i / major_segments, v = 2.0 * M_PI * j / minor_segments;
        const double ring = major_radius + minor_radius * std::cos (v);
        mesh.vertices.emplace_back (ring * std::cos (u), ring * std::sin (u), minor_radius * std::sin (v));
      }
    auto id = [&] (int i, int j) { return (i % major_segments) * minor_segments + (j % minor_segments); };
    for (int i = 0; i < major_segments; ++i)
      for (int j = 0; j < minor_segments; ++j)
      {
        mesh.triangles.emplace_back (id (i, j), id (i + 1, j), id (i + 1, j + 1));
        mesh.triangles.emplace_back (id (i, j), id (i + 1, j + 1), id (i, j + 1));
      }
    return mesh;
  }

  TriangleMesh
  makeTetrahedron ()
  {
    TriangleMesh mesh;
    const double s = 1.0 / std::sqrt (3.0);
    mesh.vertices = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
    mesh.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    return mesh;
  }

  void
  appendMesh (TriangleMesh& mesh, const TriangleMesh& other)
  {
    const int shift = static_cast<int> (mesh.vertices.size ());
    mesh.vertices.insert (mesh.vertices.end (), other.vertices.begin (), other.vertices.end ());
    for (const auto& t : other.triangles)
      mesh.triangles.emplace_back (t + Eigen::Vector3i::Constant (shift));
  }
} // namespace pcl_sparse
