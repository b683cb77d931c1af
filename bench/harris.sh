#!/bin/sh
# Harris 3D benchmark: builds bench_harris in BUILD_DIR (default build-bench) and writes
# bench/results/harris.md. Usage: bench/harris.sh [BUILD_DIR]
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-bench}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target bench_harris -j2 >/dev/null
mkdir -p "$root/bench/results"
OMP_NUM_THREADS=2 "$build/bench/bench_harris" "$root/../shared/meshes/koala-loop1-200k.ply" \
  "$root/../shared/meshes/fandisk.off" 3 > "$root/bench/results/harris.md.tmp"
mv "$root/bench/results/harris.md.tmp" "$root/bench/results/harris.md"
cat "$root/bench/results/harris.md"
