#pragma once
// Test clouds made by the tests and benches themselves (issue 16 point 5; never committed): pinhole depth
// images (a stepped slanted plane), an airborne-like tile, a terrain-like height field (as a cloud or a
// mesh), a shared mesh sampled with noise, and many noisy copies of it laid out on a grid like a city block.
// Large ones are written as binary PCD a row at a time, so even 10^8 points need little memory.
// Deterministic: the same options and seed give the same file, byte for byte.

#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/mesh/surface_sampling.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_sparse_test
{
  /// A pinhole camera at 0 looking along +z (focal 60 pixels), width x height pixels: pixel (x, y) holds the
  /// point at depth \a depth (x, y) on its ray, none where that is NaN.
  inline pcl_sparse::ScanCloud
  pinholeScan (int width, int height, const std::function<double (int, int)>& depth)
  {
    const double f = 60.0;
    pcl_sparse::ScanCloud scan;
    scan.width = width;
    scan.height = height;
    scan.has_sensor_pose = true;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
      {
        const double z = depth (x, y);
        if (std::isnan (z))
          continue;
        scan.positions.emplace_back ((x - 0.5 * width) / f * z, (y - 0.5 * height) / f * z, z);
        scan.indices.push_back (static_cast<std::size_t> (y) * width + x);
      }
    return scan;
  }

  /// A spinning lidar in a street, with the truth it samples.
  struct LidarStreet
  {
    pcl_sparse::ScanCloud scan;  ///< unorganized, in firing order, sensor pose set
    pcl_sparse::TriangleMesh truth;  ///< the street's faces (toward the sensor) and the car's (outward)
  };

  namespace detail
  {
    /// Ray from \a o along \a d against the box [lo, hi]: the distance to where it enters, or, from inside,
    /// leaves it, and the face's normal against the ray.
    inline bool
    rayBox (const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
            double& t, Eigen::Vector3d& normal)
    {
      double near = -std::numeric_limits<double>::infinity (), far = std::numeric_limits<double>::infinity ();
      int near_axis = -1, far_axis = -1;
      for (int a = 0; a < 3; ++a)
      {
        if (d[a] == 0.0)
        {
          if (o[a] < lo[a] || o[a] > hi[a])
            return false;
          continue;
        }
        double t0 = (lo[a] - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
        if (t0 > t1)
          std::swap (t0, t1);
        if (t0 > near)
          near = t0, near_axis = a;
        if (t1 < far)
          far = t1, far_axis = a;
      }
      if (near > far || far <= 0.0)
        return false;
      const int axis = near <= 0.0 ? far_axis : near_axis;
      t = near <= 0.0 ? far : near;
      normal = Eigen::Vector3d::Zero ();
      normal[axis] = d[axis] > 0.0 ? -1.0 : 1.0;
      return true;
    }

    /// The faces of the box [lo, hi] (two triangles each; the bottom left out when \a open_bottom, the top
    /// when \a open_top), turned toward \a inside (a street seen from within) or, without it, outward.
    inline void
    addBox (const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, bool open_bottom, bool open_top,
            const Eigen::Vector3d* inside, pcl_sparse::TriangleMesh& mesh)
    {
      const int base = static_cast<int> (mesh.vertices.size ());
      for (int k = 0; k < 8; ++k)  // corner bits: x 1, y 2, z 4
        mesh.vertices.emplace_back (k & 1 ? hi.x () : lo.x (), k & 2 ? hi.y () : lo.y (), k & 4 ? hi.z () : lo.z ());
      const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
      const Eigen::Vector3d centre = 0.5 * (lo + hi);
      for (int f = 0; f < 6; ++f)
      {
        if ((f == 0 && open_bottom) || (f == 1 && open_top))
          continue;
        for (const auto& tri : {Eigen::Vector3i (base + faces[f][0], base + faces[f][1], base + faces[f][2]),
                                Eigen::Vector3i (base + faces[f][0], base + faces[f][2], base + faces[f][3])})
        {
          const Eigen::Vector3d& a = mesh.vertices[tri[0]];
          const Eigen::Vector3d n = (mesh.vertices[tri[1]] - a).cross (mesh.vertices[tri[2]] - a);
          const bool toward = inside ? n.dot (*inside - a) > 0.0 : n.dot (a - centre) > 0.0;
          mesh.triangles.push_back (toward ? tri : Eigen::Vector3i (tri[0], tri[2], tri[1]));
        }
      }
    }
  } // namespace detail

  /// A spinning lidar 1.8 m above the road of a street 18 m wide and 80 m long between walls 12 m high (open
  /// sky: no return), with a parked car (a 4.5 x 1.8 x 1.5 m box): 32 rings from -30.67 degrees up, 1.33
  /// apart, and 0.17-degree azimuth steps, as the shared HDL-32E frames; range noise sigma \a noise.
  inline LidarStreet
  lidarStreet (std::uint32_t seed = 12, double noise = 0.01)
  {
    std::mt19937 random (seed);
    std::normal_distribution<double> gauss (0.0, noise);
    const Eigen::Vector3d sensor (0.0, 0.0, 1.8);
    const Eigen::Vector3d street_lo (-40.0, -8.0, 0.0), street_hi (40.0, 10.0, 12.0);
    const Eigen::Vector3d car_lo (6.0, -6.5, 0.0), car_hi (10.5, -4.7, 1.5);
    LidarStreet street;
    pcl_sparse::ScanCloud& scan = street.scan;
    const int columns = 2118;  // 360 / 0.17
    for (int column = 0; column < columns; ++column)
      for (int ring = 0; ring < 32; ++ring)
      {
        const double azimuth = 2.0 * M_PI * column / columns - M_PI, elevation = (-30.67 + 1.33 * ring) * M_PI / 180.0;
        const Eigen::Vector3d d (std::cos (elevation) * std::cos (azimuth), std::cos (elevation) * std::sin (azimuth),
                                 std::sin (elevation));
        double t = 0.0, t_car = 0.0;
        Eigen::Vector3d n, n_car;
        if (!detail::rayBox (sensor, d, street_lo, street_hi, t, n))
          continue;
        if (detail::rayBox (sensor, d, car_lo, car_hi, t_car, n_car) && t_car < t)
          t = t_car, n = n_car;
        if (n.z () < 0.0)  // the street's top: sky
          continue;
        scan.positions.push_back (sensor + (t + gauss (random)) * d);
      }
    scan.width = static_cast<std::uint32_t> (scan.positions.size ());
    scan.height = 1;
    scan.sensor_origin = sensor;
    scan.has_sensor_pose = true;
    scan.report.input_points = scan.report.kept = scan.positions.size ();
    detail::addBox (street_lo, street_hi, false, true, &sensor, street.truth);
    detail::addBox (car_lo, car_hi, true, false, nullptr, street.truth);
    return street;
  }

  /// A Kinect-like camera (pinholeScan, 64 pixels wide) sees the slanted plane z = 2 + 0.8 x with depth
  /// stored in steps of 0.15, 4.5 pixel spacings: a staircase whose risers the plain gap rule refuses.
  /// \param[in] height rows of pixels (the plane does not slant along them)
  inline pcl_sparse::ScanCloud
  steppedSlantedPlane (int height = 48)
  {
    const int width = 64;
    const double step = 0.15;
    return pinholeScan (width, height, [&] (int x, int) {
      const double u = (x - 0.5 * width) / 60.0;
      return step * std::round (2.0 / (1.0 - 0.8 * u) / step);  // the ray (u z, v z, z) meets the plane at 2 / (1 - 0.8 u)
    });
  }

  /// An airborne-like tile: points on a jittered 1 m grid over 2 half x 2 half m of gently rolling ground at
  /// height \a z0, as evenly spaced far from the origin as near it (no sensor at the origin sampled them).
  inline std::vector<Eigen::Vector3d>
  airborneTile (int half, double z0, std::mt19937& rng)
  {
    std::uniform_real_distribution<double> jitter (-0.3, 0.3);
    std::vector<Eigen::Vector3d> points;
    for (int i = -half; i < half; ++i)
      for (int j = -half; j < half; ++j)
      {
        const double x = i + jitter (rng), y = j + jitter (rng);
        points.emplace_back (x, y, z0 + 2.0 * std::sin (0.05 * x) * std::cos (0.07 * y));
      }
    return points;
  }

  /// Points drawn uniformly by area on \a mesh, seeded; \a area gets the mesh's area.
  inline std::vector<Eigen::Vector3d>
  sampleSurface (const pcl_sparse::TriangleMesh& mesh, std::size_t n, std::uint64_t seed, double& area)
  {
    std::mt19937_64 rng (seed);
    std::vector<Eigen::Vector3d> probes;
    pcl_sparse::sampleMeshSurfaceWith (mesh, n, rng, probes, nullptr, &area);
    return probes;
  }

  /// Writes a binary PCD of x y z (float, or double when \a double_xyz) whose points come from
  /// next (Eigen::Vector3d&), called \a n times; the points are written in blocks as they come.
  template <typename Next>
  void
  writeBinaryPcd (const std::string& path, std::size_t n, bool double_xyz, Next next)
  {
    std::FILE* file = std::fopen (path.c_str (), "wb");
    if (!file)
      throw std::runtime_error ("cannot write " + path);
    const char* size = double_xyz ? "8 8 8" : "4 4 4";
    std::fprintf (file,
                  "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\nSIZE %s\nTYPE F F F\n"
                  "COUNT 1 1 1\nWIDTH %zu\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS %zu\nDATA binary\n",
                  size, n, n);
    std::vector<char> block;
    const std::size_t point_bytes = double_xyz ? 24 : 12;
    block.reserve (65536 * point_bytes);
    Eigen::Vector3d p;
    for (std::size_t i = 0; i < n; ++i)
    {
      next (p);
      for (int k = 0; k < 3; ++k)
      {
        char bytes[8];
        if (double_xyz)
          std::memcpy (bytes, &p[k], 8);
        else
        {
          const float f = static_cast<float> (p[k]);
          std::memcpy (bytes, &f, 4);
        }
        block.insert (block.end (), bytes, bytes + (double_xyz ? 8 : 4));
      }
      if (block.size () >= 65536 * point_bytes || i + 1 == n)
      {
        if (std::fwrite (block.data (), 1, block.size (), file) != block.size ())
        {
          std::fclose (file);
          throw std::runtime_error ("cannot write " + path);
        }
        block.clear ();
      }
    }
    if (std::fclose (file) != 0)
      throw std::runtime_error ("cannot write " + path);
  }

  /// Options of writeTerrainPcd.
  struct TerrainOptions
  {
    std::size_t points = 1000000;  ///< points of the height field
    double side = 1000.0;          ///< side of the square it covers (metres)
    double relief = 40.0;          ///< height of its hills (metres)
    double noise = 0.02;           ///< standard deviation of the height noise (metres)
    Eigen::Vector3d offset = Eigen::Vector3d::Zero ();  ///< added to every point (map coordinates)
    bool double_xyz = false;       ///< write x y z as double (for map coordinates)
    std::uint64_t seed = 1;        ///< the random generator's seed
  };

  /// A terrain-like height field: a jittered grid over a square, rows along y, with hills of a few wave
  /// lengths and noise, like an aerial survey; exactly options.points points.
  inline void
  writeTerrainPcd (const std::string& path, const TerrainOptions& options)
  {
    const std::size_t columns = std::max<std::size_t> (1, static_cast<std::size_t> (std::ceil (std::sqrt (double (options.points)))));
    const double step = options.side / static_cast<double> (columns);
    std::mt19937_64 rng (options.seed);
    std::uniform_real_distribution<double> jitter (-0.4, 0.4);
    std::normal_distribution<double> noise (0.0, options.noise);
    const double k = 2.0 * M_PI / options.side;
    std::size_t i = 0;
    writeBinaryPcd (path, options.points, options.double_xyz, [&] (Eigen::Vector3d& p) {
      const double x = (static_cast<double> (i % columns) + 0.5 + jitter (rng)) * step;
      const double y = (static_cast<double> (i / columns) + 0.5 + jitter (rng)) * step;
      const double z = options.relief * (0.5 * std::sin (1.3 * k * x) * std::cos (0.9 * k * y) +
                                         0.3 * std::sin (3.7 * k * (x + 0.4 * y)) + 0.2 * std::cos (7.1 * k * (y - 0.3 * x))) +
                       noise (rng);
      p = Eigen::Vector3d (x, y, z) + options.offset;
      ++i;
    });
  }

  /// A terrain-like triangle mesh: the height field of writeTerrainPcd on a regular grid of
  /// \a side x \a side vertices (no jitter), two triangles per cell, written as binary little-endian PLY
  /// (double x y z; faces as uchar-int lists), vertices then faces, a block at a time.
  inline void
  writeTerrainMeshPly (const std::string& path, std::size_t side, const TerrainOptions& options)
  {
    std::FILE* file = std::fopen (path.c_str (), "wb");
    if (!file || side < 2)
      throw std::runtime_error ("cannot write " + path);
    const std::size_t cells = (side - 1) * (side - 1);
    std::fprintf (file,
                  "ply\nformat binary_little_endian 1.0\nelement vertex %zu\nproperty double x\nproperty double y\n"
                  "property double z\nelement face %zu\nproperty list uchar int vertex_indices\nend_header\n",
                  side * side, 2 * cells);
    std::mt19937_64 rng (options.seed);
    std::normal_distribution<double> noise (0.0, options.noise);
    const double step = options.side / static_cast<double> (side - 1);
    const double k = 2.0 * M_PI / options.side;
    std::string block;
    const auto flush = [&] (bool last) {
      if ((block.size () >= (1 << 20) || last) && std::fwrite (block.data (), 1, block.size (), file) != block.size ())
        throw std::runtime_error ("cannot write " + path);
      if (block.size () >= (1 << 20) || last)
        block.clear ();
    };
    for (std::size_t i = 0; i < side * side; ++i)
    {
      const double x = static_cast<double> (i % side) * step, y = static_cast<double> (i / side) * step;
      const double z = options.relief * (0.5 * std::sin (1.3 * k * x) * std::cos (0.9 * k * y) +
                                         0.3 * std::sin (3.7 * k * (x + 0.4 * y)) + 0.2 * std::cos (7.1 * k * (y - 0.3 * x))) +
                       noise (rng);
      const double v[3] = {x + options.offset.x (), y + options.offset.y (), z + options.offset.z ()};
      block.append (reinterpret_cast<const char*> (v), sizeof (v));
      flush (false);
    }
    for (std::size_t c = 0; c < cells; ++c)
    {
      const int a = static_cast<int> ((c / (side - 1)) * side + c % (side - 1));
      const int s = static_cast<int> (side);
      for (const std::array<int, 3>& t : {std::array<int, 3>{a, a + 1, a + s + 1}, std::array<int, 3>{a, a + s + 1, a + s}})
      {
        block += '\3';
        block.append (reinterpret_cast<const char*> (t.data ()), sizeof (t));
      }
      flush (false);
    }
    flush (true);
    if (std::fclose (file) != 0)
      throw std::runtime_error ("cannot write " + path);
  }

  /// Options of writeCityBlockPcd.
  struct CityBlockOptions
  {
    int copies_x = 4;                  ///< copies along x
    int copies_y = 4;                  ///< copies along y
    std::size_t points_per_copy = 100000;  ///< points sampled on each copy
    double size = 20.0;                ///< each copy is scaled to this largest side (metres)
    double spacing = 30.0;             ///< distance between the copies' centres (metres)
    double noise = 0.01;               ///< standard deviation of the noise on every coordinate (metres)
    std::uint64_t seed = 1;            ///< the random generator's seed (each copy draws its own points)
  };

  /// Copies of \a mesh laid out on a grid in the xy plane like a city block, each sampled on its own
  /// (options.points_per_copy points, uniformly by area) with noise; copies_x x copies_y x points_per_copy
  /// points. With one copy: the mesh sampled with noise.
  inline void
  writeCityBlockPcd (const std::string& path, const pcl_sparse::TriangleMesh& mesh, const CityBlockOptions& options)
  {
    Eigen::Vector3d low = mesh.vertices.front (), high = low;
    for (const Eigen::Vector3d& v : mesh.vertices)
    {
      low = low.cwiseMin (v);
      high = high.cwiseMax (v);
    }
    const double scale = options.size / std::max ((high - low).maxCoeff (), 1e-12);
    const Eigen::Vector3d centre = 0.5 * (low + high);
    std::mt19937_64 rng (options.seed);
    std::normal_distribution<double> noise (0.0, options.noise);
    const std::size_t copies = static_cast<std::size_t> (options.copies_x) * static_cast<std::size_t> (options.copies_y);
    std::vector<Eigen::Vector3d> samples;
    std::size_t copy = 0, next = 0;
    writeBinaryPcd (path, copies * options.points_per_copy, false, [&] (Eigen::Vector3d& p) {
      if (next == samples.size ())
      {
        double area = 0.0;
        samples = sampleSurface (mesh, options.points_per_copy, options.seed * 7919 + copy, area);
        ++copy;
        next = 0;
      }
      const std::size_t c = copy - 1;
      const Eigen::Vector3d place (options.spacing * static_cast<double> (c % static_cast<std::size_t> (options.copies_x)),
                                   options.spacing * static_cast<double> (c / static_cast<std::size_t> (options.copies_x)), 0.0);
      p = scale * (samples[next++] - centre) + place + Eigen::Vector3d (noise (rng), noise (rng), noise (rng));
    });
  }
} // namespace pcl_sparse_test
