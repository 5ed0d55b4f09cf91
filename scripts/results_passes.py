#!/usr/bin/env python3
"""Issue 39, point 7: the default candle at 1080p counted per pass, before and after dual contouring
moved to compute, in one run on llvmpipe: every pass's shader invocations by stage and its GPU time
(stats.json's pipeline statistics), and the frame projected onto an H200 and an RTX 4090 by the
cost model of docs/device-bench.md (scripts/cost_model.py, each path calibrated on its own 160x90
capture). `field.extraction=geometry` is the path before (geometry shaders with transform feedback);
the VPLs' receivers have no switch (their fragment-shader path is the tests' second implementation,
VplReceivers.*), so both columns have them in compute.

  results_passes.py run DIR [--quick]     captures into DIR (TALLOW: the binary); --quick: 480x270
  results_passes.py report DIR MD         appends the section to MD
  results_passes.py splice DIR MD         replaces the section in MD (or adds it before the GPU section)

Called by scripts/results.sh (run, report).
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cost_model  # noqa: E402
import results_sections  # noqa: E402

HEADING = "## The default candle counted per pass, and projected onto GPUs (issue 39, points 6 and 7)"
PATHS = ("geometry", "compute")  # before, after
DEVICES = ("h200", "rtx4090")
SKIP = 2  # steady frames: cost_model.py's default


def capture_args(out, size, frames, path):
    return ["capture", "--preset", "candle", "--size", size, "--frames", str(frames), "--fps", "8", "--time", "10",
            "--set", "field.extraction=" + path, "--out", out]


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    tallow = os.environ.get("TALLOW", "build/tallow")
    big = "480x270" if quick else "1920x1080"
    with open(os.path.join(work, "size.txt"), "w") as f:
        f.write(big + "\n")
    for path in PATHS:
        for name, size, frames in (("calibration", "160x90", 5), ("frame", big, 4)):
            out = os.path.join(work, "%s_%s" % (name, path))
            results_sections.run_once([tallow] + capture_args(out, size, frames, path),
                                      os.path.join(out, "stats.json"), quiet=True)


def calibration(work, path):
    cal_data = cost_model.load(os.path.join(work, "calibration_%s" % path, "stats.json"), SKIP)
    cores = ((cal_data["stats"].get("provenance") or {}).get("cpu") or {}).get("hardware_threads") or os.cpu_count()
    return cost_model.calibrate(cal_data, cores, cost_model.default_ghz())


def models(work):
    """Per path: its calibration, its frame's counts and times, its projections. The passes the two
    paths share are costed by one calibration (the compute run's), so that the difference between
    the projections is the extraction's alone, not the two calibrations' noise; field.extract by its
    own path's."""
    cals = {p: calibration(work, p) for p in PATHS}
    out = {}
    for p in PATHS:
        cal = dict(cals["compute"])
        cal["c"] = dict(cals["compute"]["c"])
        if "field.extract" in cals[p]["c"]:
            cal["c"]["field.extract"] = cals[p]["c"]["field.extract"]
        cal["warnings"] = cals[p]["warnings"] if p == "compute" else [
            w for w in cals[p]["warnings"] if w.startswith("field.extract")]
        frame = cost_model.load(os.path.join(work, "frame_%s" % p, "stats.json"), SKIP)
        out[p] = (cal, frame, {d: cost_model.project(cal, frame, d) for d in DEVICES})
    return out



def num(x, d=1):
    return "—" if x is None else "{:,.{}f}".format(x, d)


def section(work):
    with open(os.path.join(work, "size.txt")) as f:
        size = f.read().strip()
    modelled = models(work)
    frames = {p: modelled[p][1] for p in PATHS}
    gpu = frames["compute"]["stats"].get("gl", {})
    lines = []
    add = lines.append
    add(HEADING)
    add("")
    add(results_sections.generated_line("results_passes.py", "`tallow capture`", [frames[p]["stats"] for p in PATHS]))
    add("")
    add("The default candle (t = 10 s, 8 fps) at %s, frames after the first %d of 4, by dual contouring in" % (size, SKIP))
    add("geometry shaders (`field.extraction=geometry`, the path before) and in compute (the default), on")
    add("`%s`, 2 cores. Invocations are the driver's pipeline statistics per pass (vertex + geometry +" % gpu.get("GL_RENDERER", "?"))
    add("fragment = raster, compute); times are llvmpipe's GPU timestamps (medians). The projections are the")
    add("cost model of docs/device-bench.md (*Cost model*: a pass's cost per invocation, calibrated on a 160x90")
    add("capture, carried onto the GPU's lanes, Hopper's raster stages on its 4 graphics-capable SMs; the passes")
    add("both paths share costed by the compute run's calibration, `field.extract` by its own path's, so that")
    add("the projections differ by the extraction alone): **a model, not a measurement**, good to about a")
    add("factor of 2 on this shared machine. The llvmpipe times of the passes both paths share differ by")
    add("the machine's load between the two captures. The VPLs' light on the receivers has no switch (its")
    add("fragment-shader path is the tests' second implementation, `VplReceivers.*`): both columns have it in")
    add("compute, in the pass `vpl.receivers`.")
    add("")
    add("| pass | raster inv. before | compute inv. before | llvmpipe ms before | raster inv. after | compute inv. after | llvmpipe ms after | H200 ms before | H200 ms after |")
    add("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    names = sorted(set(frames["geometry"]["counts"]) | set(frames["compute"]["counts"]))
    h200 = {p: {row["pass"]: row["ms"] for row in modelled[p][2]["h200"]["passes"]} for p in PATHS}
    for name in names:
        cells = []
        for p in PATHS:
            n = frames[p]["counts"].get(name)
            k = cost_model.kinds(n) if n else {"raster": None, "compute": None}
            cells += [num(k["raster"], 0), num(k["compute"], 0), num(frames[p]["ms"].get(name))]
        add("| %s | %s | %s | %s |" % (name, " | ".join(cells), num(h200["geometry"].get(name), 2),
                                        num(h200["compute"].get(name), 2)))
    add("")
    for d in DEVICES:
        before, after = modelled["geometry"][2][d], modelled["compute"][2][d]
        c = after["device_constants"]
        bounds = "" if c["raster_lanes"] == c["compute_lanes"] else (
            " (after: %s to %s ms with the mixed passes' cost all on compute or all on raster)"
            % (num(after["total_all_compute_ms"], 2), num(after["total_all_raster_ms"], 2)))
        add("- %s, the frame projected: %s ms before, %s ms after%s." % (
            before["device_name"], num(before["total_ms"], 2), num(after["total_ms"], 2), bounds))
    top = sorted(modelled["compute"][2]["h200"]["passes"], key=lambda r: -(r["ms"] or 0.0))[:3]
    add("- The most expensive passes on the H200 after: %s." % ", ".join(
        "`%s` %s ms" % (r["pass"], num(r["ms"], 2)) for r in top))
    for p in PATHS:
        for w in modelled[p][0]["warnings"]:
            add("- Model warning (%s): %s." % (p, w))
    add("")
    add(results_sections.rerun("results_passes.py"))
    add("")
    return lines


if __name__ == "__main__":
    results_sections.main(sys.argv[1:], __doc__, run, section, HEADING)
