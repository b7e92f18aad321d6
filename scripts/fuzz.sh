#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the libFuzzer targets (clang, ASan and UBSan) and runs one for SECONDS over its corpus:
# the seeds of the checkout (Testing/Fuzz/seeds/TARGET), then what the run adds (kept in
# BUILD/corpus/TARGET). Crashes, leaks, timeouts (-timeout=10 s) and allocations over 2 GiB
# (-rss_limit_mb=2048) stop the run and leave the input in BUILD/artifacts/TARGET/.
#
#   scripts/fuzz.sh TARGET SECONDS [libFuzzer options...]
#   scripts/fuzz.sh --build           builds every target, runs none
#
# TARGET: fuzz_ply, fuzz_structure, fuzz_gro, fuzz_trajectory, fuzz_mesh (files); fuzz_surface,
# fuzz_ribbons, fuzz_geodesic, fuzz_cutaway, fuzz_structure_mesh (geometry); fuzz_selection
# (atom-selection text).
# BUILD is build-fuzz/ in the checkout, or $MESOLENS_FUZZ_BUILD_DIR.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${MESOLENS_FUZZ_BUILD_DIR:-$root/build-fuzz}
configure() {
  if [ ! -f "$build/CMakeCache.txt" ]; then
    CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DMESOLENS_BUILD_FUZZERS=ON -DMESOLENS_BUILD_TESTING=OFF -DMESOLENS_BUILD_EXAMPLES=OFF \
      -DMESOLENS_WRAP_PYTHON=OFF -DMESOLENS_BUILD_PARAVIEW_PLUGIN=OFF >/dev/null
  fi
}
if [ "${1:-}" = "--build" ]; then
  configure
  exec cmake --build "$build" --target mesolens_fuzzers -j "$(nproc)"
fi
if [ $# -lt 2 ]; then
  echo "usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer options...] | scripts/fuzz.sh --build" >&2
  exit 2
fi
target=$1
seconds=$2
shift 2
case "$target" in
  fuzz_ply) dict=ply.dict ;;
  fuzz_structure) dict=structure.dict ;;
  fuzz_gro) dict=gro.dict; quiet=1 ;;
  fuzz_trajectory) dict=trajectory.dict; quiet=1 ;;
  fuzz_mesh) dict=mesh.dict ;;
  fuzz_selection) dict=selection.dict ;;
  fuzz_surface | fuzz_ribbons | fuzz_geodesic | fuzz_cutaway | fuzz_structure_mesh) dict= ;;
  *) echo "unknown fuzz target $target" >&2; exit 2 ;;
esac
configure
cmake --build "$build" --target "$target" -j "$(nproc)" >/dev/null
corpus="$build/corpus/$target"
artifacts="$build/artifacts/$target"
mkdir -p "$corpus" "$artifacts"
# New inputs go to the first folder; the committed seeds are read from the second.
seeds="$root/Testing/Fuzz/seeds/$target"
[ ! -d "$seeds" ] || set -- "$seeds" "$@"
[ -z "$dict" ] || set -- -dict="$root/Testing/Fuzz/$dict" "$@"
# GROMACS reports every file it opens on stderr: closed for the target (libFuzzer and the
# sanitizers still report).
[ -z "${quiet:-}" ] || set -- -close_fd_mask=2 "$@"
export LSAN_OPTIONS="suppressions=$root/Testing/Fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
exec "$build/bin/$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$artifacts/" -print_final_stats=1 "$@"
