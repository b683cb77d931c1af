/// Writes the seed corpus for fuzz_model_file: small valid .psm files in every mode (lossless, quantised in
/// both layouts (range-coded, varints), with and without vertices, with and without colour / intensity, empty,
/// a single patch), and the same models as tiled files (version 3, three tiles when there are patches). Usage: make_seed_corpus DIR

#include "../test_format_models.h"

#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/tiled_model_file.h>

#include <algorithm>
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
            for (bool range_coding : {true, false})
      {
        if (!range_coding && tolerance == 0.0)
          continue;  // lossless files have no range-coded fields
        pcl_sparse::ModelWriteOptions options;
        options.range_coding = range_coding;
        options.zstd_level = level;
        options.tolerance = tolerance;
        options.include_vertices = vertices;
        auto model = pcl_sparse::test::makeSyntheticModel (patches, 7 + static_cast<unsigned> (patches), vertices, 8);
        if (attributes)
          pcl_sparse::test::addSyntheticAttributes (model, 3 + static_cast<unsigned> (patches));
        pcl_sparse::TiledModel tiled;
        tiled.model = model;
        tiled.grid.counts = Eigen::Vector3i (3, 1, 1);
        tiled.total_patches = patches;
        for (std::size_t t = 0, first = 0; t < 3 && first < patches; ++t)
        {
          const std::size_t count = t < 2 ? std::max<std::size_t> (1, patches / 3) : patches - first;
          tiled.tiles.push_back ({t, first, count, {}});
          first += count;
        }
        for (const auto& bytes : {pcl_sparse::encodeModel (model, options), pcl_sparse::encodeTiledModel (tiled, options, 1)})
        {
          const std::string path = directory + "/seed_" + std::to_string (written++) + ".psm";
          std::ofstream out (path, std::ios::binary);
          out.write (reinterpret_cast<const char*> (bytes.data ()), static_cast<std::streamsize> (bytes.size ()));
          if (!out)
          {
            std::fprintf (stderr, "%s: cannot write\n", path.c_str ());
            return 1;
          }
        }
      }
  std::printf ("%d seed files in %s\n", written, directory.c_str ());
  return 0;
}
