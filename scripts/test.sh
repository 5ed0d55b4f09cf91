#!/usr/bin/env bash
# Installs what is missing, builds, runs the GoogleTest suite through ctest (output on failure),
# then runs each libFuzzer target briefly. TALLOW_SANITIZE=1 builds and tests with ASan + UBSan;
# TALLOW_FUZZ_SECONDS (default 20) sets the time per fuzz target, 0 skips fuzzing.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
build="$(bash "$root/scripts/build.sh" | tail -n 1)"
jobs="$(nproc 2>/dev/null || echo 2)"
ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 600
if [ "${TALLOW_FUZZ_SECONDS:-20}" != "0" ]; then
  bash "$root/scripts/fuzz.sh"
fi
