#!/usr/bin/env bash
# Installs the Debian (bookworm) packages pcl_sparse needs to build, test and run its demo (Open MPI: the
# tiled encoder across processes, mpirun in the tests; doxygen: the
# API reference and its warning check, test doxygen_clean).
# Idempotent: packages already present are skipped. Uses sudo only when not root.
set -euo pipefail

packages=(build-essential cmake pkg-config libpcl-dev libeigen3-dev libflann-dev libboost-dev
          libgtest-dev libzstd-dev libpng-dev doxygen libopenmpi-dev openmpi-bin "$@")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
