#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Packs MesoLens' rendering benchmarks for a bare Linux x86-64 machine with an NVIDIA driver and
# no VTK: BenchmarkWarpTable (Table 1 of Membrane Mapping) and BenchmarkAtomMapper, every shared
# library they load (with this system's own dynamic loader, so the host's C library does not
# matter), an Xvfb with its keyboard data for VTK's GLX windows, Mesa (llvmpipe, and the server
# side of GLX), the glvnd loaders, the data they read, and run.sh.
#
#   scripts/gpu-kit.sh [--without-llvm] [BUILD_DIR] [OUTPUT]
#                                   (defaults: build, mesolens-gpu-kit.tar.xz)
#
# --without-llvm leaves llvmpipe's compiler out (about 56 MiB down to about 35 MiB, small enough
# to travel with this repository to a lent GPU machine, 64 MiB in all): Mesa then
# renders with softpipe, which the carried Xvfb needs only for its side of GLX on a machine
# whose GPU draws; benchmarks on llvmpipe need the full kit.
#
# On the target machine:
#   tar -xJf mesolens-gpu-kit.tar.xz -C /tmp && /tmp/mesolens-gpu-kit/run.sh [--quick]
# run.sh starts the carried Xvfb, asks glvnd for NVIDIA's GLX when the driver is there
# (__GLX_VENDOR_LIBRARY_NAME=nvidia) and for Mesa's llvmpipe when it is not, prints the OpenGL
# renderer string and the benchmarks' figures. --quick runs a small table (for llvmpipe).
#
# libLLVM (llvmpipe's compiler) links libz3 and libxml2 (with ICU), which llvmpipe never calls:
# the kit carries stubs with their symbols instead (every function says so and aborts), and
# leaves out what only the real ones needed; about 15 MiB less.
set -euo pipefail

without_llvm=
if [ "${1:-}" = "--without-llvm" ]; then
  without_llvm=1
  shift
fi
build=$(cd "${1:-build}" && pwd)
output=$(realpath -m "${2:-mesolens-gpu-kit.tar.xz}")
source_dir=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
kit="$work/mesolens-gpu-kit"
mkdir -p "$kit/bin" "$kit/lib/dri" "$kit/share" "$kit/data/meshes" "$kit/data/membranes"

multiarch=/usr/lib/x86_64-linux-gnu
programs=("$build/bin/BenchmarkWarpTable" "$build/bin/BenchmarkAtomMapper" /usr/bin/Xvfb
          /usr/bin/xkbcomp)
# Loaded with dlopen, not named by any program: glvnd's dispatch, Mesa's GLX vendor and its
# software driver.
opened=("$multiarch/libGL.so.1" "$multiarch/libGLX.so.0" "$multiarch/libGLdispatch.so.0"
        "$multiarch/libGLX_mesa.so.0" "$multiarch/dri/swrast_dri.so")
stubbed=(libz3.so.4 libxml2.so.2)
if [ -n "$without_llvm" ]; then
  stubbed=(libLLVM-15.so.1)
fi

for program in "${programs[@]}"; do
  cp -L "$program" "$kit/bin/"
done
cp -L "$multiarch/dri/swrast_dri.so" "$kit/lib/dri/"
for library in "${opened[@]}"; do
  [ "$(basename "$library")" = swrast_dri.so ] || cp -L "$library" "$kit/lib/"
done

# Every library the programs and the opened libraries need, resolved on this system, under the
# name they are asked for by.
for file in "${programs[@]}" "${opened[@]}"; do ldd "$file"; done |
  awk '$2 == "=>" && $3 ~ /^\// { print $1, $3 }' | sort -u > "$work/closure"
while read -r name library; do
  case " ${stubbed[*]} " in *" $name "*) continue ;; esac
  cp -L "$library" "$kit/lib/$name"
done < "$work/closure"
cp -L /lib64/ld-linux-x86-64.so.2 "$kit/lib/"

# The stubs: every symbol the carried libraries import from a stubbed one, with the version
# the real library gives it; functions abort, data are zero. Mesa asks LLVMIsMultithreaded when
# it is loaded: that one answers yes.
answers_yes=LLVMIsMultithreaded
for name in "${stubbed[@]}"; do
  real=$(ldconfig -p | awk -v n="$name" '$1 == n && /x86-64/ && !found { print $NF; found = 1 }')
  stub="$work/stub-${name%%.so*}"
  mkdir -p "$stub"
  nm -D --undefined-only "$kit"/lib/*.so* "$kit"/lib/dri/*.so 2>/dev/null | awk '$1 == "U" { print $2 }' |
    sort -u > "$stub/imports"
  nm -D --defined-only -S "$real" | awk 'NF == 4 { print $4, $3, $2 }' > "$stub/defined"
  awk -v out="$stub/stub.c" -v map="$stub/version.map" -v yes="$answers_yes" '
    BEGIN { n = split(yes, list, ","); for (i = 1; i <= n; ++i) answer[list[i]] = 1 }
    NR == FNR { split($1, part, "@"); type[part[1]] = $2; size[part[1]] = $3;
                version[part[1]] = part[length(part)]; next }
    { split($1, part, "@"); symbol = part[1]
      if (!(symbol in type)) next
      if (type[symbol] ~ /[DdBbRr]/) printf "char %s[0x%s];\n", symbol, size[symbol] > out
      else if (symbol in answer) printf "int %s(void) { return 1; }\n", symbol > out
      else printf "void %s(void) { stub_called(\"%s\"); }\n", symbol, symbol > out
      if (version[symbol] != symbol) versions[version[symbol]] = versions[version[symbol]] symbol ";" }
    END { for (v in versions) printf "%s { global: %s };\n", v, versions[v] > map }
  ' "$stub/defined" "$stub/imports"
  { printf '#include <stdio.h>\n#include <stdlib.h>\n'
    printf 'static void stub_called(const char* f) { fprintf(stderr, "%s: %%s is a stub\\n", f); abort(); }\n' "$name"
    cat "$stub/stub.c" 2>/dev/null || true; } > "$stub/all.c"
  version_flag=()
  [ -s "$stub/version.map" ] && version_flag=(-Wl,--version-script="$stub/version.map")
  cc -shared -fPIC -O1 -o "$kit/lib/$name" -Wl,-soname,"$name" "${version_flag[@]}" "$stub/all.c"
done

# What only the replaced libraries needed (ICU for libxml2; z3, libxml2, libedit, ... for
# libLLVM) is needed by nothing the kit carries now: out, until nothing more goes. The libraries
# loaded with dlopen stay.
kept_anyway=" ld-linux-x86-64.so.2 $(for library in "${opened[@]}"; do basename "$library"; done | tr '\n' ' ')"
while :; do
  needed=$(for file in "$kit"/bin/* "$kit"/lib/*.so* "$kit"/lib/dri/*.so; do readelf -d "$file"; done |
           awk -F'[][]' '/NEEDED/ { print $2 }' | sort -u)
  removed=
  for file in "$kit"/lib/*.so*; do
    name=$(basename "$file")
    case "$kept_anyway" in *" $name "*) continue ;; esac
    if ! grep -qxF "$name" <<< "$needed"; then
      rm "$file"
      removed=1
    fi
  done
  [ -n "$removed" ] || break
done

# Symbol tables are not needed to run (this system's own libraries come without them).
strip --strip-unneeded "$kit"/bin/* "$kit"/lib/libMesoLens*

# The keyboard data Xvfb compiles its keymap from; the rules' descriptions for desktop tools
# (.lst, .xml) are not read.
cp -r /usr/share/X11/xkb "$kit/share/xkb"
rm -f "$kit"/share/xkb/rules/*.lst "$kit"/share/xkb/rules/*.xml
cp "$source_dir/Data/meshes/mito5_outer_membrane.obj" "$kit/data/meshes/"
# The patches as the benchmarks read them; velocities dropped (the first 44 columns of an atom
# line are its name and position).
for patch in dppc128_slipids_323K.gro yiip_popepopg.gro; do
  awk 'NR <= 2 { print; next } { line[NR] = $0 } END { for (i = 3; i < NR; ++i) print substr(line[i], 1, 44); print line[NR] }' \
    "$source_dir/Data/membranes/$patch" > "$kit/data/membranes/$patch"
done
cp "$source_dir/scripts/gpu-kit-run.sh" "$kit/run.sh"
chmod +x "$kit/run.sh"
[ -z "$without_llvm" ] || touch "$kit/lib/WITHOUT_LLVM" # run.sh then asks Mesa for softpipe

# One xz stream, x86 branch filter first (machine code compresses about 10 % better), with a
# dictionary larger than the biggest library (about 3 minutes on one core).
tar -C "$work" -cf - mesolens-gpu-kit | xz --x86 --lzma2=preset=9e,dict=256MiB -T1 > "$output"
bytes=$(stat -c %s "$output")
echo "wrote $output: $bytes bytes ($(( bytes / 1048576 )).$(( bytes % 1048576 * 10 / 1048576 )) MiB)," \
  "$(du -sm "$kit" | cut -f1) MiB unpacked"
