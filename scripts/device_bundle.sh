#!/usr/bin/env bash
# Writes OUT_DIR/tallow-device.tar.xz: everything a GPU machine without packages needs to run the
# device bench (docs/device-bench.md), unpacked anywhere as tallow-device/:
#   bin/tallow, bin/tallow_bench_report   stripped Release binaries (shaders are embedded in tallow)
#   lib/                                  the shared libraries they load that GPU machines lack
#   lib/base/                             libraries most systems have (C++ runtime, zlib, X11, …),
#                                         which bench.sh takes only where the system's are missing
#                                         or too old
#   presets/, data/                       the presets, and the data files the bench reads
#   bench.sh, README.md, bundle.json      the bench, its guide, and what went in (commit, libraries,
#                                         the newest glibc symbol version the binaries need)
# Left out on purpose: glibc (the machine's own must be used) and the OpenGL/EGL loaders of
# libglvnd (they must match the machine's driver; docs/device-bench.md says how to carry them).
# libOSMesa and Mesa's LLVM are not needed: tallow loads OSMesa only for --gl osmesa.
#
# Usage: bash scripts/device_bundle.sh [--build-dir DIR] [--xz-level N] OUT_DIR
#   --build-dir DIR   take the binaries of this Release build folder as they are (the test does)
#                     instead of building with scripts/build.sh
#   --xz-level N      xz preset 0-9 (default 6: 18.6 MiB; the test's 1 takes a fifth of the time
#                     for a 22 MiB archive of the same files)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
die() { echo "device_bundle.sh: $*" >&2; exit 2; }

build="" out="" level=6
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) [ $# -ge 2 ] || die "--build-dir needs a folder"; build="$2"; shift 2 ;;
    --xz-level)
      [ $# -ge 2 ] && [[ "$2" =~ ^[0-9]$ ]] || die "--xz-level needs a digit 0-9"
      level="$2"; shift 2 ;;
    -h|--help) sed -n '2,20p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option \"$1\"" ;;
    *) [ -z "$out" ] || die "one OUT_DIR only (got \"$out\" and \"$1\")"; out="$1"; shift ;;
  esac
done
[ -n "$out" ] || die "usage: device_bundle.sh [--build-dir DIR] OUT_DIR"
# The budget of issue 18: the bundle travels to machines with little room for it.
max_bytes=$((60 * 1024 * 1024))

if [ -z "$build" ]; then
  [ "${TALLOW_SANITIZE:-0}" = "1" ] && die "TALLOW_SANITIZE=1: the bundle is a Release build"
  build="$(TALLOW_BUILD_TYPE=Release bash "$root/scripts/build.sh" | tail -n 1)"
fi
[ -f "$build/CMakeCache.txt" ] || die "--build-dir: $build is not a CMake build folder"
grep -q '^CMAKE_BUILD_TYPE:STRING=Release$' "$build/CMakeCache.txt" || die "$build is not a Release build (the bench times it)"
grep -q '^TALLOW_SANITIZE:BOOL=ON$' "$build/CMakeCache.txt" && die "$build is a sanitizer build"
for b in tallow tallow_bench_report; do
  [ -x "$build/$b" ] || die "$build/$b is missing: build it first (cmake --build $build)"
done
data="$(sed -n 's/^TALLOW_DATA_DIR:PATH=//p' "$build/CMakeCache.txt")"
[ -f "$data/materials.csv" ] || die "the build's TALLOW_DATA_DIR ($data) holds no materials.csv"

mkdir -p "$out" || die "cannot create $out"
out="$(cd "$out" && pwd)"
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT
top="$stage/tallow-device"
mkdir -p "$top/bin" "$top/lib/base" "$top/presets" "$top/data"

for b in tallow tallow_bench_report; do
  strip --strip-unneeded -o "$top/bin/$b" "$build/$b"
done

# Every library the binaries load, as the loader resolves it here. glibc's own libraries and the
# libglvnd loaders stay the machine's; the common system libraries go to lib/base/.
is_glibc() {
  case "$1" in
    linux-vdso.so.*|ld-linux*|libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|libresolv.so.*|libutil.so.*|libmvec.so.*) return 0 ;;
  esac
  return 1
}
is_glvnd() {
  case "$1" in libEGL.so.*|libGL.so.*|libGLX.so.*|libOpenGL.so.*|libGLESv2.so.*|libGLdispatch.so.*) return 0 ;; esac
  return 1
}
is_base() {
  case "$1" in
    libstdc++.so.*|libgcc_s.so.*|libz.so.*|libzstd.so.*|liblzma.so.*|libbz2.so.*|libX11.so.*|libxcb.so.*|libXau.so.*|libXdmcp.so.*|libbsd.so.*|libmd.so.*) return 0 ;;
  esac
  return 1
}
libs=()
while read -r name path; do
  is_glibc "$name" && continue
  is_glvnd "$name" && continue
  [ -f "$path" ] || die "$name is not found by the loader here ($path)"
  if is_base "$name"; then cp -L "$path" "$top/lib/base/$name"; else cp -L "$path" "$top/lib/$name"; fi
  libs+=("$name")
done < <(for b in tallow tallow_bench_report; do
           ldd "$build/$b" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3} $2 == "=>" && $3 == "not" {print $1, "missing"}'
         done | sort -u)
case " ${libs[*]} " in *" libOSMesa"*|*" libLLVM"*) die "tallow links OSMesa/LLVM again: it must load them with dlopen (gpu/gl_context_osmesa.cpp)" ;; esac

cp "$root"/presets/*.json "$top/presets/"
# The data the bench reads (materials for every preset, the bunny's mesh) and its credits.
cp "$data/materials.csv" "$data/bunny.ply" "$data/README.md" "$top/data/"
cp "$root/scripts/device_bench.sh" "$top/bench.sh"
chmod 755 "$top/bench.sh"
cp "$root/docs/device-bench.md" "$top/README.md"

# The newest glibc symbol version any bundled file asks for: the machine's glibc must be as new.
newest_glibc() { find "$@" -type f -exec objdump -T {} + 2>/dev/null | grep -o 'GLIBC_[0-9][0-9.]*' | sort -Vu | tail -n 1; }
glibc="$(newest_glibc "$top/bin" "$top/lib" -path "$top/lib/base" -prune -o)"
glibc_base="$(newest_glibc "$top/lib/base")"
commit="$(git -C "$root" rev-parse HEAD 2>/dev/null || echo unknown)"
dirty=false
[ -n "$(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null)" ] && dirty=true
commit_time="$(git -C "$root" log -1 --format=%ct 2>/dev/null || date +%s)"
{
  printf '{\n  "commit": "%s",\n  "dirty": %s,\n  "built_utc": "%s",\n  "build_dir": "%s",\n' \
    "$commit" "$dirty" "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$build"
  printf '  "glibc_needed": "%s",\n  "glibc_needed_by_lib_base": "%s",\n  "libraries": [' "$glibc" "$glibc_base"
  sep=""
  for l in "${libs[@]}"; do printf '%s"%s"' "$sep" "$l"; sep=", "; done
  printf '],\n  "left_out": ["glibc", "libglvnd (libEGL, libGLdispatch)", "libOSMesa and LLVM (loaded only for --gl osmesa)"]\n}\n'
} >"$top/bundle.json"

# Sorted, owner-free entries with the commit's time: the same tree gives the same archive.
tmp="$out/.tallow-device.tar.xz.tmp-$$"
trap 'rm -rf "$stage" "$tmp"' EXIT
tar -C "$stage" --sort=name --owner=0 --group=0 --numeric-owner --mtime="@$commit_time" -cf - tallow-device |
  xz -"$level" -T"$(nproc 2>/dev/null || echo 2)" >"$tmp"
size=$(stat -c %s "$tmp")
unpacked=$(du -sb "$top" | cut -f1)
if [ "$size" -gt "$max_bytes" ]; then
  die "the bundle is $((size / 1048576)) MiB, over the 60 MiB budget: make the largest libraries optional (dlopen)"
fi
mv "$tmp" "$out/tallow-device.tar.xz"
mib() { awk -v b="$1" 'BEGIN { printf "%.1f", b / 1048576 }'; }
note=""
[ "$dirty" = true ] && note=", with uncommitted changes"
echo "device_bundle.sh: wrote $out/tallow-device.tar.xz: $(mib "$size") MiB ($(mib "$unpacked") MiB unpacked," \
  "${#libs[@]} libraries, glibc >= ${glibc#GLIBC_}, commit ${commit:0:12}$note)"
