#!/usr/bin/env python3
"""Issue 39, point 1: the docs/RESULTS.md section on dual contouring's two extraction paths.

  results_extraction.py EXTRACTION.json MD          appends the section to MD
  results_extraction.py splice EXTRACTION.json MD   replaces it in MD (or adds it before the GPU section)

EXTRACTION.json is what `tallow probe extraction` writes (scripts/results.sh runs it): every row
times both paths of passes 2 and 4 (`paths`: compute shaders, or geometry shaders with transform
feedback) on the same lattice. Every number in the section comes from it, and so does the verdict
(which path measured faster here, against the default `field.extraction`).
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402

SOFTWARE = ("llvmpipe", "softpipe", "swrast", "lavapipe")
HEADING = "## Dual contouring in compute or in geometry shaders (issue 39, point 1)"


def fmt(x, d=2):
    return "—" if x is None else "%.*f" % (d, x)


def geomean(values):
    values = [v for v in values if v is not None and v > 0]
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else None


def section(r):
    lines = []
    add = lines.append
    gpu = r["gpu"]
    add(HEADING)
    add("")
    add("`field.extraction`: passes 2 (a vertex per surface patch) and 4 (the triangles) of the GPU dual")
    add("contouring run either in geometry shaders captured by transform feedback (`geometry`, the radiosity-maps")
    add("paper's §4 path) or in compute shaders that reserve their records' places with atomics and are drawn")
    add("by an indirect draw (`compute`; the vertex pass also writes the index map, so pass 3 goes). Both run")
    add("the same per-cell source (`shaders/dual_contouring/cell_vertices.glsl`, `cell_quads.glsl`) and make")
    add("the same vertices and triangles (`DualContouringPaths.*` compares them bit for bit, and the pictures).")
    add("Each row extracts the same lattice with both; times are medians of %d GL timestamp spans around" % r["repeats"])
    add("`extract()` after one warm-up, and `wall` is `extract()` + `glFinish()` on the CPU clock.")
    add("")
    add("Device: `%s` (%s), OpenGL context `%s`." % (gpu["GL_RENDERER"], gpu["GL_VERSION"], gpu["backend"]))
    software = any(s in gpu["GL_RENDERER"].lower() for s in SOFTWARE)
    if software:
        add("**A software rasteriser: the times compare the two paths on this CPU only.** On a GPU with few")
        add("raster units the geometry-shader path runs on those alone (docs/device-bench.md, *Counted per pass*).")
    add("")
    ratios = []
    agree = True
    for field in r["fields"]:
        add("### %s (t = %g s)" % (field["field"], field["time_s"]))
        add("")
        add("| res | compute [ms] | geometry [ms] | geometry / compute | compute wall [ms] | geometry wall [ms] | triangles compute / geometry |")
        add("|---:|---:|---:|---:|---:|---:|---:|")
        for row in field["rows"]:
            c, g = row["paths"]["compute"], row["paths"]["geometry"]
            ratio = g["gpu_extract_ms"] / c["gpu_extract_ms"] if c["gpu_extract_ms"] > 0 else None
            ratios.append(ratio)
            agree = agree and c["gpu_triangles"] == g["gpu_triangles"] and c["gpu_vertices"] == g["gpu_vertices"]
            add("| %d³ | %s | %s | %s | %s | %s | %d / %d |" % (
                row["res"], fmt(c["gpu_extract_ms"]), fmt(g["gpu_extract_ms"]), fmt(ratio),
                fmt(c["gpu_extract_wall_ms"]), fmt(g["gpu_extract_wall_ms"]), c["gpu_triangles"], g["gpu_triangles"]))
        add("")
    add("### Verdict")
    add("")
    m = geomean(ratios)
    faster = "compute" if m is not None and m > 1.0 else "geometry"
    add("- The geometry-shader path took %s× the compute path's time (geometric mean over %d cases): `%s` measured"
        % (fmt(m), len(ratios), faster))
    add("  faster on this device.")
    add("- Triangle and vertex counts of the two paths %s in every case." % ("agree" if agree else "**differ**"))
    default = r["fields"][0]["rows"][0].get("extraction", "?")
    add("- Default (`field.extraction`, `geometry::kDefaultExtraction`): `%s`%s." % (
        default, "" if default == faster else " — **not the path measured faster here**"))
    add("")
    add("Rerun: `tallow probe extraction --fields %s --res %s --repeats %d --out extraction.json`, then"
        % (",".join(f["field"] for f in r["fields"]), ",".join(str(row["res"]) for row in r["fields"][0]["rows"]),
           r["repeats"]))
    add("`python3 scripts/results_extraction.py splice extraction.json docs/RESULTS.md`.")
    add("")
    return lines


def main(argv):
    splice = len(argv) == 3 and argv[0] == "splice"
    if splice:
        argv = argv[1:]
    if len(argv) != 2:
        sys.exit(__doc__)
    with open(argv[0]) as f:
        r = json.load(f)
    lines = section(r)
    if splice:
        results_sections.splice(argv[1], lines[0], lines)
    else:
        results_sections.append(argv[1], lines)


if __name__ == "__main__":
    main(sys.argv[1:])
