#!/usr/bin/env bash
# Builds a libFuzzer target (clang, ASan + UBSan) and runs it.
# Usage: bench/fuzz.sh SECONDS [BUILD_DIR] [TARGET]   (default build dir: build-fuzz)
#   TARGET model (default): the .psm loader, built with FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION, which skips
#          the CRC checks so that mutations reach the decoder (the checks themselves are covered by
#          test_format's bit-flip test); seeds from make_seed_corpus.cpp
#   TARGET inputs: the mesh and scan readers (.obj .off .ply .stl .pcd .xyz; meshes also streamed), linked with Debian's PCL (the
#          PCD data goes through pcl::PCDReader once our header check passed); seeds from make_input_corpus.py
# Needs clang and libclang-rt-14-dev (Debian bookworm); the loader's kd-tree (FLANN's headers) needs liblz4.
# Findings (crash-*, leak-*, timeout-*) land in BUILD_DIR/findings, the corpus in BUILD_DIR/corpus-TARGET; the exit
# code is libFuzzer's (0 = no finding).
set -euo pipefail
seconds=${1:?usage: bench/fuzz.sh SECONDS [BUILD_DIR] [model|inputs]}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${2:-$root/build-fuzz}
target=${3:-model}
case $target in model|inputs) ;; *) echo "bench/fuzz.sh: TARGET must be model or inputs, got $target" >&2; exit 2 ;; esac
corpus=$build/corpus-$target
mkdir -p "$corpus" "$build/findings"
cxx=${CXX_FUZZ:-clang++}
common=(-std=c++17 -g -fopenmp -I"$root/include" -I/usr/include/eigen3 -I/usr/include/pcl-1.13)
# The loader's sources: src/format and the list test_format_sanitized builds from too.
sources=("$root"/src/format/*.cpp)
while read -r path; do
  sources+=("$root/$path")
done < <(grep -v '^#' "$root/test/sanitized/loader_sources.txt")

if [ "$target" = inputs ]; then
  echo "building $build/fuzz_input_files" >&2
  readers=()
  for name in mesh_io mesh_stream obj_reader off_reader ply_reader stl_reader pcd_reader xyz_reader scan_io scan_points \
              scan_cleaning scan_cloud polygon_mesh_conversion; do
    readers+=("$root/src/io/$name.cpp")
  done
  "$cxx" "${common[@]}" -I/usr/include/pcl-1.13 -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    "${readers[@]}" "$root/src/mesh/bounding_box.cpp" "$root/src/mesh/polygon_faces.cpp" "$root/src/mesh/vertex_welding.cpp" \
    "$root/test/fuzz/fuzz_input_files.cpp" -lpcl_io -lpcl_common -o "$build/fuzz_input_files"
  python3 "$root/test/fuzz/make_input_corpus.py" "$corpus"
  fuzzer=$build/fuzz_input_files
else
  echo "building $build/fuzz_model_file" >&2
  "$cxx" "${common[@]}" -O1 -DFUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    "${sources[@]}" "$root/test/fuzz/fuzz_model_file.cpp" -lzstd -lpcl_kdtree -lpcl_common -llz4 -o "$build/fuzz_model_file"
  "$cxx" "${common[@]}" -O1 "${sources[@]}" "$root/test/fuzz/make_seed_corpus.cpp" -lzstd -lpcl_kdtree -lpcl_common -llz4 -o "$build/make_seed_corpus"
  "$build/make_seed_corpus" "$corpus" >&2
  fuzzer=$build/fuzz_model_file
fi

cd "$build/findings"
exec "$fuzzer" -max_total_time="$seconds" -max_len=8192 -rss_limit_mb=2048 -timeout=10 \
  -print_final_stats=1 "$corpus"
