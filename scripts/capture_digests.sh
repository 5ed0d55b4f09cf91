#!/usr/bin/env bash
# Prints one line per capture: "<case> <sha256 of each frame's float EXR>", for every preset and,
# on the bunny and the blob, every translucency method. Run it with two builds and diff the output
# to check that a change leaves every picture bit for bit as it was (issue 21, point 4):
#   bash scripts/capture_digests.sh build-old/tallow > old.txt
#   bash scripts/capture_digests.sh build/tallow > new.txt && diff old.txt new.txt
# Small sizes keep it to a few minutes on llvmpipe; frames 2 and 3 exercise what passes keep
# between frames (progressive accumulation, converged maps, a moving field).
set -euo pipefail
tallow="${1:?usage: capture_digests.sh PATH/TO/tallow}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
small=(--size 64x36 --frames 3 --fps 4 --exr-float --set sss.map_size=64 --set sss.light_map_size=64
       --set field.res=32 --set render.shadow_map_size=256 --set vpl.cube_size=32 --set sslpv.grid=16
       --set sslpv.inject_size=64)
digest() {  # digest NAME ARGS…
  local name="$1"; shift
  local out="$work/$name"
  if ! "$tallow" capture --out "$out" "${small[@]}" "$@" >/dev/null 2>"$work/err"; then
    echo "$name FAILED: $(tail -n 1 "$work/err")"
    return
  fi
  printf '%s' "$name"
  for f in "$out"/frame_*.exr; do printf ' %s' "$(sha256sum "$f" | cut -c1-16)"; done
  printf '\n'
}
for p in "$root"/presets/*.json; do
  name="$(basename "$p" .json)"
  digest "$name" --preset "$name"
done
for m in radiosity-maps no-cache sslpv image-space albedo; do
  digest "bunny-$m" --preset bunny --set method=$m
  digest "blob-$m" --preset blob --set method=$m
done
digest "candle-accumulate" --preset candle --accumulate 3 --set sss.frames=2
