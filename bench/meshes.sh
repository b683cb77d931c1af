#!/usr/bin/env bash
# One table over every shared mesh (issue 13 point 5), default options and -preset paper, in one run.
#
#   bench/meshes.sh [BUILD_DIR] [MESH_FILE ...]
#     BUILD_DIR   a Release build with pcl_sparse_encode, pcl_sparse_resample, bench_format, bench_meshes
#                 (default: build)
#     MESH_FILE   names in ../shared/meshes or ../shared/extra-meshes (default: all 25 meshes of both folders)
#   Environment:
#     PCL_SPARSE_RHOS           rho sweep for RMSE at the authors' CR (default: 0.0002 0.0005 0.001 0.002 0.005)
#     PCL_SPARSE_SWEEP_MAX_V    meshes with more vertices get no sweep beyond rho 0.001 (default: 1000000, i.e. none skipped)
#     PCL_SPARSE_JOBS           meshes measured at a time (default: 2)
#     PCL_SPARSE_DRACO_QP       Draco quantisation bits (default: 6 7 8 10 12 14 16)
#
# Per mesh and configuration (default options; -preset paper; the rho sweep only for -preset paper -cone 72 and
# -preset paper -min-samples 0):
#   pcl_sparse_encode MESH [-preset paper] -rho R --json     M, CR, RMSE/diag, mean error/diag for every R of the sweep;
#     at rho 0.001 also -o FILE (the default file: quantised at the derived tolerance) -> bytes,
#     bench_format model MESH FILE -> Chamfer / diag (symmetric mean point-to-surface distance, 200k points a side)
#   pcl_sparse_resample MESH CLOUD.pcd -n 4V [-preset paper]  (the encoder's default rho)
#     bench_meshes MESH CLOUD.pcd -> p99 surface-to-cloud distance in spacings sqrt(area / points), flipped normals
# Per mesh: draco_encoder -cl 7 -qp Q on the mesh (positions and faces), bench_format mesh -> bytes, Chamfer.
# Writes bench/results/meshes.tsv (every measurement) and meshes.md (bench/meshes_report.py).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
shift || true
meshes=("$@")
shared=$root/../shared
if [ ${#meshes[@]} -eq 0 ]; then
  meshes=(anchor-dense.off armadillo-43k.obj blade.off blub.obj bunny-hr-closed.obj bunny-npm-1k.obj
          cheese-cgal.off couplingdown.off fandisk.off fandisk-large.off fertility.off horse.ply igea.ply
          kitten-14k.obj kitten-53k.obj koala.obj koala-loop1-200k.ply nefertiti-35k.obj rocker-arm.obj
          skull.obj spot.obj stanford-bunny.obj sword.obj turbine.off wingnut.obj)
fi
read -r -a rhos <<< "${PCL_SPARSE_RHOS:-0.0002 0.0005 0.001 0.002 0.005}"
read -r -a qps <<< "${PCL_SPARSE_DRACO_QP:-6 7 8 10 12 14 16}"
sweep_max=${PCL_SPARSE_SWEEP_MAX_V:-1000000}
out=$root/bench/results
mkdir -p "$out"
if ! command -v draco_encoder > /dev/null; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends draco >&2
fi

cmake --build "$build" --target pcl_sparse_encode pcl_sparse_resample bench_format bench_meshes -j2 > /dev/null
encode=$build/apps/pcl_sparse_encode
resample=$build/apps/pcl_sparse_resample
format=$build/bench/bench_format
quality=$build/bench/bench_meshes
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
json () { python3 "$root/bench/json_fields.py" "$@"; }
now () { date +%s.%N; }

tsv=$out/meshes.tsv
start=$(now)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
printf 'mesh\tvertices\tconfig\tkind\trho_or_qp\tpatches\tcr\trmse_over_diag\tmean_error_over_diag\tbytes\tchamfer\tp99_spacings\tmax_spacings\tcompleteness3\tflipped\tflipped_fraction\tseconds\n' > "$tsv.tmp"
row () { local IFS=$'\t'; echo "$*" >> "$work/rows_$base.tsv"; }
one_mesh () {
  local name=$1 mesh base vertices qp chamfer config preset rho t0 m cr rmse mean p99 pmax complete flipped fraction
  mesh=$shared/meshes/$name
  [ -f "$mesh" ] || mesh=$shared/extra-meshes/$name
  base=${name%.*}
  "$format" convert "$mesh" "$work/$base.obj"
  vertices=$(grep -c '^v ' "$work/$base.obj")
  rm -f "$work/rows_$base.tsv"
  echo "== $base ($vertices vertices) $(date -u +%T)" >&2

  for qp in "${qps[@]}"; do
    t0=$(now)
    draco_encoder -i "$work/$base.obj" -o "$work/$base.drc" -cl 7 -qp "$qp" > /dev/null
    draco_decoder -i "$work/$base.drc" -o "$work/${base}_draco.ply" > /dev/null
    chamfer=$("$format" mesh "$mesh" "$work/${base}_draco.ply" | json chamfer)
    row "$base" "$vertices" draco file "$qp" - - - - "$(stat -c %s "$work/$base.drc")" "$chamfer" - - - - - \
      "$(echo "$(now) - $t0" | bc -l)"
  done

  for config in default paper paper-cone72 paper-nosamples; do
    case $config in
      default) preset=() ;;
      paper) preset=(-preset paper) ;;
      paper-cone72) preset=(-preset paper -cone 72) ;;  # the paper with the authors' normal cone
      paper-nosamples) preset=(-preset paper -min-samples 0) ;;  # the paper coding the vertices only
    esac
    sweep_only=false; case $config in paper-*) sweep_only=true ;; esac
    for rho in "${rhos[@]}"; do
      [ "$vertices" -gt "$sweep_max" ] && [ "$rho" != 0.001 ] && continue
      t0=$(now)
      if [ "$rho" = 0.001 ] && ! $sweep_only; then
        read -r m cr rmse mean < <("$encode" "$mesh" "${preset[@]}" -rho "$rho" -o "$work/$base.psm" --json -q |
                                  json patches cr rmse_over_diag mean_error_over_diag)
        chamfer=$("$format" model "$mesh" "$work/$base.psm" | json chamfer)
        row "$base" "$vertices" $config file "$rho" "$m" "$cr" "$rmse" "$mean" "$(stat -c %s "$work/$base.psm")" "$chamfer" \
          - - - - - "$(echo "$(now) - $t0" | bc -l)"
      else
        read -r m cr rmse mean < <("$encode" "$mesh" "${preset[@]}" -rho "$rho" --json -q |
                                  json patches cr rmse_over_diag mean_error_over_diag)
        row "$base" "$vertices" $config encode "$rho" "$m" "$cr" "$rmse" "$mean" - - - - - - - "$(echo "$(now) - $t0" | bc -l)"
      fi
      echo "$config rho $rho: M $m CR $cr RMSE/diag $rmse" >&2
    done
    $sweep_only && continue
    t0=$(now)
    "$resample" "$mesh" "$work/$base.pcd" "${preset[@]}" -n $((4 * vertices)) -q
    read -r p99 pmax complete flipped fraction < <("$quality" "$mesh" "$work/$base.pcd" |
      json p99_spacings max_spacings completeness3 flipped flipped_fraction)
    row "$base" "$vertices" $config cloud - - - - - - - "$p99" "$pmax" "$complete" "$flipped" "$fraction" \
      "$(echo "$(now) - $t0" | bc -l)"
    echo "$config cloud: p99 $p99 spacings, flipped $flipped" >&2
  done
  echo "== $base done $(date -u +%T)" >&2
}
# Two meshes at a time (most steps are single-threaded); rows are joined in mesh order, so the file does not
# depend on the schedule.
export -f one_mesh row json now
export root shared work format encode resample quality sweep_max
export rhos_list="${rhos[*]}" qps_list="${qps[*]}"
printf '%s\n' "${meshes[@]}" | xargs -P "${PCL_SPARSE_JOBS:-2}" -I{} bash -c 'set -euo pipefail; read -r -a rhos <<< "$rhos_list"; read -r -a qps <<< "$qps_list"; one_mesh {}' || true
for name in "${meshes[@]}"; do
  base=${name%.*}
  if [ -f "$work/rows_$base.tsv" ] && [ "$(grep -c cloud "$work/rows_$base.tsv")" = 2 ]; then
    cat "$work/rows_$base.tsv" >> "$tsv.tmp"
  else
    echo "meshes.sh: $base did not finish; left out" >&2
  fi
done
mv "$tsv.tmp" "$tsv"
cat > "$out/.meshes_run" << EOF
date=$(date -u +%Y-%m-%dT%H:%MZ)
seconds=$(printf '%.0f' "$(echo "$(now) - $start" | bc -l)")
load_before=$load_before
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
cpus=$(nproc)
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')
commit=$(git -C "$root" rev-parse --short HEAD)
sweep_max=$sweep_max
rhos=${rhos[*]}
qps=${qps[*]}
EOF
python3 "$root/bench/meshes_report.py" "$tsv" "$out/.meshes_run" > "$out/meshes.md"
rm -f "$out/.meshes_run"
echo "wrote $tsv and $out/meshes.md" >&2
