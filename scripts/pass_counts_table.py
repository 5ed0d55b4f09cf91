#!/usr/bin/env python3
"""Prints a Markdown table of a stats.json's per-pass pipeline statistics (issue 39, point 6).

    build/tallow capture --preset candle --size 160x90 --frames 3 --fps 8 --time 10 --out /tmp/cap
    python3 scripts/pass_counts_table.py /tmp/cap/stats.json [FRAME]

FRAME (default: the last) picks the frame; the GPU time of each pass is printed beside its counts.
"""
import json
import sys

COUNTERS = ["vertex", "geometry", "primitives", "fragment", "compute"]


def main() -> int:
    if len(sys.argv) not in (2, 3):
        print("usage: pass_counts_table.py STATS.json [FRAME]", file=sys.stderr)
        return 2
    with open(sys.argv[1]) as f:
        stats = json.load(f)
    frames = stats.get("frames", [])
    if not frames:
        print(f"{sys.argv[1]}: no frames", file=sys.stderr)
        return 1
    frame = frames[int(sys.argv[2])] if len(sys.argv) == 3 else frames[-1]
    counts = frame.get("invocations", {})
    if not counts:
        print(f"{sys.argv[1]}: no pipeline statistics (the driver offers no GL_ARB_pipeline_statistics_query)",
              file=sys.stderr)
        return 1
    print("| pass | " + " | ".join(COUNTERS) + " | GPU ms |")
    print("|---|" + "---:|" * (len(COUNTERS) + 1))
    for name, c in counts.items():
        ms = frame.get("gpu_ms", {}).get(name)
        cells = [f"{c.get(k, 0):,}" for k in COUNTERS] + ["" if ms is None else f"{ms:.1f}"]
        print(f"| {name} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
