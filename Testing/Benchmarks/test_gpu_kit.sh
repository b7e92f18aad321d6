#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The GPU kit (scripts/gpu-kit.sh): it is made, fits in 60 MiB, and its run.sh draws one row of
# Table 1 from the unpacked kit alone (its own loader, libraries, Xvfb and data) and stops its
# Xvfb.
#
#   test_gpu_kit.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1
build=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$source_dir/scripts/gpu-kit.sh" "$build" "$work/kit.tar.xz"
bytes=$(stat -c %s "$work/kit.tar.xz")
limit=$(( 60 * 1048576 ))
echo "kit: $bytes bytes, limit $limit"
[ "$bytes" -le "$limit" ] || { echo "the kit is larger than 60 MiB"; exit 1; }
tar -xJf "$work/kit.tar.xz" -C "$work"
env -u DISPLAY "$work/mesolens-gpu-kit/run.sh" --tiny | tee "$work/run.log"
grep -q "^TABLE1 OpenGL renderer" "$work/run.log"
grep -q "^TABLE1 DPPC .* GPU warp [0-9.]* fps" "$work/run.log"
# run.sh stops the Xvfb it started.
sleep 1
if pgrep -f "$work/mesolens-gpu-kit/bin/Xvfb" > /dev/null; then
  echo "run.sh left its Xvfb running"
  exit 1
fi
echo "the kit runs"
