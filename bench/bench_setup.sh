# Sourced by bench scripts after `set -euo pipefail`: the paths every one needs, a scratch folder and the
# JSON reader. Sets here (bench/), root (the checkout), build (the first argument, default build/), shared
# (PCL_SPARSE_SHARED, default ../shared beside the checkout) and work (a temporary folder removed on exit);
# json KEY ... prints fields of the JSON object on stdin (json_fields.py).
here=$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)
root=$(dirname "$here")
build=${1:-$root/build}
shared=${PCL_SPARSE_SHARED:-$root/../shared}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
json () { python3 "$here/json_fields.py" "$@"; }
# write_keeping_notes NEW OUT: moves the generated NEW to OUT, keeping OUT's hand-written text from its
# "## Notes" line on (if it has one) below the new table.
write_keeping_notes () {
  if [ -f "$2" ] && grep -q '^## Notes' "$2"; then
    { echo; sed -n '/^## Notes/,$p' "$2"; } >> "$1"
  fi
  mv "$1" "$2"
  echo "written: $2"
}
# file_tools: builds pcl_sparse_encode, pcl_sparse_resample, bench_format and bench_meshes in $build and sets
# encode, resample, format and quality to them (for the scripts that measure model files and their clouds).
file_tools () {
  cmake --build "$build" --target pcl_sparse_encode pcl_sparse_resample bench_format bench_meshes -j2 > /dev/null
  encode="$build/apps/pcl_sparse_encode"
  resample="$build/apps/pcl_sparse_resample"
  format="$build/bench/bench_format"
  quality="$build/bench/bench_meshes"
}
# file_cloud_quality MESH FILE VERTICES (after file_tools): resamples the model FILE at 4 x VERTICES points and prints
# its cloud's 99th-percentile hole (surface-to-cloud distance in spacings) and flipped normals against MESH.
file_cloud_quality () {
  "$resample" "$2" "$work/cloud.pcd" -n $((4 * $3)) -q
  "$quality" "$1" "$work/cloud.pcd" | json p99_spacings flipped
}
# shared_mesh_files: every mesh of ../shared/meshes and ../shared/extra-meshes, a path a line.
shared_mesh_files () {
  local f
  for f in "$shared"/meshes/*.{obj,off,ply} "$shared"/extra-meshes/*.{obj,off,ply}; do
    if [ -f "$f" ]; then echo "$f"; fi
  done
}
# ratio A B: A / B to three decimals.
ratio () { python3 -c "print('%.3f' % ($1 / $2))"; }
# vertex_count MESH: the mesh's vertex count (after file_tools: bench_format converts it to OBJ in $work).
vertex_count () {
  "$format" convert "$1" "$work/mesh.obj" > /dev/null
  grep -c '^v ' "$work/mesh.obj"
}
# draco_ratio MESH BYTES CHAMFER: BYTES over Draco's bytes at CHAMFER, interpolated over the Draco points of
# bench/results/meshes.tsv as bench/meshes.sh's report does (meshes_report.loglog; "*" extrapolated, - too far out).
draco_ratio () {
  python3 - "$here" "$@" <<'PY'
import csv, sys
sys.path.insert(0, sys.argv[1])
from meshes_report import loglog
rows = csv.DictReader(open(sys.argv[1] + '/results/meshes.tsv'), delimiter='\t')
points = [(float(r['chamfer']), float(r['bytes'])) for r in rows if r['mesh'] == sys.argv[2] and r['config'] == 'draco']
draco, extrapolated = loglog(points, float(sys.argv[4]), envelope=True)
print('%.2f%s' % (int(sys.argv[3]) / draco, '*' if extrapolated else '') if draco else '-')
PY
}
