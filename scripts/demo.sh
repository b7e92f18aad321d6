#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs what is missing, builds, and runs the demo on Data/: writes mesolens-demo.png and,
# where a display exists, opens the interactive window.
set -eu
cd "$(dirname "$0")/.."
./scripts/setup.sh
BUILD_DIR=${BUILD_DIR:-build}
if [ -n "${DISPLAY:-}" ]; then
  "$BUILD_DIR/bin/mesolens" demo --output mesolens-demo.png
else
  # Debian's VTK renders through GLX only: without a display, use a virtual one.
  xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \
    "$BUILD_DIR/bin/mesolens" demo --no-window --output mesolens-demo.png
fi
