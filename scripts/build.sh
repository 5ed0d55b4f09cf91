#!/usr/bin/env bash
# Configures and builds Tallow into build/ (or $TALLOW_BUILD_DIR). TALLOW_SANITIZE=1 builds with
# AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ instead, TALLOW_SANITIZE=thread with
# ThreadSanitizer into build-tsan/. TALLOW_BUILD_TARGETS="tallow_tests" builds only those targets.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${TALLOW_SANITIZE:-0}" = "thread" ]; then
  build="${TALLOW_BUILD_DIR:-$root/build-tsan}"
  extra=(-DTALLOW_SANITIZE=thread)
elif [ "${TALLOW_SANITIZE:-0}" = "1" ]; then
  build="${TALLOW_BUILD_DIR:-$root/build-asan}"
  extra=(-DTALLOW_SANITIZE=ON)
else
  build="${TALLOW_BUILD_DIR:-$root/build}"
  extra=()
fi
jobs="$(nproc 2>/dev/null || echo 2)"
# ccache, where installed, keeps rebuilds of other checkouts of the same sources short.
if command -v ccache >/dev/null 2>&1; then
  extra+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${TALLOW_BUILD_TYPE:-Release}" "${extra[@]}" >/dev/null
targets=()
for t in ${TALLOW_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" -j"$jobs" "${targets[@]}"
echo "$build"
