#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) into build-fuzz/ and runs each for
# $TALLOW_FUZZ_SECONDS seconds (default 20) from its seed corpus in tests/fuzz/corpus/<name>/.
# A crash, leak, sanitizer report, timeout or out-of-memory fails the script and keeps the input.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TALLOW_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${TALLOW_FUZZ_SECONDS:-20}"
jobs="$(nproc 2>/dev/null || echo 2)"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DTALLOW_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j"$jobs"
status=0
ran=0
for target in "$build"/fuzz_*; do
  [ -f "$target" ] && [ -x "$target" ] || continue
  ran=$((ran + 1))
  name="$(basename "$target")"
  corpus_name="${name#fuzz_}"
  work="$build/corpus/$corpus_name"
  mkdir -p "$work" "$build/artifacts"
  seeds="$root/tests/fuzz/corpus/$corpus_name"
  echo "fuzz: $name for ${seconds}s"
  if ! "$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$build/artifacts/$name-" "$work" ${seeds:+$( [ -d "$seeds" ] && echo "$seeds")} \
      >"$build/$name.log" 2>&1; then
    echo "fuzz: $name FAILED; last lines of $build/$name.log:"
    tail -n 40 "$build/$name.log"
    status=1
  else
    grep -E "stat::number_of_executed_units" "$build/$name.log" | sed "s/^/fuzz: $name /" || true
  fi
done
if [ "$ran" -eq 0 ]; then
  echo "fuzz: no fuzz targets found in $build"
  exit 1
fi
[ $status -eq 0 ] && echo "fuzz: all $ran targets clean"
exit $status
