#!/bin/bash
# Flipped normals of clouds resampled from the default model file, the way users run the tools:
#   pcl_sparse_encode MESH -o FILE.psm, then pcl_sparse_resample FILE.psm CLOUD.pcd -seed S (4 points per input
#   vertex), bench_meshes MESH CLOUD.pcd (flipped: normal over 120 degrees from the nearest face's; p99 surface-to-cloud
#   distance in spacings).
# Prints a markdown table, one row per mesh: file bytes, flipped points at each seed and their sum, the largest p99.
#   bench/file_flips.sh [BUILD_DIR] [SEED ...]   (default: build; 42 1 2 3 4 5)
# ENCODE_OPTIONS="..." adds options of pcl_sparse_encode (e.g. "--exact-footprints"); PCL_SPARSE_MESHES="a.obj b.off"
# limits the meshes (names in ../shared/meshes or ../shared/extra-meshes). About 10 minutes for the 25 on 2 CPUs.
set -euo pipefail
# shellcheck source=bench/bench_setup.sh
source "$(dirname "$0")/bench_setup.sh"
shift || true
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(42 1 2 3 4 5)
file_tools
meshes=()
if [ -n "${PCL_SPARSE_MESHES:-}" ]; then
  for name in $PCL_SPARSE_MESHES; do
    for dir in meshes extra-meshes; do [ -f "$shared/$dir/$name" ] && meshes+=("$shared/$dir/$name"); done
  done
else
  mapfile -t meshes < <(shared_mesh_files)
fi
printf '| mesh | file bytes |'; printf ' seed %s |' "${seeds[@]}"; printf ' sum | largest p99 (spacings) |\n|---|---|'
printf -- '---|%.0s' "${seeds[@]}"; printf -- '---|---|\n'
for mesh in "${meshes[@]}"; do
  name=$(basename "${mesh%.*}")
  # shellcheck disable=SC2086  # ENCODE_OPTIONS is a list of words
  "$encode" "$mesh" -o "$work/$name.psm" -q ${ENCODE_OPTIONS:-} > /dev/null
  printf '| %s | %s |' "$name" "$(stat -c %s "$work/$name.psm")"
  sum=0
  p99=0
  for seed in "${seeds[@]}"; do
    "$resample" "$work/$name.psm" "$work/$name.pcd" -seed "$seed" -q
    measured=$("$quality" "$mesh" "$work/$name.pcd" | json flipped p99_spacings)
    read -r flipped p <<< "$measured"
    p99=$(python3 -c "print(max($p99, $p))")
    sum=$((sum + flipped))
    printf ' %s |' "$flipped"
  done
  printf ' %s | %.2f |\n' "$sum" "$p99"
done
