#!/bin/bash
# Writing model files: seconds and bytes at zstd's levels (ModelWriteOptions::zstd_large_section and
# zstd_large_level). Lossless files (-tolerance 0) of two shared scans and three meshes, and the default
# quantised file of the largest scan; bench_file_write encodes each model in memory, best of 3.
#   bench/file_write_speed.sh [BUILD_DIR]   (default: build) -> bench/results/file_write_speed.md
set -euo pipefail
# shellcheck source=bench/bench_setup.sh
source "$(dirname "$0")/bench_setup.sh"
cmake --build "$build" --target pcl_sparse_encode bench_file_write -j2 > /dev/null
encode="$build/apps/pcl_sparse_encode"
writer="$build/bench/bench_file_write"
out="$here/results/file_write_speed.md"
inputs="clouds/office1.pcd clouds/table_scene_mug_stereo_textured.pcd meshes/spot.obj extra-meshes/cheese-cgal.off meshes/koala-loop1-200k.ply"
{
  echo "# Writing model files: zstd levels, seconds and bytes"
  echo
  generated_by
  echo "Each input encoded with the default options (\`pcl_sparse_encode IN -tolerance 0 -o F.psm\`, lossless, or the"
  echo "default quantised \`-o\`); \`bench_file_write F.psm [TOLERANCE]\` then writes that model in memory (encodeModel,"
  echo "one thread, best of 3) with: the default levels (19 up to 1 MiB a section, 9 above), level 19 everywhere"
  echo "(the default before), level 9 everywhere, and no compression. Every file decodes to the same model."
  echo
  echo "| input | file | default bytes | s | level 19 everywhere: bytes | s | level 9 everywhere: bytes | s | stored bytes |"
  echo "|---|---|---|---|---|---|---|---|---|"
} > "$out"
for input in $inputs; do
  path="$shared/$input"
  [ -f "$path" ] || { echo "missing $path" >&2; continue; }
  name=$(basename "$input")
  for mode in lossless quantised; do
    if [ "$mode" = lossless ]; then
      "$encode" "$path" -tolerance 0 -o "$work/m.psm" -q > /dev/null
      tolerance=0
    else
      [ "$input" = clouds/office1.pcd ] || continue
      tolerance=$("$encode" "$path" -o "$work/m.psm" -q --json | python3 "$here/json_fields.py" file_tolerance)
      "$encode" "$path" -tolerance 0 -o "$work/m.psm" -q > /dev/null
    fi
    "$writer" "$work/m.psm" "$tolerance" | awk -F'\t' -v input="$name" -v mode="$mode" '
      { bytes[NR] = $2; ratio[NR] = $3; seconds[NR] = $4 }
      END { printf "| %s | %s | %d | %.3f | %d (%.4fx) | %.3f | %d (%.4fx) | %.3f | %d |\n", input, mode, bytes[1], seconds[1],
            bytes[2], ratio[2], seconds[2], bytes[3], ratio[3], seconds[3], bytes[4] }' >> "$out"
  done
done
echo "written: $out"
