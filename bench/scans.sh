#!/usr/bin/env bash
# Scans against PCL's MLS / NormalEstimationOMP, Draco and OctreePointCloudCompression, in one run
# (issue 12 point 10) -> bench/results/scans.md and scans.tsv.
#
#   bench/scans.sh [BUILD_DIR]      (default: build; bench_scans and pcl_sparse_resample are built there)
#   Environment: PCL_SPARSE_SHARED_CLOUDS, PCL_SPARSE_SHARED_MESHES (default ../shared/{clouds,meshes})
#                SCANS_RD="file ..." scans to run the rate-distortion sweep on (default below)
# Installs draco (Debian) if draco_encoder is missing. About 10-15 minutes on 2 shared cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
cmake --build "$build" --target bench_scans pcl_sparse_resample -j2 > /dev/null
clouds=${PCL_SPARSE_SHARED_CLOUDS:-$root/../shared/clouds}
meshes=${PCL_SPARSE_SHARED_MESHES:-$root/../shared/meshes}
out=$root/bench/results
mkdir -p "$out"
if ! command -v draco_encoder > /dev/null; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends draco >&2
fi
bench=$build/bench/bench_scans
tool=$build/apps/pcl_sparse_resample
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
start=$(date +%s)

"$bench" simulate "$work" "$meshes/spot.obj"
# office1 with its NaNs dropped (as a filtered frame or a tile of one): the kNN path's depth-step removal.
"$bench" unorganize "$clouds/office1.pcd" "$work/office1_unorganized.pcd"
# name | file | bench options | tool options
scans=(
  "bun000.ply|$clouds/bun000.ply|-truth $meshes/stanford-bunny.obj -viewpoint-above 1|-viewpoint -0.03,0.1,1"
  "bun045.ply|$clouds/bun045.ply|-viewpoint-above 1|-viewpoint -0.03,0.1,1"
  "milk_color.pcd|$clouds/milk_color.pcd||"
  "table_scene_mug_stereo_textured.pcd|$clouds/table_scene_mug_stereo_textured.pcd||"
  "milk_cartoon_all_small_clorox.pcd|$clouds/milk_cartoon_all_small_clorox.pcd||"
  "office1.pcd|$clouds/office1.pcd||"
  "office1_unorganized.pcd|$work/office1_unorganized.pcd||"
  "room_scan1.pcd|$clouds/room_scan1.pcd||"
  "fast_gicp_251370668.pcd|$clouds/fast_gicp_251370668.pcd||"
  "small_gicp_source.ply|$clouds/small_gicp_source.ply|-viewpoint 0,0,0|-viewpoint 0,0,0"
  "samp11-utm.pcd|$clouds/samp11-utm.pcd|-viewpoint-above 1000|"
  "lamppost.pcd|$clouds/lamppost.pcd||"
  "sim_plane_organized.pcd|$work/sim_plane_organized.pcd|-truth $work/sim_plane_truth.obj|"
  "sim_sphere_organized.pcd|$work/sim_sphere_organized.pcd|-truth $work/sim_sphere_truth.obj|"
  "sim_plane.pcd|$work/sim_plane.pcd|-truth $work/sim_plane_truth.obj|"
  "sim_sphere.pcd|$work/sim_sphere.pcd|-truth $work/sim_sphere_truth.obj|"
  "sim_spot.pcd|$work/sim_spot.pcd|-truth $meshes/spot.obj|"
  "sim_lidar_street.pcd|$work/sim_lidar_street.pcd|-truth $work/sim_lidar_street_truth.obj|"
)
read -r -a rd_scans <<< "${SCANS_RD:-bun000.ply sim_plane_organized.pcd sim_sphere_organized.pcd sim_plane.pcd sim_sphere.pcd sim_spot.pcd sim_lidar_street.pcd office1.pcd table_scene_mug_stereo_textured.pcd milk_cartoon_all_small_clorox.pcd}"

tsv=$out/scans.tsv
: > "$tsv.tmp"
for entry in "${scans[@]}"; do
  IFS='|' read -r name file options tool_options <<< "$entry"
  # shellcheck disable=SC2086
  "$bench" compare "$file" $options >> "$tsv.tmp"
  # The command-line tool end to end (load, clean, encode, resample 1x, save): wall, CPU, peak RSS.
  # shellcheck disable=SC2086
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$tool" "$file" "$work/out.pcd" --json -q -threads 2 $tool_options > "$work/json"
  read -r wall user sys rss < "$work/time"
  printf 'TOOL\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$wall" "$(echo "$user + $sys" | bc -l)" "$rss" \
    "$(python3 "$root/bench/json_fields.py" --tab encode_seconds resample_seconds load_seconds < "$work/json")" \
    "$(cut -d' ' -f1 /proc/loadavg)" >> "$tsv.tmp"
  for rd in "${rd_scans[@]}"; do
    if [ "$rd" = "$name" ]; then
      # shellcheck disable=SC2086
      "$bench" rd "$file" $options >> "$tsv.tmp"
    fi
  done
  echo "$name done after $(( $(date +%s) - start )) s" >&2
done
mv "$tsv.tmp" "$tsv"
elapsed=$(( $(date +%s) - start ))
python3 "$root/bench/scans_report.py" "$tsv" "$out/scans.md" "$load_start" "$(cut -d' ' -f1-3 /proc/loadavg)" "$elapsed"
echo "wrote $tsv and $out/scans.md" >&2
