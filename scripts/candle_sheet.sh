#!/usr/bin/env bash
# The melting candle shown (issue 35, point 6): a contact sheet of the default preset at six times
# (4, 8, 12, 14, 16 and 20 s; each rendered 16 times at its time so that the maps accumulate, as a
# paused window shows it) and a short video of its last seconds as played (t = 12 → 20 s at 15 fps,
# the flame flickering, the drips running and freezing), both from `tallow capture`; ffmpeg tiles the
# sheet and encodes the video. Beside them, pool.png: the preset at 16 s seen steeply into the cup
# (the default camera's rim hides the pool), the liquid pool and the flame's reflection in it.
#   bash scripts/candle_sheet.sh [OUT_DIR]        (default docs/images/candle)
# TALLOW_SIZE (default 480x270) and TALLOW_VIDEO_SIZE (default 320x180) set the pictures' sizes.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/docs/images/candle}"
build="$(bash "$root/scripts/build.sh" | tail -n 1)"
tallow="$build/tallow"
size="${TALLOW_SIZE:-480x270}"
video_size="${TALLOW_VIDEO_SIZE:-320x180}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
i=0
for t in 4 8 12 14 16 20; do
  echo "candle_sheet: t = $t s"
  "$tallow" capture --preset candle --time "$t" --size "$size" --accumulate 16 --out "$work/t$t" >/dev/null
  cp "$work/t$t/frame_0000.png" "$work/sheet_$(printf %02d $i).png"
  i=$((i + 1))
done
# Three by two, in time order (4, 8, 12 above; 14, 16, 20 below).
ffmpeg -hide_banner -loglevel error -y -i "$work/sheet_%02d.png" -vf "tile=3x2:padding=4:color=black" \
  -frames:v 1 -update 1 "$out/contact_sheet.png"
echo "candle_sheet: the pool"
python3 - "$root/presets/candle.json" "$work/pool.json" <<'PY'
import json, sys
preset = json.load(open(sys.argv[1]))
preset["camera"].update({"position": [0.0, 0.135, -0.036], "target": [0.0, 0.037, 0.0], "fov_deg": 25})
json.dump(preset, open(sys.argv[2], "w"))
PY
"$tallow" capture --preset "$work/pool.json" --time 16 --size "$size" --accumulate 16 --out "$work/pool" >/dev/null
cp "$work/pool/frame_0000.png" "$out/pool.png"
echo "candle_sheet: video"
"$tallow" capture --preset candle --time 12 --frames 120 --fps 15 --size "$video_size" --out "$work/video" \
  --video "$out/melt.mp4" >/dev/null
echo "candle_sheet: wrote $out/contact_sheet.png, $out/pool.png and $out/melt.mp4"
