#!/bin/bash
# Larger patches for smaller files: the default `-o` file at larger patch area bounds (`-rho`), against Draco at
# equal Chamfer distance (issue 13's bytes target), with what the larger patches cost in distance, holes and
# flipped normals. Hand-written notes stay below the "## Notes" line of the results.
#   bench/file_rho.sh [BUILD_DIR]   (default: build) -> bench/results/file_rho.md
#   Environment: PCL_SPARSE_FILE_RHO_SETS   option sets, ';'-separated (default: "-rho 0.001;-rho 0.002;-rho 0.004;
#                -rho 0.008"; the first is the one "x" compares with)
set -euo pipefail
# shellcheck source=bench/bench_setup.sh
source "$(dirname "$0")/bench_setup.sh"
file_tools
IFS=';' read -r -a sets <<< "${PCL_SPARSE_FILE_RHO_SETS:--rho 0.001;-rho 0.002;-rho 0.004;-rho 0.008}"
option_sets_report "$here/results/file_rho.md" "Larger patches for smaller files: the default file against Draco as rho grows" \
  "${sets[@]}"
