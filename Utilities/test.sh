#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# README command 2 (and CI): set up, build with warnings as errors, run the whole test suite,
# then build the C core, the modules and their C/C++ tests a second time with
# AddressSanitizer + UndefinedBehaviorSanitizer and run those tests again (labels unit and
# render: the Rendering module's C++ test runs in its own Xvfb there too).
#   APERTURE_SKIP_SANITIZERS=1  skip the second build
set -euo pipefail
# The tests run as on a fresh machine: a host's PYTHONUNBUFFERED once hid a failure there (a
# closed stdout reported at exit, not in the command's handler), so take such settings away.
unset PYTHONUNBUFFERED PYTHONDONTWRITEBYTECODE
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${APERTURE_BUILD_DIR:-$source_dir/build}
APERTURE_CMAKE_ARGS="-DAPERTURE_WERROR=ON ${APERTURE_CMAKE_ARGS:-}" \
  APERTURE_BUILD_DIR="$build_dir" bash "$source_dir/Utilities/setup.sh"

echo "== Test suite"
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"

if [ "${APERTURE_SKIP_SANITIZERS:-0}" != 1 ]; then
  san_dir="$build_dir-sanitize"
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build in $san_dir"
  cmake -S "$source_dir" -B "$san_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DPython3_EXECUTABLE=/usr/bin/python3 -DAPERTURE_WERROR=ON \
    -DAPERTURE_SANITIZE=address,undefined,float-cast-overflow
  cmake --build "$san_dir" -j "$(nproc)"
  ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1" \
  LSAN_OPTIONS="suppressions=$source_dir/Utilities/lsan.supp:print_suppressions=0" \
  UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    ctest --test-dir "$san_dir" --output-on-failure -j "$(nproc)" -L "unit|render"
fi
echo "== All tests passed"
