#!/bin/sh
# Mesh load time, ours against PCL's loaders, on the shared real meshes; writes bench/results/load.md.
#   BUILD_DIR  build directory (default: build)     MESHES  mesh folder (default: ../shared/meshes)
#   REPS       repetitions per loader (default: 7)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
meshes=${MESHES:-$root/../shared/meshes}
reps=${REPS:-7}
for mesh in koala-loop1-200k.ply sword.obj; do
  if [ ! -f "$meshes/$mesh" ]; then
    echo "load.sh: $meshes/$mesh not found (set MESHES)" >&2
    exit 1
  fi
done
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target bench_load -j2 >/dev/null
mkdir -p "$root/bench/results"
"$build/bench/bench_load" --reps "$reps" --output "$root/bench/results/load.md" \
  "$meshes/koala-loop1-200k.ply" "$meshes/sword.obj"
