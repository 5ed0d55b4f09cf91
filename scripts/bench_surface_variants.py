#!/usr/bin/env python3
"""The camera pass's cost per translucency method, two builds in one run (issue 38: one shader
variant per method against the monolithic surface.frag before it).

    python3 scripts/bench_surface_variants.py OLD_TALLOW NEW_TALLOW [--size 480x270] [--frames 6] [--reps 2]

Captures the candle under each method with each binary, alternating, and prints the median GPU
time of the `surface` pass over the frames after the first (stats.json gpu_ms) and the ratio.
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile

METHODS = ["radiosity-maps", "no-cache", "sslpv", "image-space", "albedo"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--size", default="480x270")
    ap.add_argument("--frames", type=int, default=6)
    ap.add_argument("--reps", type=int, default=2)
    a = ap.parse_args()
    if a.frames < 2 or a.reps < 1:
        sys.exit("bench_surface_variants: --frames must be at least 2 and --reps at least 1")
    times = {}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(a.reps):
            for method in METHODS:
                for name, binary in (("old", a.old), ("new", a.new)):
                    out = f"{tmp}/{name}_{method}"
                    run = subprocess.run([binary, "capture", "--preset", "candle", "--size", a.size, "--frames",
                                          str(a.frames), "--set", f"method={method}", "--set", "render.aa=1",
                                          "--out", out], capture_output=True, text=True)
                    if run.returncode != 0:
                        sys.exit(f"bench_surface_variants: {binary} failed: {run.stderr.strip().splitlines()[-1:]}")
                    with open(f"{out}/stats.json") as f:
                        frames = json.load(f)["frames"][1:]
                    times.setdefault((method, name), []).extend(
                        fr["gpu_ms"]["surface"] for fr in frames if "surface" in fr.get("gpu_ms", {}))
    for method in METHODS:
        old, new = statistics.median(times[(method, "old")]), statistics.median(times[(method, "new")])
        print(f"{method:15s} surface pass median: old {old:8.2f} ms, new {new:8.2f} ms, "
              f"new/old {new / old:.3f} ({len(times[(method, 'new')])} frames each)")


if __name__ == "__main__":
    main()
