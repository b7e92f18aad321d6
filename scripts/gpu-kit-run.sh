#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# run.sh of the MesoLens GPU kit (made by scripts/gpu-kit.sh): starts the carried Xvfb, prints
# the OpenGL renderer and runs the benchmarks with the carried libraries and data.
#
#   run.sh            Table 1 (1920 x 1080, YiiP and DPPC, 1 to 15 tiles squared) and the
#                     impostor benchmark: for a machine with a GPU
#   run.sh --quick    a small table at 640 x 360, 1 and 3 tiles: for llvmpipe
#   run.sh --tiny     one row at 320 x 180: to check a kit, or softpipe
set -u
here=$(cd "$(dirname "$0")" && pwd)
lib="$here/lib"
loader="$lib/ld-linux-x86-64.so.2"

# NVIDIA's GLX (through glvnd) where the driver is installed (MESOLENS_GL_DIR: where else to
# look); else Mesa's llvmpipe.
path="$lib"
for dir in ${MESOLENS_GL_DIR:-} /usr/local/nvidia/lib64 /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/lib; do
  if ls "$dir"/libGLX_nvidia.so.0 >/dev/null 2>&1; then
    path="$lib:$dir"
    export __GLX_VENDOR_LIBRARY_NAME=nvidia
    break
  fi
done
[ -n "${__GLX_VENDOR_LIBRARY_NAME:-}" ] || export __GLX_VENDOR_LIBRARY_NAME=mesa
if [ -e "$lib/WITHOUT_LLVM" ]; then
  # A kit without llvmpipe's compiler: Mesa (Xvfb's GLX, or the rendering without a GPU) uses
  # softpipe and its draw module no LLVM.
  export GALLIUM_DRIVER=softpipe DRAW_USE_LLVM=0
fi
export LIBGL_DRIVERS_PATH="$lib/dri"
export MESOLENS_DATA_DIR="$here/data"
run() { "$loader" --library-path "$path" "$@"; }

# Xvfb compiles its keymap by running /usr/bin/xkbcomp (a path built into it). A bare machine
# has none: the carried one is put there, through the carried loader, for this run only.
made_xkbcomp=
if [ ! -x /usr/bin/xkbcomp ]; then
  printf '#!/bin/sh\nexec "%s" --library-path "%s" "%s" "$@"\n' \
    "$loader" "$lib" "$here/bin/xkbcomp" > /usr/bin/xkbcomp || exit 1
  chmod +x /usr/bin/xkbcomp
  made_xkbcomp=1
fi
display=:$(( ($$ % 500) + 100 ))
# Started by the loader itself (not through run, a shell function): $! is then Xvfb.
"$loader" --library-path "$path" "$here/bin/Xvfb" "$display" -screen 0 1920x1080x24 -nolisten tcp -noreset \
  -xkbdir "$here/share/xkb" >/tmp/mesolens-gpu-kit-xvfb.log 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; [ -z "$made_xkbcomp" ] || rm -f /usr/bin/xkbcomp' EXIT
export DISPLAY="$display"
for _ in 1 2 3 4 5 6 7 8 9 10; do
  [ -e "/tmp/.X11-unix/X${display#:}" ] && break
  sleep 1
done
if ! kill -0 "$xvfb" 2>/dev/null; then
  echo "Xvfb did not start:"; cat /tmp/mesolens-gpu-kit-xvfb.log; exit 1
fi

echo "GLX vendor asked for: $__GLX_VENDOR_LIBRARY_NAME"
if [ "${1:-}" = "--tiny" ]; then
  run "$here/bin/BenchmarkWarpTable" --size 320x180 --tiles 1 --patches dppc \
    --methods polynomial --frames 1
elif [ "${1:-}" = "--quick" ]; then
  run "$here/bin/BenchmarkWarpTable" --size 640x360 --tiles 1,3 --frames 3
  run "$here/bin/BenchmarkAtomMapper" --atoms 100000 --frames 3 --no-warp
else
  run "$here/bin/BenchmarkWarpTable" --size 1920x1080 --tiles 1,3,5,10,15 --frames 10
  run "$here/bin/BenchmarkAtomMapper" --atoms 1000000,4000000 --frames 10
fi
