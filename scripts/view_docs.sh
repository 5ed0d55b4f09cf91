#!/usr/bin/env bash
# Regenerates the screenshots of docs/view.md (docs/images/view/): `tallow view --screenshot` under
# a virtual display (Xvfb) of our own, one run per picture; and the pictures of docs/commands.md
# (docs/images/commands/): a small `tallow bench`'s plot and a row's comparison figure, and
# `tallow compare`. Nothing is drawn by hand.
# Usage: bash scripts/view_docs.sh [--quick]   (--quick: smaller, fewer frames, for a smoke run)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(bash "$root/scripts/build.sh" | tail -n 1)"
tallow="$build/tallow"
size=1000x560
frames=24
if [ "${1:-}" = "--quick" ]; then size=480x300; frames=4; fi
images="$root/docs/images/view"
commands="$root/docs/images/commands"
mkdir -p "$images" "$commands"
work="$(mktemp -d)"

# Xvfb picks a free display itself and writes its number to fd 3 once it accepts connections. The
# screen holds the panel (420 pixels) beside a 1000-pixel image.
Xvfb -displayfd 3 -screen 0 1920x1080x24 -nolisten tcp 3>"$work/display" >"$work/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; wait $xvfb 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 200); do [ -s "$work/display" ] && break; sleep 0.05; done
[ -s "$work/display" ] || { echo "view_docs: Xvfb did not start: $(cat "$work/xvfb.log")"; exit 1; }
export DISPLAY=":$(head -n 1 "$work/display")"

# Settings that keep llvmpipe to seconds per frame: 8 maps of 256², 4 samples, the clock paused so
# the maps accumulate over the frames shown.
quick=(--set sss.maps=8 --set sss.map_size=256 --set sss.light_map_size=256 --set sss.samples=4
       --set render.shadow_map_size=1024 --paused --fps 30 --frames "$frames")
shot() {  # name, then view arguments
  local name="$1"
  shift
  echo "view_docs: $name"
  "$tallow" view --size "$size" "${quick[@]}" "$@" --screenshot "$images/$name.png" >/dev/null
}

shot panel-candle --preset candle
shot panel-blob --preset blob --time 4
# F1 pressed at the last frame: the panel hidden, the picture filling the window.
printf 'frame %d key f1\n' "$((frames - 1))" >"$work/f1.txt"
shot no-panel --preset bunny --script "$work/f1.txt"
shot map --preset bunny --debug-view map:2
shot gbuffer-normal --preset bunny --debug-view gbuffer-normal:0
shot gbuffer-point --preset candle-holder --debug-view gbuffer-position:0:2
shot coverage --preset bunny --set sss.maps=3 --debug-view coverage
shot vpl --preset candle --debug-view vpl
shot wireframe --preset blob --time 4 --set field.res=32 --debug-view wireframe

# The difference to the CPU reference of the same frame (tallow reference, at the same size).
ref_size=480x300
"$tallow" reference --preset bunny --size "$ref_size" --spp 8 --out "$work/ref.exr" >/dev/null
echo "view_docs: difference"
# +3 EV: the differences are a few percent of the radiance.
"$tallow" view "${quick[@]}" --size "$ref_size" --preset bunny --reference "$work/ref.exr" --debug-view difference \
  --set render.exposure_ev=3 --screenshot "$images/difference.png" >/dev/null
echo "view_docs: wrote $(ls "$images" | wc -l) pictures to docs/images/view/"

# docs/commands.md: a small bench of the bunny (three methods, two settings of the maps) against a
# reference of the same size: its speed-against-error plot and one row's comparison figure.
echo "view_docs: bench"
"$tallow" bench --preset bunny --size 160x120 --methods radiosity-maps,no-cache,image-space \
  --sweep sss.maps=8,16 --set sss.frames=8 --set sss.map_size=256 --set sss.light_map_size=256 --set sss.samples=4 \
  --ref-spp 8 --out "$work/bench" >/dev/null
cp "$work/bench/speed_error.png" "$commands/bench-speed-error.png"
cp "$work/bench/rows/radiosity-maps_sss.maps-16/comparison.png" "$commands/bench-comparison.png"
# tallow compare: that row's last frame against the reference, over the reference's object pixels.
"$tallow" compare "$work/bench/rows/radiosity-maps_sss.maps-16/last.exr" "$work/bench/reference.exr" \
  --mask "$work/bench/reference_stderr.exr" --caption "radiosity maps, K = 16" --caption "reference (8 passes)" \
  --title "tallow compare" --out "$commands/compare.png" >/dev/null
echo "view_docs: wrote $(ls "$commands" | wc -l) pictures to docs/images/commands/"
