#!/usr/bin/env bash
# Builds the libFuzzer target for the .psm loader (clang, ASan + UBSan) and runs it.
# Usage: bench/fuzz.sh SECONDS [BUILD_DIR]   (default build dir: build-fuzz)
# The target is built with FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION, which skips the CRC checks so that
# mutations reach the decoder (the checks themselves are covered by test_format's bit-flip test).
# Needs clang and libclang-rt-14-dev (Debian bookworm). Findings (crash-*, leak-*, timeout-*) land in
# BUILD_DIR/findings; the exit code is libFuzzer's (0 = no finding).
set -euo pipefail
seconds=${1:?usage: bench/fuzz.sh SECONDS [BUILD_DIR]}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${2:-$root/build-fuzz}
mkdir -p "$build/corpus" "$build/findings"
cxx=${CXX_FUZZ:-clang++}
common=(-std=c++17 -g -I"$root/include" -I/usr/include/eigen3)
sources=("$root"/src/format/*.cpp "$root/src/coding/cosine_dictionary.cpp" "$root/src/model/sparse_surface_model.cpp" "$root/src/model/vertex_attributes.cpp"
         "$root/src/mesh/bounding_box.cpp"
         "$root/src/common/atomic_write.cpp" "$root/src/tiles/tile_grid.cpp" "$root/src/tiles/tiled_model.cpp")

echo "building $build/fuzz_model_file" >&2
"$cxx" "${common[@]}" -O1 -DFUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  "${sources[@]}" "$root/test/fuzz/fuzz_model_file.cpp" -lzstd -o "$build/fuzz_model_file"
"$cxx" "${common[@]}" -O1 "${sources[@]}" "$root/test/fuzz/make_seed_corpus.cpp" -lzstd -o "$build/make_seed_corpus"
"$build/make_seed_corpus" "$build/corpus" >&2

cd "$build/findings"
exec "$build/fuzz_model_file" -max_total_time="$seconds" -max_len=8192 -rss_limit_mb=2048 -timeout=10 \
  -print_final_stats=1 "$build/corpus"
