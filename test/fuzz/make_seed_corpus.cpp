/// Writes the seed corpus for fuzz_model_file: small valid .psm files in every mode (lossless,
/// quantised, with and without vertices, with and without colour / intensity, empty, a single patch). Usage: make_seed_corpus DIR

#include "../test_format_models.h"

#include <pcl_sparse/format/model_file.h>

#include <cstdio>
#include <fstream>
#include <string>

int
main (int argc, char** argv)
{
  if (argc != 2)
  {
    std::fprintf (stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 1;
  }
  const std::string directory = argv[1];
  int written = 0;
  for (std::size_t patches : {0, 1, 3, 8})
    for (double tolerance : {0.0, 1e-3, 1e-5})
      for (bool vertices : {false, true})
        for (int level : {0, 19})
          for (bool attributes : {false, true})
      {
        pcl_sparse::ModelWriteOptions options;
        options.zstd_level = level;
        options.tolerance = tolerance;
        options.include_vertices = vertices;
        auto model = pcl_sparse::test::makeSyntheticModel (patches, 7 + static_cast<unsigned> (patches), vertices, 8);
        if (attributes)
          pcl_sparse::test::addSyntheticAttributes (model, 3 + static_cast<unsigned> (patches));
        const auto bytes = pcl_sparse::encodeModel (model, options);
        const std::string path = directory + "/seed_" + std::to_string (written++) + ".psm";
        std::ofstream out (path, std::ios::binary);
        out.write (reinterpret_cast<const char*> (bytes.data ()), static_cast<std::streamsize> (bytes.size ()));
        if (!out)
        {
          std::fprintf (stderr, "%s: cannot write\n", path.c_str ());
          return 1;
        }
      }
  std::printf ("%d seed files in %s\n", written, directory.c_str ());
  return 0;
}
