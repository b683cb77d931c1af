#!/bin/bash
# Seconds to write the default compact file of a mesh against Draco's encoder on the same mesh, one mesh at a
# time (nothing else of ours running), so that the cost of our smaller-or-larger bytes is a ratio too.
#   bench/write_time.sh [BUILD_DIR] [MESH_FILE ...]   (default: build; all 25 shared meshes)
#     -> bench/results/write_time.md
# Ours: `pcl_sparse_encode MESH -o F.psm -q` (read, encode, the default file's measured tolerance, write) with
# every core and with -threads 1, best of 2 each. Draco: `draco_encoder -i MESH.obj -o F.drc -cl 7 -qp Q`
# (read, encode, write; single-threaded), best of 3, at the Q whose Chamfer in bench/results/meshes.tsv lies
# nearest our default file's (log scale): the Draco file bench/meshes.sh compares our bytes with. The mesh is
# converted to OBJ for Draco first (not timed); ours reads it as shared (OBJ, OFF or PLY).
set -euo pipefail
# shellcheck source=bench/bench_setup.sh
source "$(dirname "$0")/bench_setup.sh"
shift || true
file_tools
command -v draco_encoder > /dev/null || { echo "write_time.sh: draco_encoder missing (apt-get install draco)" >&2; exit 1; }
tsv="$here/results/meshes.tsv"
[ -f "$tsv" ] || { echo "write_time.sh: $tsv missing (run bench/meshes.sh first)" >&2; exit 1; }
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  mapfile -t meshes < <(shared_mesh_files)
fi
now () { date +%s.%N; }
# best_of N COMMAND...: the fewest seconds of N runs.
best_of () {
  local n=$1 best="" t0 t
  shift
  for _ in $(seq "$n"); do
    t0=$(now)
    "$@" > /dev/null
    t=$(echo "$(now) - $t0" | bc -l)
    if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" = 1 ]; then best=$t; fi
  done
  printf '%.3f' "$best"
}
out="$work/write_time.md"
{
  echo "# Writing the default file: seconds against Draco's encoder"
  echo
  generated_by
  echo "Ours: \`pcl_sparse_encode MESH -o F.psm -q\` (read, encode, measure the default file's tolerance, write), best of 2,"
  echo "with every core and with \`-threads 1\`. Draco: \`draco_encoder -cl 7 -qp Q\` on the mesh as OBJ, best of 3, at the Q"
  echo "whose Chamfer (bench/results/meshes.tsv) is nearest our default file's. \"x Draco\" = our seconds / Draco's;"
  echo "\"bytes x Draco\" is bench/meshes.sh's ratio at equal Chamfer, for the trade."
  echo
  echo "| mesh | vertices | ours s | ours 1 thread s | Draco qp | Draco s | x Draco | 1 thread x Draco | bytes x Draco |"
  echo "|---|---|---|---|---|---|---|---|---|"
} > "$out"
for mesh in "${meshes[@]}"; do
  [ -f "$mesh" ] || mesh=$shared/meshes/$mesh
  [ -f "$mesh" ] || mesh=$shared/extra-meshes/$(basename "$mesh")
  [ -f "$mesh" ] || { echo "write_time.sh: no mesh $mesh" >&2; exit 1; }
  name=$(basename "${mesh%.*}")
  vertices=$(vertex_count "$mesh")
  # The Draco file nearest our default file's Chamfer, and the bytes ratio, from bench/meshes.sh's table.
  read -r qp bytes_ratio < <(python3 - "$tsv" "$name" "$here" <<'PY'
import csv, math, sys
sys.path.insert(0, sys.argv[3])
from meshes_report import loglog
rows = [r for r in csv.DictReader(open(sys.argv[1]), delimiter='\t') if r['mesh'] == sys.argv[2]]
ours = [r for r in rows if r['config'] == 'default' and r['kind'] == 'file']
draco = [r for r in rows if r['config'] == 'draco']
if not ours or not draco:
    print('- -')
    sys.exit()
chamfer = float(ours[0]['chamfer'])
nearest = min(draco, key=lambda r: abs(math.log(float(r['chamfer']) / chamfer)))
bytes_, extrapolated = loglog([(float(r['chamfer']), float(r['bytes'])) for r in draco], chamfer, envelope=True)
print(nearest['rho_or_qp'], '%.2f%s' % (int(ours[0]['bytes']) / bytes_, '*' if extrapolated else '') if bytes_ else '-')
PY
)
  [ "$qp" = - ] && { echo "write_time.sh: $name not in $tsv; skipped" >&2; continue; }
  echo "== $name ($vertices vertices, Draco qp $qp) $(date -u +%T)" >&2
  ours=$(best_of 2 "$encode" "$mesh" -o "$work/$name.psm" -q)
  ours_one=$(best_of 2 "$encode" "$mesh" -o "$work/$name.psm" -q -threads 1)
  draco=$(best_of 3 draco_encoder -i "$work/mesh.obj" -o "$work/$name.drc" -cl 7 -qp "$qp")
  echo "| $name | $vertices | $ours | $ours_one | $qp | $draco | $(ratio "$ours" "$draco") | $(ratio "$ours_one" "$draco") | $bytes_ratio |" >> "$out"
done
write_keeping_notes "$out" "$here/results/write_time.md"
