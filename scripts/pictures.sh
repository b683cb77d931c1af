#!/usr/bin/env bash
# The README's pictures: one row per input (input, patches, error map of the reconstruction, resampled
# cloud), drawn headless by the tools' -png option and pcl_sparse_render into docs/images/.
#   scripts/pictures.sh [BUILD_DIR]   (default: build; needs ../shared/meshes and ../shared/clouds)
# Small images (288x216) keep each PNG well under 60 kB. Deterministic: a rerun rewrites the same bytes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
apps="$build/apps"
meshes=${PCL_SPARSE_SHARED_MESHES:-$root/../shared/meshes}
clouds=${PCL_SPARSE_SHARED_CLOUDS:-$root/../shared/clouds}
out="$root/docs/images"
size=288x216
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# row NAME INPUT VIEW: NAME_input.png NAME_patches.png NAME_error.png NAME_resampled.png
row() {
  local name=$1 input=$2 view=$3
  local common=(-size "$size" -view "$view" -q)
  "$apps/pcl_sparse_render" "$input" "$out/${name}_input.png" "${common[@]}"
  "$apps/pcl_sparse_patches" "$input" "$work/patches.ply" -png "$out/${name}_patches.png" "${common[@]}" > /dev/null
  "$apps/pcl_sparse_encode" "$input" -png "$out/${name}_error.png" "${common[@]}" > /dev/null
  "$apps/pcl_sparse_resample" "$input" "$work/cloud.pcd" -png "$out/${name}_resampled.png" "${common[@]}"
}

row fandisk "$meshes/fandisk.off" iso
row bun000 "$clouds/bun000.ply" front
ls -l "$out"
