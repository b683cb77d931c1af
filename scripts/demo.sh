#!/usr/bin/env bash
# The demo: installs what is needed (Debian bookworm), builds pcl_sparse in Release, fetches the Fandisk
# mesh (CC0, CGAL's data from Debian's libcgal-demo package) into a cache outside the repository, and runs
# the tools on it: report, encode to a sparse model, resample the model into a point cloud. Idempotent: installed packages, the build and the cached mesh are reused.
# Environment: BUILD_DIR (default <repo>/build), PCL_SPARSE_CACHE (default ~/.cache/pcl_sparse).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${BUILD_DIR:-$root/build}"
cache="${PCL_SPARSE_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/pcl_sparse}"
sudo=""
apt_download=(apt-get download -q)
if [ "$(id -u)" -eq 0 ]; then
  apt_download+=(-o APT::Sandbox::User=root)  # root: skip the _apt sandbox, which cannot enter mktemp's dir
else
  sudo="sudo"
fi

"$root/scripts/install_deps.sh"
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)  # faster rebuilds, if present
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
cmake --build "$build" -j "$(nproc)"

# Fandisk: usr/share/doc/libcgal-dev/data.tar.gz inside the .deb holds data/meshes/fandisk.off.
mesh="$cache/fandisk.off"
if [ ! -s "$mesh" ]; then
  mkdir -p "$cache"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  # apt-get download needs the package lists; a fresh machine may have none yet.
  if ! (cd "$work" && "${apt_download[@]}" libcgal-demo); then
    $sudo apt-get update -q
    (cd "$work" && "${apt_download[@]}" libcgal-demo)
  fi
  dpkg-deb --fsys-tarfile "$work"/libcgal-demo_*.deb \
    | tar -xO ./usr/share/doc/libcgal-dev/data.tar.gz \
    | tar -xzO data/meshes/fandisk.off > "$work/fandisk.off"
  mv "$work/fandisk.off" "$mesh"
fi
echo "== $mesh"

# The main job. Step 1: what is in the mesh.
"$build/apps/pcl_sparse_info" "$mesh"

# Step 2: code it as a sparse model (.psm) with the paper's figures (N_V, M, rho, nnz, RMSE, CR), and show
# what the model file holds.
echo "== encode"
# The default file is quantised at a tolerance derived from the model's own error (it adds at most 10 % to
# the distance from the mesh); -tolerance T (of the diagonal) trades accuracy for bytes.
"$build/apps/pcl_sparse_encode" "$mesh" -o "$cache/fandisk.psm" -q
"$build/apps/pcl_sparse_info" "$cache/fandisk.psm"

# Step 3: resample the model into a point cloud with normals and curvature, at any density.
echo "== resample"
"$build/apps/pcl_sparse_resample" "$cache/fandisk.psm" "$cache/fandisk-100k.ply" -n 100000 -q
echo "wrote $cache/fandisk-100k.ply (100000 points with normals; view it in MeshLab or CloudCompare)"
