#!/usr/bin/env bash
# Configures and builds Tallow into build/ (or $TALLOW_BUILD_DIR). TALLOW_SANITIZE=1 builds with
# AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ instead.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${TALLOW_SANITIZE:-0}" = "1" ]; then
  build="${TALLOW_BUILD_DIR:-$root/build-asan}"
  extra=(-DTALLOW_SANITIZE=ON)
else
  build="${TALLOW_BUILD_DIR:-$root/build}"
  extra=()
fi
jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${TALLOW_BUILD_TYPE:-Release}" "${extra[@]}" >/dev/null
cmake --build "$build" -j"$jobs"
echo "$build"
