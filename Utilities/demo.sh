#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# README command 1: set up, build, and run the main job on the embedded default DEM (the USGS
# Jacksboro fault DEM): describe it, then render it lit by a winter afternoon's sun and sky
# through each cell's aperture (baking the sky products on the way) and say where the picture is.
set -euo pipefail
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${APERTURE_BUILD_DIR:-$source_dir/build}
bash "$source_dir/Utilities/setup.sh"

echo "== aperture info (embedded default DEM)"
"$build_dir/bin/aperture" info
picture="$build_dir/aperture-default.png"
echo "== aperture render"
bash "$source_dir/Utilities/with-xvfb.sh" \
  "$build_dir/bin/aperture" render -o "$picture" --size 1600x1000 --exaggeration 2 \
  --at 2026-12-21T15:30 --tz America/New_York
echo "The picture is at $picture"
