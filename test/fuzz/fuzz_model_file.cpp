/// libFuzzer target for the .psm loader: any input must either decode or throw pcl_sparse::Error;
/// sanitizers (ASan, UBSan) turn anything else (overflow, out-of-bounds, leaks) into a finding.
/// A decoded model must also re-encode losslessly to a file that decodes again (round-trip oracle).
/// Built by bench/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined).

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>

#include <cstdint>
#include <cstdlib>

extern "C" int
LLVMFuzzerTestOneInput (const std::uint8_t* data, std::size_t size)
{
  pcl_sparse::SparseSurfaceModel model;
  try
  {
    model = pcl_sparse::decodeModel (data, size, "fuzz");
    pcl_sparse::inspectModel (data, size, "fuzz");
  }
  catch (const pcl_sparse::Error&)
  {
    return 0;
  }
  // Whatever the loader accepted is a valid model: it must survive a lossless round trip.
  pcl_sparse::ModelWriteOptions options;
  options.include_vertices = true;
  options.zstd_level = 1;
  const std::vector<std::uint8_t> again = pcl_sparse::encodeModel (model, options);
  const pcl_sparse::SparseSurfaceModel decoded = pcl_sparse::decodeModel (again.data (), again.size (), "fuzz again");
  if (decoded.numPatches () != model.numPatches () || decoded.numNonZeros () != model.numNonZeros ())
    std::abort ();
  return 0;
}
