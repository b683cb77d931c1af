#!/bin/bash
# Flipped normals at several resampling seeds: every shared mesh, default options, 4 points per vertex,
# resampled with each seed in turn (bench_flips MESH -seed S; a cloud is one random draw, each patch's
# points keyed by the seed and its index). Prints a markdown table, one row per mesh, one column per seed.
#   bench/flips_seeds.sh [BUILD_DIR] [SEED ...]   (default: build; 42 1 2 3 4 5)
# FLIPS_OPTIONS="..." adds options of bench_flips to every run (e.g. "-clearance 0.045").
# The table of bench/results/flips.md, "Other resampling seeds", came from this (about 3 minutes on 2 CPUs).
set -euo pipefail
# shellcheck source=bench/bench_setup.sh
source "$(dirname "$0")/bench_setup.sh"
shift || true
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(42 1 2 3 4 5)
cmake --build "$build" --target bench_flips -j2 > /dev/null
printf '| mesh |'; printf ' %s |' "${seeds[@]}"; printf '\n|---|'; printf -- '---|%.0s' "${seeds[@]}"; printf '\n'
for mesh in $(shared_mesh_files); do
  printf '| %s |' "$(basename "${mesh%.*}")"
  for seed in "${seeds[@]}"; do
    # shellcheck disable=SC2086  # FLIPS_OPTIONS is a list of words
    flipped=$("$build/bench/bench_flips" "$mesh" -seed "$seed" ${FLIPS_OPTIONS:-} | head -1 | sed -n 's/.*flipped \([0-9]*\).*/\1/p')
    printf ' %s |' "$flipped"
  done
  printf '\n'
done
