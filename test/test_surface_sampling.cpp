// Draws by area on a mesh (mesh/surface_sampling.h): the face search the samplers use. Built twice: here and, with
// UndefinedBehaviorSanitizer's float-cast-overflow check, in test/sanitized (a draw's bucket must never reach an
// out-of-range cast).
#include <pcl_sparse/mesh/surface_sampling.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace pcl_sparse;

TEST (CumulativeAreaSearch, FindsWhatLowerBoundFinds)
{
  // Sums of areas as meshes give them: even, random, runs of zero-area faces, one face holding nearly all the
  // area (a bucket of many faces), all zero, one face. Every x: random, each sum and each bucket bound itself and
  // its neighbours.
  std::mt19937 random (11);
  std::uniform_real_distribution<double> area (0.0, 1.0);
  std::vector<std::vector<double>> areas (6);
  for (int t = 0; t < 1000; ++t)
  {
    areas[0].push_back (1.0);
    areas[1].push_back (area (random));
    areas[2].push_back (t % 7 < 3 ? 0.0 : area (random));
    areas[3].push_back (t == 500 ? 1e9 : area (random) * 1e-3);
    areas[4].push_back (0.0);
  }
  areas[5] = {0.25};
  for (const std::vector<double>& a : areas)
  {
    std::vector<double> cumulative;
    double total = 0.0;
    for (const double x : a)
      cumulative.push_back (total += x);
    const CumulativeAreaSearch search (cumulative);
    auto expected = [&] (double x) {
      return std::min<std::size_t> (std::lower_bound (cumulative.begin (), cumulative.end (), x) - cumulative.begin (),
                                    cumulative.size () - 1);
    };
    std::vector<double> xs = {0.0, total, 2.0 * total + 1.0, std::numeric_limits<double>::max ()};
    for (int i = 0; i < 20000; ++i)
      xs.push_back (std::uniform_real_distribution<double> (0.0, 1.0) (random) * total);
    for (const double c : cumulative)
      for (const double x : {c, std::nextafter (c, 0.0), std::nextafter (c, 2.0 * c + 1.0)})
        xs.push_back (x);
    for (std::size_t j = 0; j <= cumulative.size (); ++j)  // the buckets' bounds, where rounding decides
    {
      const double bound = total * (static_cast<double> (j) / static_cast<double> (cumulative.size ()));
      for (const double x : {bound, std::nextafter (bound, 0.0), std::nextafter (bound, 2.0 * bound + 1.0)})
        xs.push_back (x);
    }
    std::size_t wrong = 0;
    for (const double x : xs)
      wrong += search.find (x) != expected (x);
    EXPECT_EQ (wrong, 0u) << "faces " << a.size () << ", total " << total;
  }
}

TEST (CumulativeAreaSearch, NonFiniteDrawsStayInRange)
{
  // A mesh with a non-finite vertex sums to a non-finite area; its draws are NaN or infinite. The search still
  // answers a face (the loaders refuse such meshes; the samplers are given them through the API).
  const std::vector<double> finite = {1.0, 2.0, 3.0};
  const std::vector<double> infinite = {1.0, std::numeric_limits<double>::infinity (), std::numeric_limits<double>::infinity ()};
  for (const std::vector<double>* cumulative : {&finite, &infinite})
  {
    const CumulativeAreaSearch search (*cumulative);
    for (const double x : {std::numeric_limits<double>::quiet_NaN (), std::numeric_limits<double>::infinity (), -1.0})
      EXPECT_LT (search.find (x), cumulative->size ()) << x;
  }
}
