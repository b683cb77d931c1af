#!/usr/bin/env bash
# Builds pcl_sparse in Release and runs its test suite (ctest). Does all set-up on a fresh Debian machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install_deps.sh"
build="${BUILD_DIR:-$root/build}"
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)  # faster rebuilds, if present
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
cmake --build "$build" -j "$(nproc)"
cd "$build"
ctest --output-on-failure -j "$(nproc)" --timeout 600
# The ROS 1 node and nodelets (issue 15), in workspaces of their own; skipped, with the reason, where
# Debian's ROS packages are not available. PCL_SPARSE_SKIP_ROS=1 leaves them out.
[ "${PCL_SPARSE_SKIP_ROS:-0}" = 1 ] || "$root/scripts/test_ros.sh"
