#!/bin/bash
# Leaving out the atoms that buy least (SparseSurfaceEncoderOptions::atom_loss_allowance, `-atom-loss A`) against
# the default and against fewer atoms per patch (-L): for every shared mesh and option set, the `-o` file's atoms,
# bytes and Chamfer distance, its bytes against Draco's at that distance (Draco's points from
# bench/results/meshes.tsv, as bench/meshes.sh interpolates them), and the holes and flipped normals of the
# file's resampled cloud. Hand-written notes stay below the "## Notes" line of the results.
#   bench/atom_loss.sh [BUILD_DIR]   (default: build) -> bench/results/atom_loss.md
#   Environment: PCL_SPARSE_ATOM_LOSS_SETS   option sets, ';'-separated (default: "-atom-loss 0;-atom-loss 0.2;-L 10";
#                the first is the one "x" compares with)
set -euo pipefail
# shellcheck source=bench/bench_setup.sh
source "$(dirname "$0")/bench_setup.sh"
file_tools
IFS=';' read -r -a sets <<< "${PCL_SPARSE_ATOM_LOSS_SETS:--atom-loss 0;-atom-loss 0.2;-L 10}"
option_sets_report "$here/results/atom_loss.md" \
  "Atoms left out for their error: file bytes, Chamfer distance, bytes against Draco, holes, flipped normals" "${sets[@]}"
