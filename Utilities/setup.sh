#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Set up and build Aperture on Debian 12: install the Debian packages listed in
# Utilities/debian-packages.txt (as root, or through sudo), configure and build.
# Safe to run again: installed packages are skipped and the build is incremental.
#   APERTURE_BUILD_DIR   build folder (default: <source>/build)
#   APERTURE_CMAKE_ARGS  extra CMake arguments
set -euo pipefail
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${APERTURE_BUILD_DIR:-$source_dir/build}

mapfile -t packages < <(grep -v '^\s*#' "$source_dir/Utilities/debian-packages.txt" |
                          grep -v '^\s*$')
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "== Installing Debian packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

echo "== Configuring in $build_dir"
# shellcheck disable=SC2086
cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release \
  -DPython3_EXECUTABLE=/usr/bin/python3 ${APERTURE_CMAKE_ARGS:-}
echo "== Building"
cmake --build "$build_dir" -j "$(nproc)"
