#!/usr/bin/env bash
# Issue 13 point 1 (every triangle covered, no hole, no flipped normal), per mesh with default options:
#
#   bench/face_completion.sh [BUILD_DIR] [MESH_FILE ...]
#     BUILD_DIR   a Release build with pcl_sparse_encode, pcl_sparse_resample and bench_meshes (default: build)
#     MESH_FILE   names in ../shared/meshes or ../shared/extra-meshes (default: the ten of
#                 bench/results/face_completion.md)
#
# Per mesh, as bench/meshes.sh measures its default rows:
#   pcl_sparse_encode MESH --json                    -> M, CR, RMSE/diag, share of the area in no patch
#   pcl_sparse_resample MESH CLOUD.pcd -n 4V         then bench_meshes MESH CLOUD.pcd
#                                                    (POINTS=N in the environment: -n N instead of 4V)
#                                                    -> p99 surface-to-cloud distance in spacings, max, <= 3,
#                                                       flipped normals, mean distance / diag, mean normal angle
# Prints one tab-separated line per mesh. One mesh at a time (single-threaded steps; the machine is shared).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
cmake --build "$build" --target pcl_sparse_encode pcl_sparse_resample bench_meshes -j2 > /dev/null
shift || true
meshes=("$@")
[ ${#meshes[@]} -gt 0 ] || meshes=(couplingdown.off cheese-cgal.off turbine.off blade.off wingnut.obj rocker-arm.obj
                                  sword.obj kitten-53k.obj spot.obj armadillo-43k.obj)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
field () { python3 "$root/bench/json_fields.py" "$@"; }
printf 'mesh\tV\tM\tCR\tRMSE/diag\tarea in no patch\tp99\tmax\t<=3\tflipped\tmean dist/diag\tmean angle\n'
for name in "${meshes[@]}"; do
  mesh=$root/../shared/meshes/$name
  [ -f "$mesh" ] || mesh=$root/../shared/extra-meshes/$name
  read -r v m cr rmse area < <("$build/apps/pcl_sparse_encode" "$mesh" --json -q |
    field vertices patches cr rmse_over_diag area_in_no_patch)
  "$build/apps/pcl_sparse_resample" "$mesh" "$work/cloud.pcd" -n "${POINTS:-$((4 * v))}" -q
  read -r p99 pmax within flipped dist angle < <("$build/bench/bench_meshes" "$mesh" "$work/cloud.pcd" |
    field p99_spacings max_spacings completeness3 flipped mean_distance_over_diag mean_normal_angle)
  printf '%s\t%s\t%s\t%.3f\t%.3g\t%.3g %%\t%.2f\t%.1f\t%.4f\t%s\t%.3g\t%.2f\n' "${name%.*}" "$v" "$m" "$cr" "$rmse" \
    "$(python3 -c "print(100 * $area)")" "$p99" "$pmax" \
    "$within" "$flipped" "$dist" "$angle"
done
