// How long writing a model file takes, and how many bytes it makes, at zstd's levels: the default (level 19
// up to ModelWriteOptions::zstd_large_section, zstd_large_level above) against level 19 everywhere, level 9
// everywhere and nothing compressed. The model is the file's own (loaded once); each row encodes it three
// times in memory (encodeModel) and keeps the fastest; every row's file decodes to the same model.
//   bench_file_write MODEL.psm [TOLERANCE]   (TOLERANCE: 0 = lossless, the default; as -tolerance otherwise)
// Prints one tab-separated line per configuration: name, bytes, bytes / default's, seconds.

#include "bench_main.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  struct Configuration
  {
    const char* name;
    ModelWriteOptions options;
  };

  struct Measurement
  {
    std::size_t bytes = 0;
    double seconds = 0.0;
  };

  /// The model \a bytes hold, encoded again uncompressed (zstd level 0) with \a options' other fields.
  std::vector<std::uint8_t>
  storedBytesOf (const std::vector<std::uint8_t>& bytes, const ModelWriteOptions& options)
  {
    ModelWriteOptions stored = options;
    stored.zstd_level = 0;
    return encodeModel (decodeModel (bytes.data (), bytes.size ()), stored);
  }

  Measurement
  measure (const SparseSurfaceModel& model, const ModelWriteOptions& options, const std::vector<std::uint8_t>& raw)
  {
    Measurement m;
    m.seconds = 1e300;
    for (int run = 0; run < 3; ++run)
    {
      const auto start = std::chrono::steady_clock::now ();
      const std::vector<std::uint8_t> bytes = encodeModel (model, options);
      m.seconds = std::min (m.seconds, std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ());
      m.bytes = bytes.size ();
      // Whatever the levels, the file holds the same model.
      if (run == 0 && storedBytesOf (bytes, options) != raw)
        throw Error ("the file written with these levels decodes to another model");
    }
    return m;
  }
} // namespace

int
run (int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf (stderr, "usage: %s MODEL.psm [TOLERANCE]\n", argv[0]);
    return 2;
  }
  const SparseSurfaceModel model = loadModel (argv[1]);
  ModelWriteOptions defaults;
  defaults.tolerance = argc > 2 ? std::stod (argv[2]) : 0.0;
  ModelWriteOptions stored = defaults, level19 = defaults, level9 = defaults;
  stored.zstd_level = 0;
  level19.zstd_large_level = 19;
  level9.zstd_level = 9;
  // The reference: the model as the file holds it (quantised or not), re-encoded uncompressed.
  const std::vector<std::uint8_t> raw = storedBytesOf (encodeModel (model, stored), stored);
  const Configuration configurations[] = {{"default", defaults}, {"level 19 everywhere", level19},
                                          {"level 9 everywhere", level9}, {"stored", stored}};
  std::vector<Measurement> measured;
  for (const Configuration& c : configurations)
    measured.push_back (measure (model, c.options, raw));
  for (std::size_t i = 0; i < measured.size (); ++i)
    std::printf ("%s\t%zu\t%.4f\t%.3f\n", configurations[i].name, measured[i].bytes,
                 static_cast<double> (measured[i].bytes) / measured[0].bytes, measured[i].seconds);
  return 0;
}

int
main (int argc, char** argv)
{
  return runReportingErrors (argc, argv, run);
}
