#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) into build-fuzz/ and runs each for
# $TALLOW_FUZZ_SECONDS seconds (default 20), starting from the kept corpus tests/fuzz/corpus/<name>/
# and from this machine's working corpus build-fuzz/corpus/<name>/ (what earlier runs learned),
# with the target's dictionary tests/fuzz/dict/<name>.dict where there is one. New inputs go to
# the working corpus. A crash, leak, sanitizer report, timeout or out-of-memory fails the script
# and keeps the input in build-fuzz/artifacts/: once fixed, copy it into tests/fuzz/corpus/<name>/,
# where ctest replays it on every run (FuzzReplay.<name>, tests/CMakeLists.txt).
#
#   TALLOW_FUZZ_TARGETS="ply preset"   only these targets
#   TALLOW_FUZZ_MERGE=1                afterwards, minimise kept + working corpus into a fresh kept
#                                      corpus (libFuzzer -merge=1: the named seeds plus the fewest
#                                      found inputs that add a feature), in tests/fuzz/corpus/<name>/;
#                                      commit it
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TALLOW_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${TALLOW_FUZZ_SECONDS:-20}"
merge="${TALLOW_FUZZ_MERGE:-0}"
jobs="$(nproc 2>/dev/null || echo 2)"
# Inputs longer than this add little to text and header parsers and make the kept corpora large.
max_len=4096
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DTALLOW_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j"$jobs"
status=0
ran=0
for target in "$build"/fuzz_*; do
  [ -f "$target" ] && [ -x "$target" ] || continue
  name="$(basename "$target")"
  corpus_name="${name#fuzz_}"
  if [ -n "${TALLOW_FUZZ_TARGETS:-}" ] && [[ " $TALLOW_FUZZ_TARGETS " != *" $corpus_name "* ]]; then
    continue
  fi
  ran=$((ran + 1))
  work="$build/corpus/$corpus_name"
  mkdir -p "$work" "$build/artifacts"
  seeds="$root/tests/fuzz/corpus/$corpus_name"
  dict="$root/tests/fuzz/dict/$corpus_name.dict"
  options=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$max_len" -print_final_stats=1
           -artifact_prefix="$build/artifacts/$name-")
  [ -f "$dict" ] && options+=(-dict="$dict")
  dirs=("$work")
  [ -d "$seeds" ] && dirs+=("$seeds")
  echo "fuzz: $name for ${seconds}s"
  if ! "$target" "${options[@]}" "${dirs[@]}" >"$build/$name.log" 2>&1; then
    echo "fuzz: $name FAILED; last lines of $build/$name.log:"
    tail -n 40 "$build/$name.log"
    status=1
    continue
  fi
  grep -E "stat::number_of_executed_units|stat::new_units_added" "$build/$name.log" | sed "s/^/fuzz: $name /" || true
  if [ "$merge" = "1" ]; then
    # Named inputs (hand-made seeds, fixed crashes: anything not called by its SHA-1 as libFuzzer
    # names what it finds) are kept as they are; merging adds only the inputs that reach features
    # they do not, and drops earlier merged inputs that no longer add any.
    fresh="$build/merge/$corpus_name"
    rm -rf "$fresh"
    mkdir -p "$fresh" "$seeds"
    find "$seeds" -maxdepth 1 -regextype posix-extended -type f ! -regex '.*/[0-9a-f]{40}' -exec cp {} "$fresh"/ \;
    "$target" -merge=1 -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 "$fresh" "${dirs[@]}" \
      >"$build/$name.merge.log" 2>&1
    find "$seeds" -maxdepth 1 -regextype posix-extended -type f -regex '.*/[0-9a-f]{40}' -delete
    find "$fresh" -maxdepth 1 -regextype posix-extended -type f -regex '.*/[0-9a-f]{40}' -exec cp {} "$seeds"/ \;
    echo "fuzz: $name kept corpus: $(ls "$seeds" | wc -l) input(s), $(du -sk --apparent-size "$seeds" | cut -f1) KiB"
  fi
done
if [ "$ran" -eq 0 ]; then
  echo "fuzz: no fuzz targets found in $build"
  exit 1
fi
[ $status -eq 0 ] && echo "fuzz: all $ran targets clean"
exit $status
