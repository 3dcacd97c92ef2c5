#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Run a command with its own Xvfb display (Mesa's software OpenGL, llvmpipe), then stop it.
#   Utilities/with-xvfb.sh COMMAND [ARGS...]
# Xvfb chooses a free display itself and reports it through -displayfd once it is ready, which
# avoids the start-up race of `xvfb-run -a` when several servers start and stop together;
# -noreset keeps the server from resetting (and refusing connections) whenever its last client
# closes, which happens between the windows of one test.
set -uo pipefail
dir=$(mktemp -d "${TMPDIR:-/tmp}/aperture-xvfb.XXXXXX")
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -ac -noreset 3>"$dir/display" 2>"$dir/log" &
pid=$!
cleanup() {
  kill "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  rm -rf "$dir"
}
trap cleanup EXIT
for _ in $(seq 200); do
  [ -s "$dir/display" ] && break
  if ! kill -0 "$pid" 2>/dev/null; then
    echo "with-xvfb.sh: Xvfb failed to start:" >&2
    cat "$dir/log" >&2
    exit 1
  fi
  sleep 0.05
done
if [ ! -s "$dir/display" ]; then
  echo "with-xvfb.sh: Xvfb did not report a display within 10 s" >&2
  exit 1
fi
export DISPLAY=":$(head -n 1 "$dir/display")"
export LIBGL_ALWAYS_SOFTWARE=1
"$@"
