#!/bin/sh
# Cloud surface benchmark: builds bench_cloud_surface in BUILD_DIR (default build-bench) and writes
# bench/results/cloud_surface.md. Usage: bench/cloud_surface.sh [BUILD_DIR]
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-bench}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target bench_cloud_surface -j2 >/dev/null
mkdir -p "$root/bench/results"
OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive "$build/bench/bench_cloud_surface" "$root/../shared/clouds" "$root/../shared/meshes" 5 \
  > "$root/bench/results/cloud_surface.md.tmp"
mv "$root/bench/results/cloud_surface.md.tmp" "$root/bench/results/cloud_surface.md"
cat "$root/bench/results/cloud_surface.md"
