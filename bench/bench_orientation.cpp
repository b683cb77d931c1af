/// \file bench_orientation.cpp
/// Spanning-tree normal orientation on a cloud of many short wires (power lines, branches): each wire is a
/// flat tree, oriented along its thinnest axis by the grazing-point spreading. Prints points, wires, seconds
/// and a checksum of the normals (the same before and after a change that only makes it faster).
///
///   bench_orientation [WIRES ...]     (default: 2000 8000 32000 128000; 10 points a wire)
///
/// Measured 2026-12-04 (2 shared cores): 20k / 80k / 320k points 0.049 / 0.54 / 9.3 s when each flat tree
/// allocated arrays over the whole cloud; 0.011 / 0.047 / 0.22 s, and 1.28M points 0.94 s, since.

#include <pcl_sparse/cloud/normal_orientation.h>
#include <pcl_sparse/cloud/point_neighborhoods.h>

#include "bench_main.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// \a wires wires of \a per points 0.1 apart along x, 100 apart from each other, normals perpendicular to
  /// x in random directions; each point's neighbours the two before and after it on its wire.
  void
  makeWires (int wires, int per, std::vector<Eigen::Vector3d>& positions, std::vector<Eigen::Vector3d>& normals,
             PointNeighborhoods& hoods)
  {
    std::mt19937 rng (3);
    std::uniform_real_distribution<double> u (-1.0, 1.0);
    hoods.offsets = {0};
    for (int w = 0; w < wires; ++w)
    {
      const Eigen::Vector3d base (100.0 * (w % 1000), 100.0 * (w / 1000), 0.0);
      const int first = static_cast<int> (positions.size ());
      for (int i = 0; i < per; ++i)
      {
        positions.push_back (base + Eigen::Vector3d (0.1 * i, 0.0, 0.0));
        normals.push_back (Eigen::Vector3d (0.0, u (rng), u (rng)).normalized ());
      }
      for (int i = 0; i < per; ++i)
      {
        for (int j = std::max (0, i - 2); j <= std::min (per - 1, i + 2); ++j)
          if (j != i)
            hoods.neighbors.push_back (first + j);
        hoods.offsets.push_back (hoods.neighbors.size ());
      }
    }
    hoods.spacing.assign (positions.size (), 0.1);
  }
} // namespace

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, [] (int argc, char** argv) {
    std::vector<int> counts = {2000, 8000, 32000, 128000};
    if (argc > 1)
      counts.clear ();
    for (int a = 1; a < argc; ++a)
      counts.push_back (std::stoi (argv[a]));
    for (const int wires : counts)
    {
      std::vector<Eigen::Vector3d> positions, normals;
      PointNeighborhoods hoods;
      makeWires (wires, 10, positions, normals, hoods);
      const std::vector<std::uint8_t> usable (positions.size (), 1);
      const auto start = std::chrono::steady_clock::now ();
      orientBySpanningTree (positions, hoods, usable, normals);
      const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      double checksum = 0.0;
      for (std::size_t i = 0; i < normals.size (); ++i)
        checksum += static_cast<double> (i % 7 + 1) * (normals[i].y () + 2.0 * normals[i].z ());
      std::printf ("%zu points, %d wires: %.3f s, checksum %.12g\n", positions.size (), wires, seconds, checksum);
    }
    return 0;
  });
}
